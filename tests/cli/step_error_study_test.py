"""End-to-end test of seed 000's study in its quick profile: `cnclab
reproduce --quick experiments/step_error` into a temporary folder, then
`cnclab tables step-error` in every format, then the figures and the
study's report (figures embedded, opened in Chromium), then
`--check` against the declared targets (passing, and failing for a copy of
the manifest with a target beyond the measured value).

Checks structural facts against the paper and against independent
computations (Python's csv module reads the CSV; h5py reads the results and
the dataset): table shapes, the test sample counts of Tables 4 and 5
(19,800 / 19,602 / 18,810 / 17,820 / 16,830), monotone bin edges, bin counts
summing to the test sizes, ratios summing to 100 %, Table 8's rows, and that
the quick network beats the mean-of-training-targets predictor by a wide
margin.

Usage: /usr/bin/python3 step_error_study_test.py CNCLAB SOURCE_DIR
"""
import base64
import csv
import glob
import io
import os
import re
import shutil
import subprocess
import sys
import tempfile

import h5py
import numpy as np
import yaml
from PIL import Image

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "report"))
from machine_tables import check_machine_tables, csv_tables  # noqa: E402

import chromium_page  # noqa: E402  (beside this file)

PAPER_TEST_SIZES = [19800, 19602, 18810, 17820, 16830]
# "Wide margin": the network's test MSE below this share of the MSE of
# predicting the mean of the training targets (R^2 > 0.9 on average).
TRIVIAL_MSE_RATIO = 0.1

failures = []


def check(ok, message):
    if not ok:
        failures.append(message)
        print("FAIL:", message)


def run(args, cwd):
    p = subprocess.run(args, cwd=cwd, capture_output=True, text=True)
    if p.returncode != 0:
        print(p.stdout[-4000:])
        print(p.stderr[-4000:])
        raise SystemExit(f"{' '.join(args)}: exit {p.returncode}")
    return p.stdout


def edges_of(labels):
    """Numbers in bin labels '< 0.1', '0.1–0.2', '> 20 %', '≥ 0.8'."""
    numbers = []
    for label in labels:
        for n in re.findall(r"[0-9.]+", label):
            v = float(n)
            if not numbers or numbers[-1] != v:
                numbers.append(v)
    return numbers


def main():
    cnclab, source = sys.argv[1], os.path.abspath(sys.argv[2])
    tmp = tempfile.mkdtemp(prefix=f"cnclab_step_error_study_{os.getpid()}_")
    try:
        results = os.path.join(tmp, "results")
        out = run([cnclab, "reproduce", "--quick", "--quiet", "--check", "experiments/step_error",
                   "--out", results, "--data-dir", os.path.join(tmp, "datasets")], source)
        check("step_error_table8_timing" in out, "reproduce ran the Table 8 timing job")
        check(re.search(r"^targets: [1-9][0-9]* PASS, 0 FAIL", out, re.M) is not None,
              "reproduce --check: the quick profile's declared targets pass")
        tables_results = os.path.join(results, "quick")
        check(os.path.isdir(tables_results), "reproduce --out ROOT --quick wrote ROOT/quick")
        # One rule: --results names the root, --profile its subfolder.
        common = ["tables", "step-error", "--results", results, "--profile", "quick"]
        texts = {f: run([cnclab] + common + ["--format", f], source)
                 for f in ("text", "md", "csv", "latex", "json")}
        for f, text in texts.items():
            check("Table 8" in text and "Table 7" in text, f"{f}: all tables printed")
            check("not printed" not in text, f"{f}: no table missing")
        check_sources(texts["text"], source)
        check(texts["latex"].count("\\begin{tabular}") == texts["latex"].count("\\end{tabular}")
              and texts["latex"].count("\\begin{tabular}") >= 10, "latex: balanced tabulars")
        for failure in check_machine_tables(texts["csv"], texts["json"]):
            check(False, f"machine-readable tables: {failure}")
        check_csv(csv_tables(texts["csv"]))
        check_table2_choice(csv_tables(texts["csv"]), texts["text"])
        check_seed_spread(csv_tables(texts["csv"]), tables_results)
        check_table2_over_seeds(csv_tables(texts["csv"]), tables_results)
        check_trivial_predictor(cnclab, tables_results, source)
        check_targets(cnclab, source, common, tmp)
        run(["bash", os.path.join(source, "scripts/figures/run"), tables_results], source)
        pngs = glob.glob(os.path.join(tables_results, "figures", "step_error", "*.png"))
        names = {os.path.basename(p).split("_")[0] for p in pngs}
        check({"fig5", "fig6", "fig7", "fig8"} <= names, f"figures written: {sorted(pngs)}")
        check_report(cnclab, source, results, pngs, tmp)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    if failures:
        print(f"{len(failures)} check(s) failed")
        return 1
    print("step-error study: all checks passed")
    return 0


