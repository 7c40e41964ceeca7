#!/usr/bin/env python3
"""Runs a torch export (`cnclab export --format torch`) in PyTorch on a CSV of
raw inputs and compares it with `cnclab predict`'s CSV of the same inputs:
equal to 1e-12 (relative to max(1, |value|)) in float64.

Usage: torch_export_check.py MODULE.py CLASS INPUT.csv PREDICTED.csv
"""
import importlib.util
import sys

import numpy as np
import torch

TOLERANCE = 1e-12


def read_csv(path):
    """{name: column} of a cnclab CSV ('# ' comments, 'name [unit]' headers)."""
    with open(path, encoding="utf-8") as f:
        lines = [l.strip() for l in f if l.strip() and not l.startswith("#")]
    names = [h.split("[")[0].strip() for h in lines[0].split(",")]
    values = np.array([[float(c) for c in l.split(",")] for l in lines[1:]])
    return {n: values[:, j] for j, n in enumerate(names)}


def compare(label, got, want):
    worst = float(np.max(np.abs(got - want) / np.maximum(1.0, np.abs(want))))
    print(f"{label}: max relative difference {worst:.3g} over {len(want)} values")
    return worst <= TOLERANCE


def main():
    module_file, class_name, input_csv, predicted_csv = sys.argv[1:5]
    spec = importlib.util.spec_from_file_location(class_name, module_file)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    model = getattr(module, class_name)()
    assert isinstance(model, torch.nn.Module)
    inputs, predicted = read_csv(input_csv), read_csv(predicted_csv)
    x = torch.tensor(np.stack([inputs[n] for n in model.INPUT_COLUMNS], axis=1),
                     dtype=torch.float64)
    ok = True
    with torch.no_grad():
        if hasattr(model, "simulate"):  # narx: closed loop from standstill
            y = model.simulate(x.unsqueeze(1))[:, 0, :]
            suffix = ".closed_loop"
        else:
            y = model(x)
            suffix = ".predicted"
        for k, name in enumerate(model.OUTPUT_COLUMNS):
            ok &= compare(name, y[:, k].numpy(), predicted[name + suffix])
        if hasattr(model, "contour_error") and "ref_x" in inputs:
            pair = lambda a, b: torch.tensor(np.stack([inputs[a], inputs[b]], axis=1),
                                             dtype=torch.float64)
            c = model.contour_error(pair("ref_x", "ref_y"), pair("d1_x", "d1_y"),
                                    pair("d2_x", "d2_y"), y)
            ok &= compare("contour_error", c.numpy(), predicted["contour_error.closed_loop"])
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
