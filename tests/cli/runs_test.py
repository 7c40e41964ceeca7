#!/usr/bin/env python3
"""`cnclab runs` and result provenance, checked against h5py.

Makes a few small Friedman #1 runs (overrides, a profile, a git project),
a foreign HDF5 file and a corrupt one, then:
  - every result's /provenance holds the command line, overrides, profile,
    the project's git commit and dirty flag, wall and CPU time (h5py), and
    `cnclab show` prints them;
  - `cnclab runs --format json` with --where/--sort gives the runs, in the
    order, that h5py + PyYAML select and sort independently;
  - the index file is used (no file read the second time), refreshed when a
    file changes or goes, rebuilt when corrupt, and never trusted over files.
Usage: runs_test.py CNCLAB SOURCE_DIR
"""
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
import time

import h5py
import yaml

CNCLAB, SOURCE = sys.argv[1], sys.argv[2]
failures = []


def check(cond, what):
    if not cond:
        failures.append(what)
        print("FAIL:", what)


def run(args, cwd, expect=0):
    r = subprocess.run([CNCLAB] + args, cwd=cwd, capture_output=True, text=True)
    if r.returncode != expect:
        print(r.stdout, r.stderr)
        raise SystemExit(f"cnclab {' '.join(args)}: exit {r.returncode}, expected {expect}")
    return r


EXPERIMENT = """name: tiny
seed: 7
dataset:
  generator: friedman1
  options: {samples: 120, inputs: 6, noise_std: 1.0}
split: {train: 0.6, validation: 0.2}
model: {type: mlp, hidden: [4], hidden_activation: tanh, output_activation: linear}
trainer: {type: sgdm, learning_rate: 0.01, momentum: 0.9, batch_size: 16, epochs: 4}
metrics: [rmse, mae]
profiles:
  quick:
    trainer.epochs: 2
"""


def git(args, cwd):
    subprocess.run(["git", "-c", "user.name=t", "-c", "user.email=t@t", *args], cwd=cwd,
                   check=True, capture_output=True)


def h5_text(v):
    return v.decode() if isinstance(v, bytes) else str(v)


def flat(node, prefix=""):
    """The resolved YAML as dotted keys (the same rule as the listing, but
    written here from the YAML alone)."""
    out = {}
    if isinstance(node, dict):
        for k, v in node.items():
            out.update(flat(v, f"{prefix}.{k}" if prefix else str(k)))
    else:
        out[prefix] = node
    return out


def result_files(root):
    found = []
    for d, _, names in os.walk(root):
        for n in names:
            if n.endswith(".h5") and not n.startswith(".") and n != "summary.h5":
                found.append(os.path.join(d, n))
    return found


