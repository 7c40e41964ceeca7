"""Checks that `cnclab tables NAME --format csv` and `--format json` carry
numbers only, reading them with Python's own csv and json
modules:

- json: a document {"name", "profile", "tables": [{"title", "columns",
  "rows", ...}], "notes"}; each column {"name", "header", "label"}; every
  row has exactly the column names as keys; a label column's values are
  strings (or null), every other column's are numbers or null.
- csv: the same tables in the same order ('# title' comment, header, rows,
  blank line); each header equals the json table's column names; every
  column that is not a declared label column (json "label": true) parses
  as a float in every row, or is empty (missing); and each number equals the
  json's (two renderings of the same cells).
- column names are machine names: lower-case ASCII letters, digits, '_' and
  '.', units as suffixes (_um, _mm, _deg, _s, _percent).

Usage: python3 machine_tables.py TABLE.csv TABLE.json   (exit 1 on a failure)
or import check_machine_tables(csv_text, json_text) -> list of failures.
"""
import csv
import io
import json
import math
import re
import sys

NAME = re.compile(r"^[a-z0-9_.]+$")


def csv_tables(text):
    """Tables of a CSV document: '# title' comment, then rows until a blank
    line or the next comment."""
    tables, title, lines = [], None, []

    def flush():
        if lines:
            tables.append((title, list(csv.reader(io.StringIO("".join(lines))))))

    for line in text.splitlines(keepends=True):
        if line.startswith("# ") and not lines:
            title = line[2:].strip()
        elif line.startswith("#") or not line.strip():
            flush()
            lines = []
        else:
            lines.append(line)
    flush()
    return tables


def is_number(v):
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def check_machine_tables(csv_text, json_text):
    failures = []

    def check(ok, message):
        if not ok:
            failures.append(message)

    doc = json.loads(json_text)
    tables = doc.get("tables")
    check(isinstance(tables, list) and len(tables) > 0, "json: a non-empty 'tables' list")
    if not isinstance(tables, list):
        return failures
    from_csv = csv_tables(csv_text)
    check(len(from_csv) == len(tables),
          f"csv has {len(from_csv)} tables, json {len(tables)}: "
          f"{[t for t, _ in from_csv]} vs {[t.get('title') for t in tables]}")
    numeric_cells = 0
    for i, table in enumerate(tables):
        title = table.get("title", f"table {i}")
        columns = table.get("columns", [])
        names = [c["name"] for c in columns]
        labels = {c["name"] for c in columns if c.get("label")}
        check(len(set(names)) == len(names), f"{title}: column names unique {names}")
        for n in names:
            check(NAME.match(n) is not None, f"{title}: column name {n!r} is not a machine name")
        check(len(labels) < len(names), f"{title}: some number column besides labels {names}")
        for r, row in enumerate(table.get("rows", [])):
            check(list(row.keys()) == names, f"{title} row {r}: keys {list(row)} != {names}")
            for n, v in row.items():
                if n in labels:
                    check(v is None or isinstance(v, str), f"{title} row {r} {n}: label {v!r}")
                else:
                    check(v is None or (is_number(v) and math.isfinite(v)),
                          f"{title} row {r} {n}: not a number or null: {v!r}")
        if i >= len(from_csv):
            continue
        csv_title, rows = from_csv[i]
        check(csv_title == title, f"csv table {i} titled {csv_title!r}, json {title!r}")
        check(rows and rows[0] == names, f"{title}: csv header {rows[0] if rows else []} != {names}")
        check(len(rows) - 1 == len(table.get("rows", [])),
              f"{title}: {len(rows) - 1} csv rows, {len(table.get('rows', []))} json rows")
        for r, cells in enumerate(rows[1:]):
            check(len(cells) == len(names), f"{title} csv row {r}: {len(cells)} cells")
            jrow = table["rows"][r] if r < len(table.get("rows", [])) else {}
            for n, cell in zip(names, cells):
                if n in labels:
                    continue
                if cell == "":
                    check(jrow.get(n) is None, f"{title} row {r} {n}: empty in csv, json {jrow.get(n)}")
                    continue
                try:
                    value = float(cell)
                except ValueError:
                    check(False, f"{title} csv row {r} column {n}: {cell!r} is not a number")
                    continue
                numeric_cells += 1
                check(jrow.get(n) is not None and value == float(jrow[n]),
                      f"{title} row {r} {n}: csv {cell} != json {jrow.get(n)}")
    check(numeric_cells > 0, "csv: some numbers at all")
    return failures


def main():
    with open(sys.argv[1], encoding="utf-8") as f:
        csv_text = f.read()
    with open(sys.argv[2], encoding="utf-8") as f:
        json_text = f.read()
    failures = check_machine_tables(csv_text, json_text)
    for f in failures:
        print("FAIL:", f)
    if failures:
        return 1
    print(f"machine tables: {len(csv_tables(csv_text))} tables, csv and json consistent")
    return 0


if __name__ == "__main__":
    sys.exit(main())
