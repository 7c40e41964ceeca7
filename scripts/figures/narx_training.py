#!/usr/bin/python3
"""What Levenberg-Marquardt did in each NARX training stage of seed 002's two
studies: the data for docs/narx_training.md.

Usage: /usr/bin/python3 scripts/figures/narx_training.py [RESULTS_DIR]

Reads the finished sweeps of experiments/contour_error/training_methods.yaml
and architecture.yaml (RESULTS_DIR/<study>/sweep-<plan hash>/, chosen as
contour_error.py chooses them) and every complete trial's per-network stage
histories (result_narx.hpp: /history/<axis>/stage<k>/ with sse, mu, alpha,
beta, gamma, gradient, curvature per epoch and the initial_* attributes, the
state before the first step). Prints one line per network and stage (epochs,
termination, SSE before -> after, mu and the curvature scale
beta max diag(J^T J) at the start and the end) and the closed-loop validation
RMS of the network, and draws the closed-loop stage's series per epoch
(epoch 0: the initial state), failed stages (mu_max) in red, to
RESULTS_DIR/figures/narx_training/closed_loop_stage.png.
"""
import argparse
import os
import sys

import h5py
import matplotlib
import numpy as np
import yaml

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from contour_error import Missing, newest_sweep, resolved_yaml, save, text  # noqa: E402

STUDIES = ["contour_error_training_methods", "contour_error_architecture"]
SERIES = ["sse", "mu", "curvature", "alpha", "beta", "gamma", "gradient"]


def stage_record(group):
    """One stage: attributes and the series with the initial state first."""
    rec = {k: text(group.attrs[k]) for k in ("mode", "termination")}
    for name in SERIES:
        values = group[name][()] if name in group else np.full(len(group["epoch"]), np.nan)
        start = group.attrs.get("initial_" + name, np.nan)
        rec[name] = np.concatenate([[start], values])
    return rec


def trial_records(path):
    """(label, axis, closed-loop validation RMS in normalised units, stages)
    per network of a complete trial."""
    with h5py.File(path, "r") as h:
        if text(h.attrs.get("status", "")) != "complete":
            return []
        config = yaml.safe_load(resolved_yaml(h)) or {}
        stages = (config.get("trainer") or {}).get("stages") or []
        model = config.get("model") or {}
        label = (f"{'+'.join(s['mode'] for s in stages)} seed {config.get('seed')} "
                 f"H={model.get('hidden')} D={model.get('input_delays')}")
        axes = [text(a) for a in h["model/networks"][()]]
        first = int(h["validation"].attrs["first_step"])
        pred, target = h["validation/predictions"][()], h["validation/targets"][()]
        out = []
        for i, axis in enumerate(axes):
            err = (pred[:, i] - target[:, i])[first:]  # steps x networks, as contour_error.py
            rms = float(np.sqrt(np.mean(err**2))) if np.all(np.isfinite(err)) else float("inf")
            g = h[f"history/{axis}"]
            recs = [stage_record(g[f"stage{k}"]) for k in range(len(g)) if f"stage{k}" in g]
            out.append((label, axis, rms, recs))
        return out


def fmt(x):
    return "nan" if not np.isfinite(x) else f"{x:.3g}"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("results", nargs="?", default="results")
    args = parser.parse_args()
    rows = []
    for study in STUDIES:
        try:
            _, paths = newest_sweep(args.results, study)
        except Missing as e:
            print(f"narx_training.py: {study}: {e}", file=sys.stderr)
            continue
        for p in paths:
            rows += trial_records(p)
    if not rows:
        print("narx_training.py: no finished NARX sweep", file=sys.stderr)
        return 3
    print("trial | axis | val RMS | stage: epochs termination SSE0 -> SSE, mu0 -> mu, "
          "curvature0 -> curvature")
    for label, axis, rms, stages in rows:
        parts = []
        for s in stages:
            parts.append(f"{s['mode']}: {len(s['sse']) - 1} {s['termination']} "
                         f"{fmt(s['sse'][0])} -> {fmt(s['sse'][-1])}, mu {fmt(s['mu'][0])} -> "
                         f"{fmt(s['mu'][-1])}, curv {fmt(s['curvature'][0])} -> "
                         f"{fmt(s['curvature'][-1])}")
        print(f"{label} | {axis} | {fmt(rms)} | " + "; ".join(parts))

    closed = [(label, axis, s) for label, axis, _, stages in rows for s in stages
              if s["mode"] == "closed_loop" and "open_loop" in label]
    if not closed:
        return 0
    fig, axs = plt.subplots(len(SERIES), 1, figsize=(8, 2.2 * len(SERIES)), sharex=True)
    for label, axis, s in closed:
        failed = s["termination"] == "mu_max"
        for ax, name in zip(axs, SERIES):
            ax.semilogy(np.arange(len(s[name])), np.abs(s[name]),
                        color="tab:red" if failed else "tab:blue", alpha=0.8 if failed else 0.35,
                        lw=1.2 if failed else 0.8, label=f"{label} {axis}" if failed else None)
    for ax, name in zip(axs, SERIES):
        ax.set_ylabel(name)
    axs[0].set_title("two-stage trials, closed-loop stage (red: stopped on mu_max)")
    axs[-1].set_xlabel("epoch (0: before the first step)")
    if any(s["termination"] == "mu_max" for _, _, s in closed):
        axs[0].legend(fontsize=6)
    out_dir = os.path.join(args.results, "figures", "narx_training")
    os.makedirs(out_dir, exist_ok=True)
    save(fig, out_dir, "closed_loop_stage.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