with tempfile.TemporaryDirectory() as tmp:
    project = os.path.join(tmp, "project")
    os.makedirs(project)
    with open(os.path.join(project, "tiny.yaml"), "w") as f:
        f.write(EXPERIMENT)
    git(["init", "-q"], project)
    git(["add", "tiny.yaml"], project)
    git(["commit", "-q", "-m", "tiny"], project)
    head = subprocess.run(["git", "rev-parse", "HEAD"], cwd=project, capture_output=True,
                          text=True, check=True).stdout.strip()
    common = ["--quiet", "--out", "results", "--data-dir", "data"]
    # Four runs: learning rates and hidden sizes by override, one with a profile.
    for lr, hidden in [("0.01", "[4]"), ("0.05", "[4]"), ("0.02", "[6]"), ("0.05", "[6]")]:
        run(["run", "tiny.yaml", f"trainer.learning_rate={lr}", f"model.hidden={hidden}", *common],
            project)
    run(["run", "tiny.yaml", "trainer.learning_rate=0.03", "--profile", "quick", *common], project)
    # A tracked file changed: the next result records a dirty project.
    with open(os.path.join(project, "tiny.yaml"), "a") as f:
        f.write("# edited\n")
    run(["run", "tiny.yaml", "seed=8", *common], project)

    results = os.path.join(project, "results")
    files = result_files(results)
    check(len(files) == 6, f"six results written (found {len(files)})")

    # --- provenance, read with h5py ---
    profiled = dirty = None
    for path in files:
        with h5py.File(path, "r") as h:
            p = h["provenance"].attrs
            over = h5_text(p["overrides"]).splitlines()
            check(h5_text(p["command_line"]).split()[1:2] == ["run"],
                  f"{path}: command_line {h5_text(p['command_line'])!r}")
            check(h5_text(p["project_commit"]) == head, f"{path}: project_commit is HEAD")
            check(float(p["cpu_seconds"]) > 0 and float(p["wall_seconds"]) > 0,
                  f"{path}: CPU and wall time")
            check(os.path.realpath(h5_text(p["project_dir"])) == os.path.realpath(project),
                  f"{path}: project_dir {h5_text(p['project_dir'])!r}")
            if h5_text(p["profile"]) == "quick":
                profiled = path
                check(over == ["trainer.learning_rate=0.03"], f"{path}: overrides {over}")
            if h5_text(p["project_dirty"]) == "yes":
                dirty = path
                check(over == ["seed=8"], f"{path}: overrides {over}")
    check(profiled is not None, "one result records the profile 'quick'")
    check(dirty is not None and len([f for f in files if f != dirty]) == 5,
          "exactly the result after the edit records a dirty project")
    if profiled:
        shown = run(["show", profiled], project).stdout
        check("profile      quick" in shown, "show prints the profile")
        check("override     trainer.learning_rate=0.03" in shown, "show prints the override")
        check("(git " + head + ", clean)" in shown, "show prints the project's commit")
        check("CPU " in shown and "command      " in shown, "show prints CPU time and command")

    # Files that are not results: a foreign HDF5 file and a corrupt one.
    with h5py.File(os.path.join(results, "foreign.h5"), "w") as h:
        h["x"] = [1.0, 2.0]
    with open(os.path.join(results, "corrupt.h5"), "wb") as f:
        f.write(b"\x89HDF\r\n\x1a\n" + b"\0" * 100)

    # --- --where / --sort against h5py ---
    def h5py_select(min_lr, metric):
        rows = []
        for path in result_files(results):
            try:
                with h5py.File(path, "r") as h:
                    if h5_text(h.attrs.get("format", b"")) != "cnclab-result":
                        continue
                    cfg = flat(yaml.safe_load(h5_text(h["config"][()])))
                    metrics = {k: float(v) for k, v in h["metrics"].attrs.items()}
            except OSError:
                continue
            if float(cfg["trainer.learning_rate"]) >= min_lr:
                rows.append((metrics[metric], os.path.realpath(path)))
        rows.sort(key=lambda r: -r[0] if not math.isnan(r[0]) else math.inf)
        return rows

    with h5py.File(files[0], "r") as h:
        metric = sorted(k for k in h["metrics"].attrs.keys() if k.endswith("rmse"))[0]
    r = run(["runs", "--results", "results", "--where", "learning_rate", ">=", "0.03",
             "--sort", "-" + metric, "--format", "json"], project)
    got = json.loads(r.stdout)["runs"]
    want = h5py_select(0.03, metric)
    check([os.path.realpath(g["file"]) for g in got] == [w[1] for w in want],
          f"--where learning_rate >= 0.03 --sort -{metric}: same runs and order as h5py")
    check(all(abs(g["metrics"][metric] - w[0]) <= 1e-12 * abs(w[0]) for g, w in zip(got, want)),
          "metric values equal h5py's")
    check(len(want) == 3, f"three runs have learning_rate >= 0.03 (h5py: {len(want)})")
    check("not a readable result" in r.stderr, "foreign and corrupt files are reported")

    # Table: the varying keys, the metric with its unit, the profile's run.
    table = run(["runs", "--results", "results"], project).stdout
    check("trainer.learning_rate" in table and "model.hidden" in table,
          "the table shows the config keys that vary")
    check("6 of 6 runs" in table, "the table counts the runs")

    # --- the index ---
    index = os.path.join(results, ".runs-index.json")
    check(os.path.exists(index), "the index file exists under the results root")
    with open(index) as f:
        entries = json.load(f)["runs"]
    check(len(entries) == 8, f"the index holds every .h5 file (got {len(entries)})")
    # Not trusted over the files: a result replaced by another run's file (new
    # size or mtime) is read again.
    victim = [f for f in files if f != profiled][0]
    shutil.copyfile(profiled, victim)
    os.utime(victim, (time.time() + 5, time.time() + 5))
    got = json.loads(run(["runs", "--results", "results", "--format", "json",
                          "--where", "profile=quick"], project).stdout)["runs"]
    check(sorted(os.path.realpath(g["file"]) for g in got) ==
          sorted(os.path.realpath(p) for p in [profiled, victim]),
          "a changed file is read again, not taken from the index")
    os.remove(victim)
    got = json.loads(run(["runs", "--results", "results", "--format", "json"], project).stdout)
    check(len(got["runs"]) == 5, "a removed file leaves the listing")
    with open(index, "w") as f:
        f.write("{ not json")
    r = run(["runs", "--results", "results", "--format", "json"], project)
    check(len(json.loads(r.stdout)["runs"]) == 5 and "rebuilt" in r.stderr,
          "a corrupt index is rebuilt")

    # --diff: only what differs.
    a, b = sorted(f for f in result_files(results) if os.path.basename(f).startswith("tiny"))[:2]
    d = run(["runs", "--results", "results", "--diff", a, b], project).stdout
    check("delta" in d or "(" in d, "--diff prints metric deltas")
    # Errors: unknown key (exit 2, named), bad operator text.
    e = run(["runs", "--results", "results", "--where", "nosuchkey=1"], project, expect=2)
    check("nosuchkey" in e.stderr, "an unknown key is named")
    run(["runs", "--results", "results", "--where", "learning_rate"], project, expect=2)

if failures:
    print(f"{len(failures)} check(s) failed")
    sys.exit(1)
print("runs_test: all checks passed")
