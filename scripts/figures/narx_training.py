#!/usr/bin/python3
"""What Levenberg-Marquardt did in each NARX training stage of seed 002's two
studies: the data for docs/narx_training.md.

Usage: /usr/bin/python3 scripts/figures/narx_training.py [--format png|pdf|svg]
       [--dpi N] [--out DIR] [--no-title] [--unfinished] [RESULTS_DIR]

Reads the finished sweeps of experiments/contour_error/training_methods.yaml
and architecture.yaml (RESULTS_DIR/<study>/sweep-<plan hash>/, chosen as
contour_error.py chooses them) and every complete trial's per-network stage
histories (result_narx.hpp: /history/<axis>/stage<k>/ with sse, mu, alpha,
beta, gamma, gradient, curvature per epoch and the initial_* attributes, the
state before the first step). Prints one line per network and stage (epochs,
termination, SSE before -> after, mu and the curvature scale
beta max diag(J^T J) at the start and the end, the final gradient 2 ||J^T e||
beside its floor 2 (alpha/beta) ||w|| at trainbr's optimum, and the wall
time per epoch) and the closed-loop validation RMS of the network, and
draws the closed-loop stage's series per epoch (epoch 0: the initial state), failed stages (mu_max) in red, to
RESULTS_DIR/figures/narx_training/closed_loop_stage.png (or --out
DIR/narx_training/, --format; style of paper_style.py).

--unfinished: a study whose sweeps are all unfinished (a long run such as
the converged profile, still going) is read from its newest sweep's
finished trials, with a line saying how many of how many; no figure is
drawn then.
"""
import argparse
import glob
import os
import sys

import h5py
import numpy as np
import yaml
from contour_error import Missing, finished, newest_sweep, resolved_yaml, sweep_trials, text
from matplotlib.lines import Line2D
from matplotlib.ticker import MaxNLocator
from paper_style import DOUBLE, ERROR, Output, add_arguments, apply, plt

STUDIES = ["contour_error_training_methods", "contour_error_architecture"]
SERIES = ["sse", "mu", "curvature", "alpha", "beta", "gamma", "gradient"]
# Panel titles: the symbols of the Levenberg-Marquardt / Bayesian
# regularisation update (MacKay; Foresee and Hagan), as docs/narx_training.md.
TITLES = {
    "sse": "sum of squared errors $E_D$",
    "mu": "damping $\\mu$",
    "curvature": "curvature scale $\\beta\\,\\max\\,\\mathrm{diag}(J^TJ)$",
    "alpha": "weight prior $\\alpha$",
    "beta": "noise precision $\\beta$",
    "gamma": "effective parameters $\\gamma$",
    "gradient": "gradient norm",
}


def stage_record(group):
    """One stage: attributes and the series with the initial state first."""
    rec = {k: text(group.attrs[k]) for k in ("mode", "termination")}
    for name in SERIES:
        values = group[name][()] if name in group else np.full(len(group["epoch"]), np.nan)
        start = group.attrs.get("initial_" + name, np.nan)
        rec[name] = np.concatenate([[start], values])
    # E_W at the end and the stage's wall time (not in older files: nan).
    for name in ("ssw", "wall_seconds"):
        rec[name] = float(group[name][-1]) if name in group and len(group[name]) else np.nan
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
        # The same in seed 002's words, for the figure's legend.
        words = (f"seed {config.get('seed')}, {model.get('hidden')} hidden, "
                 f"{model.get('input_delays')} delays")
        axes = [text(a) for a in h["model/networks"][()]]
        first = int(h["validation"].attrs["first_step"])
        pred, target = h["validation/predictions"][()], h["validation/targets"][()]
        out = []
        for i, axis in enumerate(axes):
            err = (pred[:, i] - target[:, i])[first:]  # steps x networks, as contour_error.py
            rms = float(np.sqrt(np.mean(err**2))) if np.all(np.isfinite(err)) else float("inf")
            g = h[f"history/{axis}"]
            recs = [stage_record(g[f"stage{k}"]) for k in range(len(g)) if f"stage{k}" in g]
            out.append((label, axis, rms, recs, f"{words}, {axis.upper()} axis"))
        return out


def fit_limits(ax, finished, stopped, decades=3):
    """y limits that show every finished stage and the stopped ones up to
    `decades` above the finished ones: a diverging stage (1e100) would
    flatten every other line; it leaves the panel at the top instead."""
    def positive(series):
        v = np.abs(np.concatenate([np.ravel(x) for x in series])) if series else np.array([])
        return v[np.isfinite(v) & (v > 0)]

    done, bad = positive(finished), positive(stopped)
    if not done.size:
        return
    everything = np.concatenate([done, bad])
    top = min(everything.max() * 2.0, done.max() * 10.0**decades)
    ax.set_ylim(everything.min() / 2.0, top)


def fmt(x):
    return "nan" if not np.isfinite(x) else f"{x:.3g}"


def unfinished_sweep(results, study):
    """The newest sweep-* folder of the study (by sweep.yaml's time) and its
    finished trial files, with a note: "k of n trials finished"."""
    dirs = [d for d in glob.glob(os.path.join(results, study, "sweep-*"))
            if os.path.exists(os.path.join(d, "sweep.yaml"))]
    if not dirs:
        raise Missing(f"no sweep under {os.path.join(results, study)}/sweep-*")
    d = max(dirs, key=lambda d: os.path.getmtime(os.path.join(d, "sweep.yaml")))
    paths, _ = sweep_trials(d)
    done = [p for p in paths if finished(p)]
    return done, f"{os.path.basename(d)}: {len(done)} of {len(paths)} trials finished"


