#!/usr/bin/env python3
"""No file outside train/ and studies/ names a trainer.

The names are the registry's: trainer.type's enum in `cnclab schema`. Every
file under src/ but src/cnclab/train/ and src/cnclab/studies/ is searched,
in its comments and string literals (what people read: messages, schema
text, captions, units), for a name as a whole word: case-insensitive, but
exact for names of two letters ("lm"; "LM" abbreviates Levenberg-Marquardt).
Identifiers are not searched (a variable may be called lm).
Usage: trainer_names_test.py CNCLAB SOURCE_DIR
"""
import json
import pathlib
import re
import subprocess
import sys


def trainer_names(cnclab):
    schema = json.loads(subprocess.run([cnclab, "schema"], check=True, capture_output=True,
                                       text=True).stdout)
    found = set()

    def walk(node):
        if isinstance(node, dict):
            trainer = node.get("properties", {}).get("trainer", {})
            enum = trainer.get("properties", {}).get("type", {}).get("enum")
            if enum:
                found.update(enum)
            for value in node.values():
                walk(value)
        elif isinstance(node, list):
            for value in node:
                walk(value)

    walk(schema)
    return sorted(found)


# Comments and string literals of C++ (raw strings included) and of
# CMake/shell/Python ('#' comments); code between them is dropped.
CPP_TEXT = re.compile(r'//[^\n]*|/\*.*?\*/|R"([^(]*)\(.*?\)\1"|"(?:\\.|[^"\\\n])*"|'
                      r"'(?:\\.|[^'\\\n])*'", re.S)
HASH_TEXT = re.compile(r'#[^\n]*|"(?:\\.|[^"\\\n])*"')


def readable_text(path):
    text = path.read_text(errors="replace")
    pattern = CPP_TEXT if path.suffix in (".cpp", ".hpp", ".h", ".c", ".in") else HASH_TEXT
    for m in pattern.finditer(text):
        yield text.count("\n", 0, m.start()) + 1, m.group(0)


def main():
    cnclab, source = sys.argv[1], pathlib.Path(sys.argv[2])
    names = trainer_names(cnclab)
    if len(names) < 3:
        print(f"FAIL: only {names} found as trainer.type in `cnclab schema`")
        return 1
    words = [re.compile(rf"\b{re.escape(n)}\b", 0 if len(n) <= 2 else re.I) for n in names]
    allowed = [source / "src/cnclab/train", source / "src/cnclab/studies"]
    hits, inside = [], 0
    for path in sorted((source / "src").rglob("*")):
        if not path.is_file():
            continue
        mine = any(a in path.parents for a in allowed)
        for line, text in readable_text(path):
            if any(w.search(text) for w in words):
                if mine:
                    inside += 1
                else:
                    hits.append(f"{path.relative_to(source)}:{line}: {text.strip()[:120]}")
    # The search finds the names where they belong, so finding none outside means something.
    if inside == 0:
        print("FAIL: no trainer name found in train/ either (the search is broken)")
        return 1
    if hits:
        print(f"trainer names ({', '.join(names)}) outside train/ and studies/:")
        print("\n".join(hits))
        return 1
    print(f"no trainer name ({', '.join(names)}) outside train/ and studies/ "
          f"({inside} mentions inside)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