def check_report(cnclab, source, results, pngs, tmp):
    """`cnclab report step-error`: the study's figures embedded byte for byte
    (base64 decoded here) at 1.5x the size they were drawn for (PIL reads
    the PNG's pixels and dpi), and the page passes the file and browser
    checks of chromium_page.py (no console error, no request leaving it)."""
    html = os.path.join(tmp, "report-step-error.html")
    run([cnclab, "report", "step-error", "--results", results, "--profile", "quick",
         "-o", html], source)
    for problem in chromium_page.file_problems(html):
        check(False, f"report: {problem}")
    text = open(html, encoding="utf-8").read()
    images = {}
    for attrs in re.findall(r"<img ([^>]*)>", text):
        data = re.search(r'src="data:image/png;base64,([^"]*)"', attrs)
        images[base64.b64decode(data[1])] = attrs
    for png in pngs:
        with open(png, "rb") as f:
            attrs = images.get(f.read())
        check(attrs is not None, f"report: {os.path.basename(png)} embedded as it is")
        if attrs:
            with Image.open(png) as im:
                width = round(im.size[0] * 144 / im.info["dpi"][0])
            check(f'width="{width}"' in attrs, f"report: {png} shown {width} px wide: {attrs[-60:]}")
    chromium_page.require_chromium()
    dom, console, leaving = chromium_page.open_in_chromium(
        "file://" + html, os.path.join(tmp, "chromium-profile"), tmp)
    check(dom.count("<img ") == len(pngs), f"report: {len(pngs)} figures in the DOM")
    check("Table 2" in dom and "PASS" in dom, "report: tables and targets in the DOM")
    check(not console and not leaving, f"report: no console message {console[:3]}, "
                                       f"no request leaving {leaving[:3]}")


def check_sources(text, source):
    """Every table ends with the files it read: the paper's numbers first
    (except the normaliser table, which has none), then result files that
    exist."""
    lines = [l[len("sources: "):] for l in text.splitlines() if l.startswith("sources: ")]
    # Tables 2, 2 over seeds, 3, surface-1 text, 4, 6, 5, 7, normaliser, seed spread, 8.
    check(len(lines) == 11, f"one sources line per table: {len(lines)}")
    for line in lines:
        files = line.split(", ")
        for f in files:
            check(os.path.isfile(os.path.join(source, f)), f"sources: {f} exists")
        check(sum(f.endswith("seed000_step_error.yaml") for f in files) <= 1, f"reference once: {line}")
        check(any(f.endswith(".h5") for f in files), f"sources name result files: {line}")
    check(sum(l.startswith("results/reference/seed000_step_error.yaml") for l in lines) == 10,
          "the paper's numbers are named where they are used")


def find(tables, prefix):
    found = [rows for title, rows in tables if title.startswith(prefix)]
    check(len(found) == 1, f"one table titled '{prefix}...' (found {len(found)})")
    return found[0] if found else [[]]


