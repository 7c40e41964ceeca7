#!/usr/bin/env python3
"""`cnclab report` opened in a real browser (Debian's chromium, headless).

Makes a tiny result and a small sweep, writes one report of both, then
checks the file and what Chromium does with it from file:// with the
network disabled:
  - the file: at most 5 MB, no <script>, no external reference (src/href
    to http(s) or //), every figure inline SVG;
  - Chromium's network log: no request that leaves the file;
  - Chromium's log: no console error;
  - the DOM Chromium built (--dump-dom): every table (metrics, ranking) and
    every figure (training history, parallel coordinates) present.
With a third argument (a folder), also leaves a 1280 px screenshot and the
printed PDF there, to look at.
Usage: report_browser_test.py CNCLAB [SHOT_DIR]
"""
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

CNCLAB = sys.argv[1]
SHOTS = sys.argv[2] if len(sys.argv) > 2 else None
CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
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
"""

# No request may leave the page: no proxy reachable, names resolve nowhere,
# and Chromium's own background traffic switched off so that any request in
# the log is the page's.
QUIET = ["--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync",
         "--disable-default-apps", "--disable-extensions", "--disable-domain-reliability",
         "--metrics-recording-only", "--no-pings", "--proxy-server=http://127.0.0.1:9",
         "--host-resolver-rules=MAP * ~NOTFOUND", "--enable-logging=stderr", "--v=0"]

def open_in_chromium(url, profile, tmp):
    """(DOM, console lines, URLs the page asked for outside the file)."""
    netlog = os.path.join(tmp, "net.json")
    r = subprocess.run([CHROMIUM, *QUIET, f"--user-data-dir={profile}", f"--log-net-log={netlog}",
                        "--dump-dom", url], capture_output=True, text=True, timeout=120)
    console = [l for l in r.stderr.splitlines() if "CONSOLE" in l or "Uncaught" in l]
    text = open(netlog).read()
    try:
        log = json.loads(text)
    except ValueError:  # cut short at exit: close it
        log = json.loads(text.rstrip().rstrip(",") + "]}")
    start_job = log["constants"]["logEventTypes"]["URL_REQUEST_START_JOB"]
    leaving = set()
    for e in log["events"]:
        p = e.get("params") or {}
        # Chromium's own traffic (updater, clock, accounts) is browser-initiated
        # ("not an origin"); what the page asks for has its origin ("null" for file://).
        if e["type"] == start_job and p.get("initiator") != "not an origin":
            if not p.get("url", "file:").startswith(("file:", "data:", "about:", "chrome:")):
                leaving.add(p.get("url"))
    return r.stdout if r.returncode == 0 else "", console, sorted(leaving)


if not CHROMIUM:
    raise SystemExit("chromium not found: scripts/setup installs it (CNCLAB_SETUP_TEST=1)")

with tempfile.TemporaryDirectory() as tmp:
    with open(os.path.join(tmp, "tiny.yaml"), "w") as f:
        f.write(EXPERIMENT)
    common = ["--quiet", "--out", "results", "--data-dir", "data"]
    run(["run", "tiny.yaml", "trainer.learning_rate=0.02", *common], tmp)
    run(["sweep", "tiny.yaml", "trainer.learning_rate=0.005,0.01,0.05", "model.hidden=[3],[5]",
         *common], tmp)
    results = os.path.join(tmp, "results", "tiny")
    # The single run (the sweep's trials are linked beside it too): found by its override.
    listed = json.loads(run(["runs", "results", "--where", "learning_rate=0.02", "--format",
                             "json"], tmp).stdout)["runs"]
    check(len(listed) == 1, f"one run with learning_rate 0.02 ({len(listed)})")
    result = listed[0]["file"]
    sweep = [os.path.join(results, d) for d in os.listdir(results) if d.startswith("sweep")][0]
    html = os.path.join(tmp, "report.html")
    run(["report", result, sweep, "-o", html], tmp)

    text = open(html, encoding="utf-8").read()
    check(os.path.getsize(html) <= 5 * 1024 * 1024, "at most 5 MB")
    check("<script" not in text.lower(), "no script")
    external = re.findall(r'(?:src|href)\s*=\s*["\']?\s*(?:https?:|//)', text, re.I)
    check(not external, f"no external reference ({external[:3]})")
    check("<img" not in text.lower() and "<link" not in text.lower(), "figures inline, no <link>")

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
    check("command" in dom and "trainer.learning_rate=0.02" in dom, "provenance: the override")

    if SHOTS:
        os.makedirs(SHOTS, exist_ok=True)
        profile = os.path.join(tmp, "chromium-profile")
        for name, extra in [("report-1280.png", ["--window-size=1280,2200",
                                                 "--screenshot=" + os.path.join(SHOTS, "report-1280.png")]),
                            ("report-print.pdf", ["--print-to-pdf=" + os.path.join(SHOTS, "report-print.pdf"),
                                                  "--no-pdf-header-footer"])]:
            subprocess.run([CHROMIUM, *QUIET, f"--user-data-dir={profile}", *extra, url],
                           capture_output=True, timeout=120)
            print("wrote", os.path.join(SHOTS, name))

if failures:
    print(f"{len(failures)} check(s) failed")
    sys.exit(1)
print("report_browser_test: all checks passed")