def stage_text(s):
    """One stage's line part (main's header names the fields)."""
    epochs = len(s["sse"]) - 1
    floor = 2 * s["alpha"][-1] / s["beta"][-1] * np.sqrt(s["ssw"])
    per_epoch = s["wall_seconds"] / epochs if epochs else np.nan
    return (f"{s['mode']}: {epochs} {s['termination']} {fmt(s['sse'][0])} -> "
            f"{fmt(s['sse'][-1])}, mu {fmt(s['mu'][0])} -> {fmt(s['mu'][-1])}, curv "
            f"{fmt(s['curvature'][0])} -> {fmt(s['curvature'][-1])}, grad "
            f"{fmt(s['gradient'][-1])} (floor {fmt(floor)}), {fmt(per_epoch)} s/epoch")


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("results", nargs="?", default="results",
                        help="results folder (default: results)")
    parser.add_argument("--unfinished", action="store_true",
                        help="read the finished trials of a study's unfinished sweep")
    add_arguments(parser)
    args = parser.parse_args()
    rows, partial = [], False
    for study in STUDIES:
        try:
            _, paths = newest_sweep(args.results, study)
        except Missing as e:
            if not args.unfinished:
                print(f"narx_training.py: {study}: {e}", file=sys.stderr)
                continue
            try:
                paths, note = unfinished_sweep(args.results, study)
            except Missing as e2:
                print(f"narx_training.py: {study}: {e2}", file=sys.stderr)
                continue
            print(f"{study}: unfinished, {note}")
            partial = True
        for p in paths:
            rows += trial_records(p)
    if not rows:
        print("narx_training.py: no finished NARX sweep" +
              ("" if args.unfinished else " (--unfinished: the finished trials of one)"),
              file=sys.stderr)
        return 3
    print("trial | axis | val RMS | stage: epochs termination SSE0 -> SSE, mu0 -> mu, "
          "curvature0 -> curvature, final gradient 2||J^T e|| (floor 2 (alpha/beta) ||w||), "
          "wall time per epoch")
    for label, axis, rms, stages, _ in rows:
        print(f"{label} | {axis} | {fmt(rms)} | " + "; ".join(stage_text(s) for s in stages))

    closed = [(f"{words}, stage {k + 1}", s) for label, _, _, stages, words in rows
              for k, s in enumerate(stages) if s["mode"] == "closed_loop" and "open_loop" in label]
    if partial:
        print("narx_training.py: unfinished sweeps: no figure drawn", file=sys.stderr)
    elif closed:
        apply()
        closed_loop_figure(Output(args, args.results, "narx_training"), closed)
    return 0


def closed_loop_figure(out, closed):
    """The closed-loop (parallel) stage of every two-stage trial, per
    network: one panel per series of SERIES (log scale, shared epoch axis),
    the stages that stopped at mu_max in red and named in the legend."""
    fig, axs = plt.subplots(4, 2, figsize=(DOUBLE, 6.4), sharex=True, layout="constrained")
    panels = axs.ravel()
    failed = {}  # legend label -> how many networks
    for words, s in closed:
        stopped = s["termination"] == "mu_max"
        if stopped:
            failed[words] = failed.get(words, 0) + 1
        for ax, name in zip(panels, SERIES):
            y = np.abs(s[name])
            if np.isfinite(y).any():
                ax.semilogy(np.arange(len(y)), y, color=ERROR if stopped else "tab:blue",
                            alpha=0.9 if stopped else 0.35, lw=1.0 if stopped else 0.6)
    for ax, name in zip(panels, SERIES):
        ax.set_title(TITLES[name])
        fit_limits(ax, [s[name] for _, s in closed if s["termination"] != "mu_max"],
                   [s[name] for _, s in closed if s["termination"] == "mu_max"])
        if not ax.lines:
            ax.text(0.5, 0.5, "not recorded", transform=ax.transAxes, ha="center", va="center")
    # The bottom panel of each column carries the epoch axis (the eighth
    # panel is the legend's).
    axs[0][0].xaxis.set_major_locator(MaxNLocator(integer=True))  # shared by all
    for ax in (axs[-1][0], axs[-2][1]):
        ax.tick_params(labelbottom=True)
        ax.set_xlabel("epoch (0: before the first step)")
    legend_ax = axs[-1][1]
    legend_ax.axis("off")
    n_failed = sum(failed.values())
    handles = [Line2D([], [], color="tab:blue", alpha=0.6, lw=1.0,
                      label=f"finished ({len(closed) - n_failed} stages)")]
    handles += [Line2D([], [], color=ERROR, lw=1.0,
                       label=f"stopped at $\\mu_{{max}}$: {w}" + (f" (×{n})" if n > 1 else ""))
                for w, n in failed.items()]
    legend_ax.legend(handles=handles, loc="center", frameon=False)
    out.title(fig, "Parallel (closed-loop) stage of the two-stage training, per network")
    out.save(fig, "closed_loop_stage")


if __name__ == "__main__":
    sys.exit(main())