def check_csv(tables):
    for title, rows in tables:
        width = len(rows[0])
        check(all(len(r) == width for r in rows), f"{title}: every row as wide as the header")

    t2 = find(tables, "Seed 000 Table 2:")
    check(t2[0][2:] == [f"p_0.{k}" for k in range(3, 10)], f"Table 2 header {t2[0]}")
    check((len(t2) - 2) % 4 == 0 and len(t2) >= 6,
          "Table 2: paper row + 4 rows per variant (validation MSE, test MSE deterministic and "
          "MC dropout, training loss)")

    # Tables 4 and 5: the test sizes, ours equal to the paper's.
    for prefix in ("Seed 000 Table 4", "Seed 000 Table 5"):
        rows = find(tables, prefix)
        check(rows[0][2:] == [f"fine_tune_{p}_percent" for p in (0, 1, 5, 10, 15)],
              f"{prefix} header {rows[0]}")
        test_rows = test_sample_rows(rows)
        check(len(test_rows) >= 2, f"{prefix}: paper and our test-size rows")
        for r in test_rows:
            check([int(v) for v in r[2:]] == PAPER_TEST_SIZES, f"{prefix}: test sizes {r}")

    # Bin tables: monotone edges; counts sum to the test size; ratios to 100.
    surface1 = find(tables, "Surface 1 in the text")
    check(surface1[1][0] == "test_samples", f"surface 1: first row {surface1[1]}")
    s1_sizes = dict(zip(surface1[0][1:], surface1[1][1:]))  # header -> test samples
    check(s1_sizes.get("paper") == "5940", "surface 1: paper test set 5,940")
    for prefix, sizes in (("Seed 000 Table 3", s1_sizes), ("Seed 000 Table 6", None),
                          ("Seed 000 Table 7", None)):
        for part in ("(a)", "(b)"):
            rows = find(tables, f"{prefix}" + (" (a)" if part == "(a)" else " (b)"))
            edges = edges_of(rows[0][2:])
            check(all(a < b for a, b in zip(edges, edges[1:])), f"{prefix} {part}: edges {edges}")
            for i in range(1, len(rows), 2):
                source, count, ratio = rows[i][0], rows[i], rows[i + 1]
                check(count[1] == "count" and ratio[1] == "percent", f"{prefix}: row pairs")
                if source == "paper":
                    continue
                total = sum(int(v) for v in count[2:])
                expected = int(sizes[source]) if sizes else 16830
                check(total == expected, f"{prefix} {part} {source}: {total} != {expected}")
                check(abs(sum(float(v) for v in ratio[2:]) - 100.0) < 0.01 * len(ratio),
                      f"{prefix} {part} {source}: ratios sum to 100")
    for source, n in s1_sizes.items():
        if source != "paper":
            check(n == "5940", f"surface 1 {source}: 30 % of 19,800 = 5,940 test samples, got {n}")

    t8 = find(tables, "Seed 000 Table 8")
    labels = [r[0] for r in t8[1:]]
    for needed in ("geometric_s", "exact_s", "network_total_s"):
        check(needed in labels, f"Table 8 row {needed}")
    for r in t8[1:]:
        if r[0].endswith("_s"):
            check(float(r[1]) > 0 and float(r[3]) > 0, f"Table 8 {r[0]}: positive times")
    norm = find(tables, "Beyond the paper: z-score normaliser")
    check(len(norm) == 5, "normaliser table: keep/refit x surfaces 2, 3")


def check_table2_choice(tables, text):
    """Table 2 chooses p on validation: each variant's note names the p of
    the lowest value of its validation row (not of its test row), and the
    test choice beside it is the lowest of the test row."""
    t2 = find(tables, "Seed 000 Table 2:")
    ps = [h[len("p_"):] for h in t2[0][2:]]
    rows = {(r[0], r[1]): r[2:] for r in t2[1:]}
    for source in sorted({r[0] for r in t2[1:] if r[0] != "paper"}):
        lowest = {}
        for quantity in ("validation_mse", "test_mse"):
            values = [float(v) if v not in ("", "-") else float("inf")
                      for v in rows.get((source, quantity), [])]
            check(len(values) == len(ps), f"Table 2 {source}: a {quantity} row")
            if values and min(values) < float("inf"):
                lowest[quantity] = ps[values.index(min(values))]
        label = source.replace("ours_", "ours, ")
        if "validation_mse" in lowest:
            want = f"{label}: chosen on validation, p = {lowest['validation_mse']} "
            check(want in text, f"Table 2 note '{want}'")
        if "test_mse" in lowest:
            check(f"shown beside, not used): p = {lowest['test_mse']}" in text,
                  f"Table 2 {source}: the test choice p = {lowest['test_mse']} beside it")


