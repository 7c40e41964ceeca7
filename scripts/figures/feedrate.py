#!/usr/bin/python3
"""The contour-error constrained feedrate (seed 002's application, docs/motion.md).

Usage: /usr/bin/python3 scripts/figures/feedrate.py [--format png|pdf|svg]
       [--dpi N] [--out DIR] [--no-title] [RESULTS_DIR]

Reads the newest per-tick file of experiments/contour_error/feedrate.yaml
(RESULTS_DIR/contour_error_feedrate/*-ticks.h5, written beside the job's
result by `cnclab reproduce`): per tolerance group eps<N>um, per method
(unconstrained, constrained, uniform, constant) the 1 ms time, path feed
[mm/s], simulated contour error [mm] and, for the predictor's plans, the
predicted one. Draws, for every tolerance, on one time axis: the feed of the
unconstrained, constrained and uniformly slowed plans, and the constrained
plan's predicted and simulated contour error against eps_max. Writes
feedrate_<label> to RESULTS_DIR/figures/feedrate/ (or --out DIR/feedrate/).
Exits 3 when there is no such file.
"""
import glob
import os
import sys

import h5py
import numpy as np
from paper_style import (ACTUAL, DOUBLE, ERROR, PREDICTED, Output, apply, parse_arguments,
                         plt)

JOB = "contour_error_feedrate"
MAKE = ("cnclab reproduce experiments/contour_error/narx.yaml "
        "experiments/contour_error/feedrate.yaml")


def tolerance_um(label):
    return float(label[len("eps"):-len("um")])


def figure(out, label, group):
    eps = tolerance_um(label)
    fig, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=(DOUBLE, 0.6 * DOUBLE))
    styles = {"unconstrained": ("0.5", "unconstrained (minimum time)"),
              "constrained": (ACTUAL, "constrained (NARX-predicted feed limits)"),
              "uniform": (ERROR, "uniform slowdown (simulated bisection)")}
    for method, (colour, name) in styles.items():
        if method in group:
            g = group[method]
            top.plot(g["time"][:], g["feed"][:], color=colour, lw=0.8,
                     label=f"{name}, {g['time'][-1]:.3f} s")
    top.set_ylabel("feed [mm/s]")
    top.legend(loc="lower center", fontsize="small")
    c = group["constrained"]
    bottom.plot(c["time"][:], 1e3 * c["simulated"][:], color=ACTUAL, lw=0.8,
                label="simulated (exact, tool position)")
    bottom.plot(c["time"][:], 1e3 * c["predicted"][:], color=PREDICTED, lw=0.8,
                label="predicted (NARX + Taylor)")
    bottom.axhline(eps, color=ERROR, lw=0.8, ls="--", label=f"eps_max = {eps:g} um")
    bottom.set_xlabel("time [s]")
    bottom.set_ylabel("contour error [um]")
    bottom.legend(loc="upper right", fontsize="small")
    out.title(fig, f"Contour-error constrained feedrate, eps_max = {eps:g} um")
    fig.tight_layout()
    out.save(fig, f"feedrate_{label}")


def main():
    args = parse_arguments(__doc__)
    files = glob.glob(os.path.join(args.results, JOB, "*-ticks.h5"))
    if not files:
        print(f"feedrate.py: no {JOB} ticks file under {args.results}; run `{MAKE}`",
              file=sys.stderr)
        return 3
    path = max(files, key=os.path.getmtime)
    apply()
    out = Output(args, args.results, "feedrate")
    with h5py.File(path, "r") as f:
        for label in sorted(f, key=tolerance_um, reverse=True):
            if "constrained" in f[label]:
                figure(out, label, f[label])
    return 0


if __name__ == "__main__":
    sys.exit(main())
