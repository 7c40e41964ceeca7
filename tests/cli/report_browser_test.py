#!/usr/bin/env python3
"""`cnclab report` opened in a real browser (Debian's chromium, headless).

Makes a tiny result and a job (kind: sweep), each with an override and a
profile (both shown by `show` and in the report), and a small sweep given a
parameter importance in the layout an Optuna sweep writes (h5py), writes
one report of them, then checks the file and what Chromium does with it
from file:// with the network disabled:
  - the file: at most 5 MB, no <script>, no external reference (src/href
    to http(s) or //), one <style>, figures inline SVG or PNG data URIs;
  - Chromium's network log: no request that leaves the file;
  - Chromium's log: no console error;
  - the DOM Chromium built (--dump-dom): every table (metrics, ranking,
    importance) and every figure (training history, parallel coordinates,
    importance bars in proportion to the values written) present.
With a third argument (a folder), also leaves a 1280 px screenshot and the
printed PDF there, to look at.
Usage: report_browser_test.py CNCLAB [SHOT_DIR]
"""
import json
import os
import re
import subprocess
import sys
import tempfile

import h5py
import numpy as np

from chromium_page import file_problems, open_in_chromium, require_chromium, screenshots

CNCLAB = sys.argv[1]
SHOTS = sys.argv[2] if len(sys.argv) > 2 else None
failures = []


def check(cond, what):
    if not cond:
        failures.append(what)
        print("FAIL:", what)


def run(args, cwd):
    r = subprocess.run([CNCLAB] + args, cwd=cwd, capture_output=True, text=True)
    if r.returncode != 0:
        print(r.stdout, r.stderr)
        raise SystemExit(f"cnclab {' '.join(args)}: exit {r.returncode}")
    return r


EXPERIMENT = """name: tiny
seed: 5
dataset:
  generator: friedman1
  options: {samples: 150, inputs: 5, noise_std: 1.0}
split: {train: 0.6, validation: 0.2}
model: {type: mlp, hidden: [4], hidden_activation: tanh, output_activation: linear}
trainer: {type: sgdm, learning_rate: 0.01, momentum: 0.9, batch_size: 16, epochs: 30}
metrics: [rmse, mae]
profiles: {short: {trainer.epochs: 20}}
"""

# A job (kind: sweep) over it, run with an override and the profile: its
# result must show both, as the training result does.
SEARCH = """kind: sweep
name: tiny_search
experiment: tiny.yaml
jobs: 1
sweep:
  method: grid
  objective: {metric: validation.rmse, mode: min}
  parameters:
    trainer.momentum: [0.5, 0.9]
profiles: {short: {jobs: 1}}
"""

require_chromium()