def trial_figures(results, sweep, group_key):
    """Per value of `group_key` (a function of the resolved config), the mean
    |e| and the share of |e| < 0.5 µm of each trial of the seed sweep
    `sweep`, from the trial files' stored predictions and targets."""
    groups = {}
    for path in glob.glob(os.path.join(results, sweep, "sweep-*", "trials", "*.h5")):
        with h5py.File(path, "r") as f:
            text = f["config"][()]
            config = yaml.safe_load(text.decode() if isinstance(text, bytes) else text)
            err = np.abs(np.ravel(f["test/predictions"][:]) - np.ravel(f["test/targets"][:]))
        groups.setdefault(group_key(config), []).append(
            {"mean_abs_um": float(np.mean(err)),
             "share_abs_below_0.5um_percent": 100.0 * float(np.mean(err < 0.5))})
    return groups


def check_seed_spread(tables, results):
    """The seed-spread table: its mean and std columns
    against numpy's mean and std (ddof=1) of the figures computed here from
    each trial's stored predictions, grouped by the trial's own config; the
    seed count against the quick profile's 2 repeats."""
    rows = find(tables, "Seed-to-seed spread")
    header = rows[0]
    check(header == ["row", "quantity", "paper", "one_run", "seeds_mean", "seeds_std", "seeds"],
          f"seed spread header {header}")
    table = {(r[0], r[1]): dict(zip(header, r)) for r in rows[1:]}
    expected = {}
    keep = lambda c: float(c["model"]["dropout"]["keep_probability"])
    table2 = trial_figures(results, "step_error_tuned_seeds_table2", keep)
    check(sorted(table2) == [0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0],
          f"Table 2 sweep points {sorted(table2)}")
    s1 = trial_figures(results, "step_error_tuned_seeds_surface1", keep)
    check(sorted(s1) == [1.0], f"surface-1 sweep points {sorted(s1)}")
    expected["surface1"] = s1.get(1.0, [])
    for surface in (2, 3):
        g = trial_figures(results, f"step_error_tuned_seeds_surface{surface}_ft15",
                          lambda c: c["init_from"]["normaliser"])
        for name, runs in g.items():
            expected[f"surface{surface}_ft15_{name}"] = runs
    check(len(expected) == 5, f"seed groups {sorted(expected)}")
    for row, runs in expected.items():
        check(len(runs) == 2, f"{row}: 2 seeds in the quick profile, {len(runs)} trial files")
        for quantity in ("mean_abs_um", "share_abs_below_0.5um_percent"):
            if (row, quantity) not in table:
                check(quantity != "mean_abs_um", f"seed spread row {row} {quantity}")
                continue
            values = np.array([r[quantity] for r in runs])
            got = table[(row, quantity)]
            for column, want in (("seeds_mean", values.mean()), ("seeds_std", values.std(ddof=1))):
                check(abs(float(got[column]) - want) <= 1e-9 * max(1.0, abs(want)),
                      f"seed spread {row} {quantity} {column}: {got[column]} != {want}")
            check(got["seeds"] == str(len(runs)), f"seed spread {row}: seeds {got['seeds']}")


