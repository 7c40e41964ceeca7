"""Seed 000's figures from the step-error study's HDF5 results.

Usage: /usr/bin/python3 scripts/figures/step_error.py [--format png|pdf|svg]
       [--dpi N] [--out DIR] [--no-title] [RESULTS_DIR]
(scripts/figures/run calls it).

Reads configs/studies/step_error_tables.yaml (which experiment made what, per
variant) and, for each experiment, the newest complete result file
RESULTS_DIR/<name>/<name>-seed*-*.h5 (what `cnclab reproduce` just wrote or
reused). Writes to RESULTS_DIR/figures/step_error/ (or --out DIR/step_error/),
in the style of paper_style.py:

  fig5_loss_<variant>.png          surface-1 MSE per epoch (training, test)
  fig6_surface1_<variant>.png      predicted vs theoretical step error (density),
                                   (a) with and (b) without dropout, and |error|
                                   histograms on one shared log axis
  fig7_surface2_<variant>.png      the same per test set 1-5 (fine-tune share,
  fig8_surface3_<variant>.png      the paper's extract proportion 0-15 %)

<variant> is the manifest's (paper, tuned); titles use the paper's terms.
A variant without dropout (tuned) draws Fig. 6a from its Table 2 p = 0.5 run.

Exits 3 with a note when results are missing (scripts/figures/run skips).
"""
import glob
import os
import sys

import h5py
import numpy as np
import yaml
from matplotlib.ticker import LogLocator, NullFormatter
from paper_style import (DOUBLE, SINGLE, Output, apply, density, parse_arguments, plt,
                         share_clim)

# The repository's manifest, wherever the script is run from.
REPOSITORY = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
MANIFEST = os.path.join(REPOSITORY, "configs", "studies", "step_error_tables.yaml")


class Missing(Exception):
    pass


def experiment_name(path):
    """The `name:` of an experiment file, following `include:` if needed."""
    with open(path) as f:
        doc = yaml.safe_load(f) or {}
    if "name" in doc:
        return str(doc["name"])
    includes = doc.get("include", [])
    for inc in [includes] if isinstance(includes, str) else includes:
        candidate = os.path.join(os.path.dirname(path), inc)
        if os.path.exists(candidate):
            try:
                return experiment_name(candidate)
            except Missing:
                pass
    raise Missing(f"{path}: no name")


def newest_result(results, experiment_file):
    if not os.path.exists(experiment_file):
        raise Missing(f"{experiment_file}: experiment file not found")
    name = experiment_name(experiment_file)
    best = None
    for path in glob.glob(os.path.join(results, name, f"{name}-seed*-*.h5")):
        try:
            with h5py.File(path, "r") as f:
                if f.attrs.get("status", b"") not in ("complete", b"complete"):
                    continue
        except OSError:
            continue
        if best is None or os.path.getmtime(path) > os.path.getmtime(best):
            best = path
    if best is None:
        raise Missing(f"no complete result of {name} in {results}/{name}/")
    return best


def read(path):
    with h5py.File(path, "r") as f:
        config = yaml.safe_load(text(f["config"][()])) if "config" in f else {}
        return {
            "file": path,
            "pred": np.ravel(f["test/predictions"][:]),
            "target": np.ravel(f["test/targets"][:]),
            "train_loss": np.asarray(f["history/train_loss"][:]),
            "test_loss": np.asarray(f["history/test_loss"][:]),
            "keep": keep_probability(config or {}),
        }


def text(value):
    return value.decode() if isinstance(value, bytes) else str(value)


def keep_probability(config):
    """The dropout keep probability p of a result's resolved config (1: none)."""
    model = config.get("model") or {}
    return float((model.get("dropout") or {}).get("keep_probability", 1.0))


def dropout_label(run):
    return f"With Dropout (p = {run['keep']:g})" if run["keep"] < 1 else "Without Dropout"


def error_stats(run):
    e = np.abs(run["pred"] - run["target"])
    return f"n = {e.size}\nmax {e.max():.3g} µm\n{100.0 * np.mean(e < 1.0):.1f} % < 1 µm"


