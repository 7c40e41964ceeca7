#!/usr/bin/env python3
"""Metrics per split, checked outside cnclab.

1. `cnclab run` of a small Friedman #1 MLP: every stored metric is
   <split>.<metric>, and each is recomputed here with numpy from the stored
   network (parameters, activations, z-score scalings), the dataset file and
   the stored split indices, on that split's samples.
2. The same file rewritten with h5py the way result format 1 stored it (the
   test split's metrics under bare names, normalised_validation_mse, no
   /metrics/units): `show` and `compare` print today's names with the same
   numbers, and `reproduce` does not reuse it: it trains again and writes
   format 2.

Usage: split_metrics_test.py CNCLAB SOURCE_DIR
"""
import json
import os
import shutil
import subprocess
import sys
import tempfile

import h5py
import numpy as np

failures = []
SPLITS = ("train", "validation", "test")
BASES = ("mse", "rmse", "mae", "max_abs_error", "r2")


def check(ok, message):
    print(("ok   " if ok else "FAIL ") + message)
    if not ok:
        failures.append(message)


def run(args, cwd):
    p = subprocess.run(args, cwd=cwd, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"{' '.join(args)}: exit {p.returncode}\n{p.stdout}{p.stderr}")
    return p.stdout + p.stderr


def text(v):
    return v.decode() if isinstance(v, bytes) else str(v)


def forward(f, x):
    """The stored MLP on physical inputs x (n x d): z-score in, layers
    (W n_out x n_in column-major, then b), z-score out (result_file.cpp)."""
    model = f["model"]
    sizes = [int(s) for s in model["layer_sizes"][:]]
    acts = {"tanh": np.tanh, "linear": lambda a: a, "relu": lambda a: np.maximum(a, 0.0),
            "sigmoid": lambda a: 1.0 / (1.0 + np.exp(-a))}
    hidden, output = acts[text(model.attrs["hidden_activation"])], acts[text(model.attrs["output_activation"])]
    for g in ("input_scaling", "target_scaling"):
        check(text(model[g].attrs["method"]) == "zscore", f"{g} is z-score")
    a = ((x - model["input_scaling/mean"][:]) / model["input_scaling/std"][:]).T
    p, at = model["parameters"][:], 0
    for layer, (n_in, n_out) in enumerate(zip(sizes, sizes[1:])):
        w = p[at:at + n_out * n_in].reshape((n_out, n_in), order="F")
        at += n_out * n_in
        b = p[at:at + n_out]
        at += n_out
        a = w @ a + b[:, None]
        a = output(a) if layer == len(sizes) - 2 else hidden(a)
    check(at == len(p), f"parameter layout uses all {len(p)} parameters")
    return (a.T * model["target_scaling/std"][:]) + model["target_scaling/mean"][:]


def expected_metrics(pred, y):
    err = pred - y
    sse = np.sum(err**2, axis=0)
    sst = np.sum((y - y.mean(axis=0)) ** 2, axis=0)
    mse = np.mean(err**2)
    return {"mse": mse, "rmse": np.sqrt(mse), "mae": np.mean(np.abs(err)),
            "max_abs_error": np.max(np.abs(err)), "r2": np.mean(1.0 - sse / sst)}


def metrics_of(path):
    with h5py.File(path, "r") as f:
        return {k: float(v) for k, v in f["metrics"].attrs.items()}


def main():
    cnclab, source = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    tmp = tempfile.mkdtemp(prefix=f"cnclab_split_metrics_{os.getpid()}_")
    try:
        experiment = os.path.join(tmp, "small.yaml")
        with open(experiment, "w") as f:
            f.write(f"include: {os.path.join(source, 'experiments/friedman/friedman1_mlp.yaml')}\n"
                    "trainer: {epochs: 5}\ndataset: {options: {samples: 300}}\n")
        args = [experiment, "--out", "results", "--data-dir", "datasets"]
        out = run([cnclab, "run", *args, "--quiet"], tmp)
        result = os.path.join(tmp, out.strip().splitlines()[-1])
        with h5py.File(result, "r") as f:
            check(int(f.attrs["format_version"]) == 2, "result format 2")
            stored = {k: float(v) for k, v in f["metrics"].attrs.items()}
            units = {k: text(v) for k, v in f["metrics/units"].attrs.items()}
            want = {f"{s}.{b}" for s in SPLITS for b in BASES}
            check(set(stored) == want, f"metric names {sorted(stored)}")
            check(set(units) == want and set(units.values()) == {"1"}, f"units {units}")
            dataset = text(f["dataset"].attrs["file"])
            with h5py.File(os.path.join(tmp, dataset) if not os.path.isabs(dataset) else dataset,
                           "r") as d:
                x, y = d["inputs"][:], d["targets"][:]
            pred = forward(f, x)
            for split in SPLITS:
                idx = np.asarray(f[f"split/{split}"][:], dtype=np.int64)
                check(len(idx) > 0, f"{split}: {len(idx)} samples")
                for base, value in expected_metrics(pred[idx], y[idx]).items():
                    got = stored[f"{split}.{base}"]
                    check(abs(got - value) <= 1e-9 * max(1.0, abs(value)),
                          f"{split}.{base}: stored {got!r}, numpy {value!r}")

        # Result format 1, as that code wrote it.
        old = os.path.join(tmp, "old.h5")
        shutil.copy(result, old)
        with h5py.File(old, "r+") as f:
            f.attrs["format_version"] = np.int64(1)
            del f["metrics"]
            g = f.create_group("metrics")
            for base in BASES:
                g.attrs[base] = stored[f"test.{base}"]
        shown = run([cnclab, "show", old], tmp)
        check("an older result (format 1)" in shown, "show says the file is of format 1")
        for base in BASES:
            check(f"  test.{base} " in shown, f"show prints test.{base}")
        check("  rmse " not in shown and "train." not in shown, "no older names, no train.*")
        compared = json.loads(run([cnclab, "compare", old, result, "--format", "json"], tmp))
        for base in BASES:
            m = compared["metrics"][f"test.{base}"]
            check(m["values"][0] == m["values"][1] and m["delta_to_first"][1] == 0,
                  f"compare: test.{base} of both files equal ({m})")
        check("validation.rmse" in compared["metrics"]
              and compared["metrics"]["validation.rmse"]["values"][0] is None,
              "compare: the format-1 file has no validation.rmse")

        # At the store's path of its config, reproduce runs it again.
        shutil.copy(old, result)
        out = run([cnclab, "reproduce", *args], tmp)
        said = "result format 1" in out
        check(said, "reproduce says why it runs again" + ("" if said else f":\n{out}"))
        with h5py.File(result, "r") as f:
            check(int(f.attrs["format_version"]) == 2, "reproduce wrote format 2")
        check(metrics_of(result) == stored, "the run again gives the same metrics")
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    if failures:
        print(f"{len(failures)} check(s) failed")
        return 1
    print("split metrics: all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