def check_table2_over_seeds(tables, results):
    """Table 2 over seeds under both dropout evaluations: each trial's z-score
    test MSE computed here from its stored predictions (/test/predictions:
    deterministic; /other_inference/test_predictions: MC dropout), targets
    and target scaling, and its validation MSE as stored per evaluation
    (/metrics and /other_inference attributes validation.normalised_mse),
    grouped by the trial's keep probability, against the table's mean and
    std columns; no dropout (1.0) has one evaluation."""
    rows = find(tables, "Seed 000 Table 2 over seeds")
    header = rows[0]
    columns = [f"{split}_mse_{name}" for name in ("deterministic", "mc")
               for split in ("validation", "test")]
    check(header == ["p", "paper_mse"] + [f"{c}_{s}" for c in columns for s in ("mean", "std")]
          + ["complete", "planned"], f"Table 2 over seeds header {header}")
    groups = {}
    pattern = os.path.join(results, "step_error_tuned_seeds_table2", "sweep-*", "trials", "*.h5")
    for path in glob.glob(pattern):
        with h5py.File(path, "r") as f:
            text = f["config"][()]
            config = yaml.safe_load(text.decode() if isinstance(text, bytes) else text)
            mean = f["model/target_scaling/mean"][()]
            std = f["model/target_scaling/std"][()]
            target = (f["test/targets"][()] - mean) / std
            validation = [float(f["metrics"].attrs["validation.normalised_mse"])]
            mse = [float(np.mean(((f["test/predictions"][()] - mean) / std - target) ** 2))]
            if "other_inference" in f:
                mc = (f["other_inference/test_predictions"][()] - mean) / std
                mse.append(float(np.mean((mc - target) ** 2)))
                validation.append(float(f["other_inference"].attrs["validation.normalised_mse"]))
        p = float(config["model"]["dropout"]["keep_probability"])
        check(len(mse) == (1 if p == 1.0 else 2), f"{path}: MC evaluation stored iff dropout")
        groups.setdefault(p, []).append((validation[0], mse[0], validation[-1], mse[-1]))
    table = {float(r[0]): dict(zip(header, r)) for r in rows[1:]}
    check(sorted(table) == sorted(groups), f"Table 2 over seeds rows {sorted(table)}")
    for p, runs in groups.items():
        values = np.array(runs)
        for k, column in enumerate(columns):
            for stat, want in (("mean", values[:, k].mean()), ("std", values[:, k].std(ddof=1))):
                got = table.get(p, {}).get(f"{column}_{stat}", "nan")
                check(abs(float(got) - want) <= 1e-9 * max(1.0, abs(want)),
                      f"Table 2 over seeds p = {p} {column}_{stat}: {got} != {want}")


def run_code(args, cwd):
    p = subprocess.run(args, cwd=cwd, capture_output=True, text=True)
    return p.returncode, p.stdout, p.stderr


def check_targets(cnclab, source, common, tmp):
    """`tables step-error --check`: the declared targets pass on the quick
    results (exit 0); a copy of the manifest with a target beyond the
    measured value fails (exit 1); an unknown name is a config error naming
    the file and key (exit 2)."""
    code, out, err = run_code([cnclab] + common + ["--check"], source)
    check(code == 0, f"tables --check on the quick results: exit {code}\n{out[-2000:]}{err}")
    check("tuned.surface1.test_samples" in out and "PASS" in out, "--check prints PASS rows")
    base = os.path.join(source, "configs", "studies")
    with open(os.path.join(base, "step_error_tables.yaml")) as f:
        manifest = yaml.safe_load(f)

    def absolute(node):  # the copy lives elsewhere: experiment paths made absolute
        if isinstance(node, dict):
            return {k: absolute(v) for k, v in node.items()}
        if isinstance(node, str) and node.endswith(".yaml"):
            return os.path.normpath(os.path.join(base, node))
        return node

    manifest = absolute(manifest)
    configs = os.path.join(tmp, "configs")
    os.makedirs(os.path.join(configs, "studies"), exist_ok=True)
    copy = os.path.join(configs, "studies", "step_error_tables.yaml")

    def check_with(targets):
        with open(copy, "w") as f:
            yaml.safe_dump(dict(manifest, targets=targets), f)
        return run_code([cnclab] + common + ["--check", "--configs", configs], source)

    # 5,940 test samples measured: one more is beyond it.
    code, out, err = check_with([{"name": "tuned.surface1.test_samples", "op": ">=",
                                  "value": 5941, "profiles": {"quick": 5941}, "source": "test"}])
    check(code == 1, f"a target beyond the measured value: exit {code} (want 1)")
    check(re.search(r"tuned\.surface1\.test_samples.*5940.*FAIL", out) is not None,
          f"the failing target is shown with its measured value\n{out[-1500:]}")
    code, out, err = check_with([{"name": "tuned.surface1.test_sample", "op": "==",
                                  "value": 1, "source": "test"}])
    check(code == 2, f"an unknown target name: exit {code} (want 2)")
    check(copy in err and "targets[0].name = tuned.surface1.test_sample" in err,
          f"the config error names the manifest and key: {err}")


