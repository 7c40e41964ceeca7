#!/usr/bin/python3
"""Model-based sweeps (methods tpe, cmaes, nsga2, qmc): optimisation history,
parallel coordinates and parameter importance of each sweep folder below
RESULTS_DIR, read from its summary.h5 (src/cnclab/sweep/sweep_summary.hpp).

  <name>_history      the objective of each complete trial in study order and
                      the best so far; pruned trials (not ranked) as ticks
  <name>_parallel     one line per complete trial across the swept
                      parameters (each axis from its lowest to its highest
                      value, log-scaled for log_uniform), coloured by the
                      objective
  <name>_importance   fANOVA importance (/importance), largest first

<name> is the sweep's experiment and folder (step_error_tuned_table2_keep_0.5
_sweep-1a2b3c4d). Written to OUT/search/. Exit 3 when no model-based sweep
has a summary yet.
"""
import os
import sys

import h5py
import numpy as np

from matplotlib.colors import LogNorm, Normalize
from paper_style import ACTUAL, DOUBLE, ERROR, SINGLE, Output, apply, parse_arguments, plt

MODEL_BASED = ("tpe", "cmaes", "nsga2", "qmc")


def text(v):
    return v.decode() if isinstance(v, (bytes, np.bytes_)) else str(v)


def studies(results):
    """Sweep folders below `results` whose summary.h5 is of a model-based sweep."""
    for root, dirs, files in os.walk(results):
        dirs[:] = sorted(d for d in dirs if d not in ("figures", "trials", "slurm"))
        if "summary.h5" not in files:
            continue
        path = os.path.join(root, "summary.h5")
        try:
            with h5py.File(path, "r") as f:
                if text(f.attrs.get("method", "")) in MODEL_BASED and f.attrs.get("complete"):
                    yield root
        except OSError as e:
            print(f"figures: search: {path} unreadable ({e}); skipped", file=sys.stderr)


def read(folder):
    with h5py.File(os.path.join(folder, "summary.h5"), "r") as f:
        metric = text(f.attrs["objective_metric"])
        s = {
            "experiment": text(f.attrs["experiment"]),
            "method": text(f.attrs["method"]),
            "metric": metric,
            "maximize": text(f.attrs["objective_mode"]) == "max",
            "status": [text(v) for v in f["trials/status"][:]],
            "point": f["trials/point"][:],
            "objective": f[f"trials/metrics/{metric}"][:] if f"trials/metrics/{metric}" in f
            else np.full(len(f["trials/status"]), np.nan),
            "parameters": {},
            "plan": text(f["plan"][()]) if "plan" in f else "",
            "importance": None,
        }
        for key in f["trials/parameters"]:
            values = f[f"trials/parameters/{key}"][:]
            if values.dtype.kind == "f":
                s["parameters"][key] = values
        if "importance" in f:
            g = f["importance"]
            s["importance"] = ([text(p) for p in g["parameter"][:]], g["value"][:])
    return s


def history(out, s, stem):
    complete = np.array([st == "complete" for st in s["status"]])
    pruned = np.array([st == "pruned" for st in s["status"]])
    x = s["point"].astype(float)
    y = s["objective"]
    fig, ax = plt.subplots(figsize=(SINGLE, 2.4), layout="constrained")
    ax.scatter(x[complete], y[complete], s=8, color=ACTUAL, linewidths=0, label="complete")
    if complete.any():
        order = np.argsort(x[complete], kind="stable")
        ys = y[complete][order]
        best = np.maximum.accumulate(ys) if s["maximize"] else np.minimum.accumulate(ys)
        ax.step(x[complete][order], best, where="post", color=ERROR, label="best so far")
        if np.all(ys > 0) and ys.max() / ys.min() > 30:
            ax.set_yscale("log")
    if pruned.any():
        ax.plot(x[pruned], np.zeros(pruned.sum()), "|", color="0.4", markersize=8,
                transform=ax.get_xaxis_transform(), label=f"pruned ({pruned.sum()})")
    ax.set_xlabel("trial (study order)")
    ax.set_ylabel(s["metric"])
    ax.legend(loc="best")
    out.title(fig, f"{s['method']} history: {s['experiment']}")
    out.save(fig, stem + "_history")


def parallel(out, s, stem):
    complete = np.array([st == "complete" for st in s["status"]])
    keys = [k for k in s["parameters"] if np.isfinite(s["parameters"][k][complete]).all()]
    if not complete.any() or not keys:
        return
    logs = {k for k in keys if f"{k}: log_uniform" in s["plan"] or f"{k}=log_uniform" in s["plan"]}
    columns = []
    for k in keys:
        v = s["parameters"][k][complete].astype(float)
        v = np.log10(v) if k in logs and np.all(v > 0) else v
        lo, hi = v.min(), v.max()
        columns.append((v - lo) / (hi - lo) if hi > lo else np.full_like(v, 0.5))
    y = s["objective"][complete]
    norm = (LogNorm(y.min(), y.max()) if np.all(y > 0) and y.max() / y.min() > 30
            else Normalize(y.min(), y.max()))
    cmap = plt.get_cmap("viridis_r" if not s["maximize"] else "viridis")
    fig, ax = plt.subplots(figsize=(DOUBLE, 2.6), layout="constrained")
    xs = np.arange(len(keys))
    for i in np.argsort(-y if not s["maximize"] else y):  # best drawn last, on top
        ax.plot(xs, [c[i] for c in columns], color=cmap(norm(y[i])), linewidth=0.7, alpha=0.8)
    for x in xs:
        ax.axvline(x, color="0.3", linewidth=0.5)
    ax.set_xticks(xs, [k + (" (log)" if k in logs else "") for k in keys])
    ax.set_yticks([0, 1], ["lowest", "highest"])
    ax.set_xlim(-0.1, len(keys) - 0.9)
    bar = fig.colorbar(plt.cm.ScalarMappable(norm=norm, cmap=cmap), ax=ax, pad=0.01)
    bar.set_label(s["metric"])
    out.title(fig, f"{s['method']} trials: {s['experiment']}")
    out.save(fig, stem + "_parallel")


def importance(out, s, stem):
    if s["importance"] is None:
        return
    names, values = s["importance"]
    fig, ax = plt.subplots(figsize=(SINGLE, 0.6 + 0.3 * len(names)), layout="constrained")
    ax.barh(np.arange(len(names))[::-1], values, color=ACTUAL)
    ax.set_yticks(np.arange(len(names))[::-1], names)
    ax.set_xlabel(f"fANOVA importance for {s['metric']}")
    ax.set_xlim(0, max(1.0, float(np.max(values)) if len(values) else 1.0))
    out.title(fig, f"importance: {s['experiment']}")
    out.save(fig, stem + "_importance")


def main():
    args = parse_arguments(__doc__)
    apply()
    folders = list(studies(args.results))
    if not folders:
        print(f"figures: search: no model-based sweep with a summary below {args.results}",
              file=sys.stderr)
        return 3
    out = Output(args, args.results, "search")
    for folder in folders:
        s = read(folder)
        stem = f"{s['experiment']}_{os.path.basename(os.path.normpath(folder))}"
        history(out, s, stem)
        parallel(out, s, stem)
        importance(out, s, stem)
    return 0


if __name__ == "__main__":
    sys.exit(main())
