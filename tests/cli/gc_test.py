#!/usr/bin/env python3
"""`cnclab gc` on a results folder holding current, stale and foreign files.

Two tiny experiments run (one also with its quick profile), then one is
edited and re-run, and one run is made with an override: the results and
datasets that no experiment file still produces are known by construction.
A NARX stage cache folder is added: gc lists it always (a cache).
Checks that the dry run lists exactly those and removes nothing, that --yes
removes exactly those, that foreign files are never touched, and that
`reproduce` afterwards reuses every current result (nothing was removed
that a current experiment would reuse).
Usage: gc_test.py CNCLAB
"""
import os
import subprocess
import sys
import tempfile

import h5py

CNCLAB = sys.argv[1]
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


def experiment(name, samples, epochs):
    return f"""name: {name}
seed: 3
dataset:
  generator: friedman1
  options: {{samples: {samples}, inputs: 5, noise_std: 1.0}}
split: {{train: 0.7, validation: 0.0}}
model: {{type: mlp, hidden: [3], hidden_activation: tanh, output_activation: linear}}
trainer: {{type: sgdm, learning_rate: 0.01, momentum: 0.9, batch_size: 16, epochs: {epochs}}}
metrics: [rmse]
profiles:
  quick:
    trainer.epochs: 1
"""


def files_under(*roots):
    """Every file but the runs index (a cache gc and `runs` refresh)."""
    out = set()
    for root in roots:
        for d, _, names in os.walk(root):
            for n in names:
                if n != ".runs-index.json":
                    out.add(os.path.realpath(os.path.join(d, n)))
    return out


with tempfile.TemporaryDirectory() as tmp:
    exp = os.path.join(tmp, "experiments")
    os.makedirs(exp)
    common = ["--quiet", "--out", "results", "--data-dir", "datasets"]
    write = lambda name, text: open(os.path.join(exp, name), "w").write(text)
    write("a.yaml", experiment("a", 100, 2))
    write("b.yaml", experiment("b", 140, 2))
    res, data = os.path.join(tmp, "results"), os.path.join(tmp, "datasets")

    run(["run", "experiments/a.yaml", *common], tmp)
    run(["run", "experiments/a.yaml", "--profile", "quick", *common], tmp)
    before_b = files_under(res, data)
    run(["run", "experiments/b.yaml", *common], tmp)
    b_old = files_under(res, data) - before_b  # b's result and its dataset
    before = files_under(res, data)
    run(["run", "experiments/a.yaml", "trainer.epochs=3", *common], tmp)
    a_override = files_under(res, data) - before  # no experiment file makes it
    # b edited: a new dataset size and epochs; its old result and dataset are stale.
    write("b.yaml", experiment("b", 160, 3))
    run(["run", "experiments/b.yaml", *common], tmp)
    # Foreign files: never touched.
    foreign = [os.path.join(res, "notes.txt"), os.path.join(res, "a", "mine.h5"),
               os.path.join(data, "other.h5")]
    open(foreign[0], "w").write("my notes\n")
    for f in foreign[1:]:
        with h5py.File(f, "w") as h:
            h["x"] = [1, 2, 3]

    # The NARX stage cache: a folder gc always lists (a cache) and --yes removes.
    stage_cache = os.path.join(data, "narx-stages")
    os.makedirs(stage_cache)
    stage_file = os.path.realpath(os.path.join(stage_cache, "0123456789abcdef.h5"))
    with h5py.File(stage_file, "w") as h:
        h["x"] = [1.0]

    stale = {f for f in b_old | a_override if f.endswith(".h5")}
    check(len(stale) == 3, f"three stale files by construction (got {sorted(stale)})")
    stale_files = stale | {stage_file}
    stale = stale | {os.path.realpath(stage_cache)}
    everything = files_under(res, data)
    r = run(["gc", "experiments", "--out", "results", "--data-dir", "datasets"], tmp)
    listed = {os.path.realpath(line.split("\t")[-1]) for line in r.stdout.splitlines()
              if line.startswith("stale")}
    check(listed == stale, f"dry run lists exactly the stale files\n  listed {sorted(listed)}\n"
                           f"  stale  {sorted(stale)}")
    check(files_under(res, data) == everything, "the dry run removes nothing")
    run(["gc", "experiments", "--out", "results", "--data-dir", "datasets", "--yes"], tmp)
    left = files_under(res, data)
    check(left == everything - stale_files, "--yes removes exactly the stale files")
    check(not os.path.exists(stage_cache), "--yes removes the stage cache folder")
    check(all(os.path.exists(f) for f in foreign), "foreign files are left alone")
    again = run(["gc", "experiments", "--out", "results", "--data-dir", "datasets"], tmp)
    check(again.stdout.startswith("0 stale items"), "nothing stale after --yes")
    # Every current result is reused as it is (same files, nothing regenerated).
    run(["reproduce", "experiments", *common], tmp)
    check(files_under(res, data) == left,
          "reproduce after gc makes no file: nothing it reuses was removed")
    run(["gc", "--yes", "--dry-run"], tmp, expect=2)

if failures:
    print(f"{len(failures)} check(s) failed")
    sys.exit(1)
print("gc_test: all checks passed")