with tempfile.TemporaryDirectory() as tmp:
    with open(os.path.join(tmp, "tiny.yaml"), "w") as f:
        f.write(EXPERIMENT)
    with open(os.path.join(tmp, "search.yaml"), "w") as f:
        f.write(SEARCH)
    common = ["--quiet", "--out", "results", "--data-dir", "data"]
    run(["run", "tiny.yaml", "trainer.learning_rate=0.02", "--profile", "short", *common], tmp)
    run(["run", "search.yaml", "description=by hand", "--profile", "short", *common], tmp)
    run(["sweep", "tiny.yaml", "trainer.learning_rate=0.005,0.01,0.05", "model.hidden=[3],[5]",
         *common], tmp)
    results = os.path.join(tmp, "results", "tiny")
    # The single run (the sweep's trials are linked beside it too): found by its override.
    listed = json.loads(run(["runs", "results/short", "--where", "learning_rate=0.02",
                             "--format", "json"], tmp).stdout)["runs"]
    check(len(listed) == 1, f"one run with learning_rate 0.02 ({len(listed)})")
    result = listed[0]["file"]
    job_dir = os.path.join(tmp, "results", "short", "tiny_search")
    job = [os.path.join(job_dir, f) for f in os.listdir(job_dir) if f.endswith(".h5")]
    check(len(job) == 1, f"one job result in {job_dir}: {job}")
    # `show` of both: the override and the profile each was made with.
    for file, override in [(result, "trainer.learning_rate=0.02"), (job[0], "description=by hand")]:
        shown = run(["show", file], tmp).stdout
        check(re.search(r"^override +" + re.escape(override) + "$", shown, re.M),
              f"show {file}: override {override}\n{shown}")
        check(re.search(r"^profile +short$", shown, re.M), f"show {file}: profile short\n{shown}")
    sweep = [os.path.join(results, d) for d in os.listdir(results) if d.startswith("sweep")][0]
    # Parameter importance as an Optuna sweep records it (fANOVA), written
    # here with h5py in that layout: fixed-length strings (cnclab reads no
    # variable-length ones), largest first.
    importance = {"trainer.learning_rate": 0.625, "model.hidden": 0.25}
    with h5py.File(os.path.join(sweep, "summary.h5"), "a") as f:
        g = f.create_group("importance")
        g.attrs["evaluator"] = np.bytes_("fanova")
        g["parameter"] = np.array(list(importance), dtype="S")
        g["value"] = np.array(list(importance.values()), dtype="f8")
    html = os.path.join(tmp, "report.html")
    run(["report", result, job[0], sweep, "-o", html], tmp)

    for problem in file_problems(html):
        check(False, f"the file: {problem}")

    profile = os.path.join(tmp, "chromium-profile")
    url = "file://" + html
    dom, console, leaving = open_in_chromium(url, profile, tmp)
    check(dom, "chromium dumped the DOM")
    check(not console, f"no console message: {console[:3]}")
    check(not leaving, f"no request leaves the file: {leaving[:5]}")
    # The checks can fail: a page with an external image and a script error.
    control = os.path.join(tmp, "control.html")
    with open(control, "w") as f:
        f.write('<!DOCTYPE html><html><body><img src="http://example.invalid/x.png">'
                '<script>console.error("boom")</script></body></html>')
    check(file_problems(control), "the control page's file is caught")
    _, c_console, c_leaving = open_in_chromium("file://" + control, profile, tmp)
    check(c_leaving and c_console, f"the control page is caught ({c_leaving}, {c_console})")

    tables = re.findall(r"<table class=\"data\">\s*<caption>([^<]*)", dom)
    check(any("metrics" in t for t in tables), f"metrics table in the DOM ({tables})")
    check(any("ranking" in t for t in tables), f"sweep ranking table in the DOM ({tables})")
    figures = re.findall(r"<svg[^>]*aria-label=\"([^\"]*)\"", dom)
    check(sum("training history" in f for f in figures) >= 2,
          f"a training history per run (the result and the best trial): {figures}")
    check(any("parallel coordinates" in f for f in figures), f"parallel coordinates: {figures}")
    check("<path d=\"M" in dom, "the figures have drawn lines")
    # Provenance of the training result and of the job: override and profile.
    definitions = dict()
    for block in re.findall(r"<dl>(.*?)</dl>", dom, re.S):
        for k, v in re.findall(r"<dt>([^<]*)</dt><dd>([^<]*)</dd>", block):
            definitions.setdefault(k, []).append(v)
    for override in ("trainer.learning_rate=0.02", "description=by hand"):
        check(override in definitions.get("override", []), f"provenance: override {override}")
    # The contents: a link to each section, and every link lands on an id of the page.
    links = re.findall(r'<nav class="contents"[^>]*>.*?</nav>', dom, re.S)
    check(links, "a contents list")
    targets = re.findall(r'href="#([^"]+)"', links[0]) if links else []
    check(len(targets) >= 3, f"the contents link the sections: {targets}")
    check(all(f'id="{t}"' in dom for t in targets), f"every contents link has a target: {targets}")
    # A run's heading names the point it is (a sweep trial keeps its base experiment's name).
    headings = re.findall(r"<h[2-6][^>]*>(Run [^<]*)</h", dom)
    check(any("[trainer.learning_rate=0.02]" in h for h in headings),
          f"the run's heading shows its override: {headings}")
    check(any("model.hidden=" in h and "trainer.learning_rate=" in h for h in headings),
          f"the best trial's heading shows its sweep point: {headings}")
    check(definitions.get("profile", []).count("short") >= 2,
          f"provenance: profile short of the result and the job ({definitions.get('profile')})")
    # The importance: one bar per parameter, longest first, and the table.
    chart = re.search(r"<svg[^>]*aria-label=\"parameter importance \(fanova\)\".*?</svg>", dom,
                      re.S)
    check(chart, f"importance bar chart: {figures}")
    if chart:
        widths = [float(w) for w in re.findall(r'class="bar"[^>]*width="([0-9.]+)"', chart[0])]
        check(len(widths) == 2 and widths[0] > widths[1] > 0
              and abs(widths[1] / widths[0] - 0.25 / 0.625) < 0.01,
              f"bars in proportion to the values: {widths}")
    table = re.search(r"<caption>parameter importance \(fanova\)</caption>.*?</table>", dom, re.S)
    rows = re.findall(r"<tr><td>([^<]*)</td><td>([^<]*)</td></tr>", table[0]) if table else []
    check([(k, float(v)) for k, v in rows] == list(importance.items()),
          f"importance table as written: {rows}")

    if SHOTS:
        for shot in screenshots(url, os.path.join(tmp, "chromium-profile"), SHOTS, "report"):
            print("wrote", shot)

if failures:
    print(f"{len(failures)} check(s) failed")
    sys.exit(1)
print("report_browser_test: all checks passed")