def test_sample_rows(rows):
    """csv carries the quantity on every row, continuation rows included."""
    return [r for r in rows[1:] if r[0] == "test_samples"]


def final_networks(source):
    """Experiment files of the last variant's surface-1 and 15 % networks
    (the tuned variant when present: the one meant to meet the targets; the
    paper variant's quick runs are a few epochs of per-sample SGD)."""
    base = os.path.join(source, "configs", "studies")
    with open(os.path.join(base, "step_error_tables.yaml")) as f:
        variant = list(yaml.safe_load(f)["variants"].values())[-1]
    return [os.path.normpath(os.path.join(base, rel))
            for rel in (variant["surface1"], variant["surface2"][15], variant["surface3"][15])]


def own_result(cnclab, source, results, experiment):
    """The result of the experiment file itself: the one whose stored config is
    the file's resolved config (`cnclab validate --full`). The seed sweeps
    store their trials of the same experiment (other seeds, other dropout)
    beside it."""
    resolved = yaml.safe_load(run([cnclab, "validate", "--full", "--profile", "quick", experiment],
                                  source))
    name = resolved["name"]
    paths = []
    for path in glob.glob(os.path.join(results, name, f"{name}-*.h5")):
        with h5py.File(path, "r") as f:
            text = f["config"][()]
        if yaml.safe_load(text.decode() if isinstance(text, bytes) else text) == resolved:
            paths.append(path)
    return name, paths


def check_trivial_predictor(cnclab, results, source):
    """The final quick networks against predicting the mean of their own
    training targets (read from the dataset file)."""
    for experiment in final_networks(source):
        name, paths = own_result(cnclab, source, results, experiment)
        check(len(paths) == 1, f"one result of {name} ({paths})")
        if len(paths) != 1:
            continue
        with h5py.File(paths[0], "r") as f:
            train = np.asarray(f["split/train"][:], dtype=np.int64)
            dataset = f["dataset"].attrs["file"]
            dataset = dataset.decode() if isinstance(dataset, bytes) else dataset
            pred, y = np.ravel(f["test/predictions"][:]), np.ravel(f["test/targets"][:])
            # README's h5py example: /metrics holds numbers only, units apart;
            # recompute the test split's mse from the stored arrays.
            metrics = {k: float(v) for k, v in f["metrics"].attrs.items()}
            units = {k: (v.decode() if isinstance(v, bytes) else v)
                     for k, v in f["metrics/units"].attrs.items()}
        check(set(units) == set(metrics), f"{name}: a unit per metric ({units})")
        expected = {"mse": "µm²", "rmse": "µm", "mae": "µm", "max_abs_error": "µm", "r2": "1",
                    "normalised_mse": "scaled²"}
        for metric, unit in units.items():
            split, _, base = metric.partition(".")
            check(split in ("train", "validation", "test") and base in expected,
                  f"{name}: metric {metric} is <split>.<metric>")
            if base in expected:
                check(unit == expected[base], f"{name}: {metric} in {unit!r}")
        if "test.mse" in metrics:
            check(abs(metrics["test.mse"] - np.mean((pred - y) ** 2))
                  <= 1e-9 * max(1.0, metrics["test.mse"]),
                  f"{name}: stored test.mse {metrics['test.mse']} against the stored predictions")
        if not os.path.isabs(dataset):
            dataset = os.path.join(source, dataset)
        with h5py.File(dataset, "r") as d:
            targets = np.ravel(d["targets"][:])
        net = np.mean((pred - y) ** 2)
        trivial = np.mean((targets[train].mean() - y) ** 2)
        print(f"{name}: network test MSE {net:.4g} µm², mean-of-training-targets {trivial:.4g} µm²")
        check(net < TRIVIAL_MSE_RATIO * trivial,
              f"{name}: network MSE {net:.4g} vs mean predictor {trivial:.4g}")


if __name__ == "__main__":
    sys.exit(main())