def panels(out, runs, stem, title):
    """Seed 000's Figs. 6-8: per test set, predicted against theoretical step
    error (top; hexbin density, one colour scale) and the |error| histogram
    (bottom). Panels share their axes: the histograms one log |e| axis and
    one y axis (percent of the test set), so the panels compare at a glance."""
    n = len(runs)
    # Two panels (Fig. 6) would be 3.3 in squares at full width: narrower.
    size, ratios = ((DOUBLE, 4.0), [1.2, 1]) if n > 2 else ((5.0, 4.6), [1.3, 1])
    fig, (tops, bottoms) = plt.subplots(2, n, figsize=size, squeeze=False, layout="constrained",
                                        gridspec_kw={"height_ratios": ratios})
    for row in (tops, bottoms):
        for ax in row[1:]:
            ax.sharex(row[0])
            ax.sharey(row[0])
            ax.tick_params(labelleft=False)
    hi = max(max(float(r["target"].max()), float(r["pred"].max())) for _, r in runs)
    lo = min(min(float(r["target"].min()), float(r["pred"].min()), 0.0) for _, r in runs)
    bins = error_bins(runs)
    hexbins = []
    for top, bottom, (label, run) in zip(tops, bottoms, runs):
        hexbins.append(density(top, run["target"], run["pred"], (lo, hi, lo, hi), gridsize=60))
        top.plot([lo, hi], [lo, hi], color="k", ls="--", lw=0.6)
        top.set_xlim(lo, hi)
        top.set_ylim(lo, hi)
        top.set_aspect("equal", adjustable="box")
        top.set_title(label)
        e = np.clip(np.abs(run["pred"] - run["target"]), bins[0], bins[-1])
        bottom.hist(e, bins=bins, weights=np.full(e.size, 100.0 / e.size), color="tab:orange")
        bottom.axvline(1.0, color="k", ls=":", lw=0.8)
        bottom.text(0.03, 0.97, error_stats(run), transform=bottom.transAxes, va="top",
                    fontsize=6, bbox=dict(boxstyle="square,pad=0.1", fc="white", ec="none"))
    bottoms[0].set_xscale("log")
    bottoms[0].xaxis.set_major_locator(LogLocator(base=100.0))
    bottoms[0].xaxis.set_minor_locator(LogLocator(base=10.0, numticks=20))
    bottoms[0].xaxis.set_minor_formatter(NullFormatter())
    bottoms[0].set_ylim(0, 1.45 * bottoms[0].get_ylim()[1])  # room for the numbers
    tops[0].set_ylabel("predicted (µm)")
    bottoms[0].set_ylabel("share of test set (%)")
    # One x label per row: under the middle panel (n odd); for n even under
    # each top panel and once below the figure (too long for each bottom one).
    for ax in ([tops[n // 2]] if n % 2 else tops):
        ax.set_xlabel("theoretical step error (µm)")
    error_label = "|predicted − theoretical| (µm); dotted: 1 µm"
    if n % 2:
        bottoms[n // 2].set_xlabel(error_label)
    else:
        fig.supxlabel(error_label, fontsize=plt.rcParams["axes.labelsize"])
    share_clim(fig, hexbins, tops.tolist())
    out.title(fig, title)
    out.save(fig, stem)


def error_bins(runs, per_decade=12):
    """Log-spaced |error| bins shared by all panels: from the decade below
    the 0.5th percentile of the smallest errors (at least 1e-4 µm; smaller
    errors land in the first bin) to the largest error."""
    errors = [np.abs(r["pred"] - r["target"]) for _, r in runs]
    small = min(float(np.percentile(e, 0.5)) for e in errors)
    lo = 10.0 ** np.floor(np.log10(max(small, 1e-4)))
    hi = 10.0 ** np.ceil(np.log10(max(max(float(e.max()) for e in errors), 1.01 * lo)))
    return np.logspace(np.log10(lo), np.log10(hi),
                       int(round(per_decade * np.log10(hi / lo))) + 1)


def loss_curve(out, run, stem):
    """Seed 000's Fig. 5: MSE per epoch on surface 1 (single column)."""
    fig, ax = plt.subplots(figsize=(SINGLE, 2.5), layout="constrained")
    epochs = np.arange(1, run["train_loss"].size + 1)
    train = "training" + (f" (Dropout p = {run['keep']:g} active)" if run["keep"] < 1 else "")
    # Training on top: the noisier test curve would hide it.
    ax.plot(epochs, run["train_loss"], label=train, zorder=3)
    if np.isfinite(run["test_loss"]).any():
        ax.plot(epochs, run["test_loss"], label="test", lw=0.7)
    ax.axhline(0.001, color="k", ls=":", lw=0.8, label="0.001: the paper after 2000 epochs")
    ax.set_yscale("log")
    ax.set_xlabel("epoch")
    ax.set_ylabel("MSE (z-score units)")
    out.title(fig, "MSE loss, Surface 1")
    ax.legend(loc="upper right")
    out.save(fig, stem)


def main():
    args = parse_arguments(__doc__)
    results = args.results
    if not os.path.exists(MANIFEST):
        print(f"step_error figures: {MANIFEST} not found", file=sys.stderr)
        return 3
    with open(MANIFEST) as f:
        manifest = yaml.safe_load(f)
    base = os.path.dirname(MANIFEST)
    try:
        # Everything located first: either all figures or a note.
        plan = []
        for variant, v in manifest["variants"].items():
            def result(rel):
                return newest_result(results, os.path.normpath(os.path.join(base, rel)))

            with_dropout = [result(v["surface1"])]
            if "table2" in v and 0.5 in {float(k) for k in v["table2"]}:
                p05 = {float(k): f for k, f in v["table2"].items()}[0.5]
                try:
                    with_dropout.append(result(p05))
                except Missing:
                    # Needed only when surface 1 itself has no dropout (checked
                    # below): the paper's per-sample SGDM may diverge at p = 0.5.
                    pass
            plan.append((variant, with_dropout, result(v["surface1_no_dropout"]),
                         {float(k): result(f) for k, f in v["surface2"].items()},
                         {float(k): result(f) for k, f in v["surface3"].items()}))
    except Missing as e:
        print(f"step_error figures: {e}; run `cnclab reproduce experiments/step_error`",
              file=sys.stderr)
        return 3
    apply()
    out = Output(args, results, "step_error")
    for variant, with_dropout, s1_nodrop, s2, s3 in plan:
        surface1 = read(with_dropout[0])
        loss_curve(out, surface1, f"fig5_loss_{variant}")
        # Fig. 6a is a network trained with dropout: surface1 itself, or (a
        # variant without dropout, as tuned) its table2 p = 0.5 sibling.
        dropout_run = surface1
        if surface1["keep"] >= 1:
            if len(with_dropout) < 2:
                print(f"step_error figures: fig6_surface1_{variant} not drawn: no complete "
                      "result of its table2 p = 0.5 run (a network trained with dropout)",
                      file=sys.stderr)
                dropout_run = None
            else:
                dropout_run = read(with_dropout[1])
        no_dropout = read(s1_nodrop)
        if dropout_run is not None:
            panels(out, [(f"(a) {dropout_label(dropout_run)}", dropout_run),
                         (f"(b) {dropout_label(no_dropout)}", no_dropout)],
                   f"fig6_surface1_{variant}",
                   "Step error between theoretical and predicted values, Surface 1")
        for fig, surface, files in (("fig7", 2, s2), ("fig8", 3, s3)):
            # The paper's Tables 4/5: test set i uses the i-th extract proportion.
            runs = [(f"({chr(ord('a') + i)}) Test set {i + 1}, {k:g} %", read(files[k]))
                    for i, k in enumerate(sorted(files))]
            panels(out, runs, f"{fig}_surface{surface}_{variant}",
                   f"Step error between theoretical and predicted values, Surface {surface}"
                   " (% of its samples used for training)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
