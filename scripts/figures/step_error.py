"""Seed 000's figures from the step-error study's HDF5 results.

Usage: /usr/bin/python3 scripts/figures/step_error.py RESULTS_DIR
(scripts/figures/run calls it; run from the repository root).

Reads configs/studies/step_error_tables.yaml (which experiment made what, per
variant) and, for each experiment, the newest complete result file
RESULTS_DIR/<name>/<name>-seed*-*.h5 (what `cnclab reproduce` just wrote or
reused). Writes PNGs to RESULTS_DIR/figures/step_error/:

  fig5_loss_<variant>.png          surface-1 MSE per epoch (training, test)
  fig6_surface1_<variant>.png      predicted vs theoretical step error, with
                                   and without dropout, and |error| histograms
  fig7_surface2_<variant>.png      the same per fine-tune share (0-15 %)
  fig8_surface3_<variant>.png

Exits 3 with a note when results are missing (scripts/figures/run skips).
"""
import argparse
import glob
import os
import sys

import h5py
import matplotlib
import numpy as np
import yaml

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

MANIFEST = "configs/studies/step_error_tables.yaml"


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
        return {
            "file": path,
            "pred": np.ravel(f["test/predictions"][:]),
            "target": np.ravel(f["test/targets"][:]),
            "train_loss": np.asarray(f["history/train_loss"][:]),
            "test_loss": np.asarray(f["history/test_loss"][:]),
        }


def scatter(ax, run, title):
    t, p = run["target"], run["pred"]
    ax.scatter(t, p, s=2, alpha=0.4, linewidths=0)
    hi = max(float(t.max()), float(p.max())) if t.size else 1.0
    ax.plot([0, hi], [0, hi], "k--", lw=0.8, label="predicted = theoretical")
    ax.set_xlabel("theoretical step error (µm)")
    ax.set_ylabel("predicted step error (µm)")
    ax.set_title(f"{title}\n(n = {t.size}, max |e| = {np.abs(p - t).max():.3g} µm)", fontsize=9)
    ax.legend(fontsize=7, loc="upper left")


def histogram(ax, run, title):
    e = np.abs(run["pred"] - run["target"])
    ax.hist(e, bins=60, color="tab:orange")
    ax.set_yscale("log")
    ax.set_xlabel("|predicted − theoretical| (µm)")
    ax.set_ylabel("samples")
    ax.set_title(f"{title}: {100.0 * np.mean(e < 1.0):.2f} % below 1 µm", fontsize=9)


def panels(runs, path, suptitle):
    fig, axes = plt.subplots(2, len(runs), figsize=(3.6 * len(runs), 7), squeeze=False)
    for col, (title, run) in enumerate(runs):
        scatter(axes[0][col], run, title)
        histogram(axes[1][col], run, title)
    fig.suptitle(suptitle)
    fig.tight_layout()
    save(fig, path)


def save(fig, path):
    tmp = os.path.join(os.path.dirname(path), "." + os.path.basename(path) + ".partial.png")
    fig.savefig(tmp, dpi=110)
    plt.close(fig)
    os.replace(tmp, path)  # atomic: never a half-written PNG
    print(f"figures: wrote {path}")


def loss_curve(run, path, variant):
    fig, ax = plt.subplots(figsize=(6, 4))
    epochs = np.arange(1, run["train_loss"].size + 1)
    ax.plot(epochs, run["train_loss"], label="training loss (dropout active)")
    if np.isfinite(run["test_loss"]).any():
        ax.plot(epochs, run["test_loss"], label="test MSE")
    ax.axhline(0.001, color="k", ls=":", lw=0.8, label="paper: 0.001 after 2000 epochs")
    ax.set_yscale("log")
    ax.set_xlabel("epoch")
    ax.set_ylabel("MSE (z-score units)")
    ax.set_title(f"Fig. 5: MSE per epoch, surface 1 ({variant})")
    ax.legend(fontsize=8)
    fig.tight_layout()
    save(fig, path)


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("results", help="results folder")
    results = parser.parse_args().results
    if not os.path.exists(MANIFEST):
        print(f"step_error figures: {MANIFEST} not found", file=sys.stderr)
        return 3
    with open(MANIFEST) as f:
        manifest = yaml.safe_load(f)
    base = os.path.dirname(MANIFEST)
    out = os.path.join(results, "figures", "step_error")
    try:
        # Everything located first: either all figures or a note.
        plan = []
        for variant, v in manifest["variants"].items():
            def result(rel):
                return newest_result(results, os.path.normpath(os.path.join(base, rel)))

            plan.append((variant, result(v["surface1"]), result(v["surface1_no_dropout"]),
                         {float(k): result(f) for k, f in v["surface2"].items()},
                         {float(k): result(f) for k, f in v["surface3"].items()}))
    except Missing as e:
        print(f"step_error figures: {e}; run `cnclab reproduce experiments/step_error`",
              file=sys.stderr)
        return 3
    os.makedirs(out, exist_ok=True)
    for variant, s1, s1_nodrop, s2, s3 in plan:
        surface1 = read(s1)
        loss_curve(surface1, os.path.join(out, f"fig5_loss_{variant}.png"), variant)
        panels([("(a) with dropout", surface1), ("(b) without dropout", read(s1_nodrop))],
               os.path.join(out, f"fig6_surface1_{variant}.png"),
               f"Fig. 6: surface 1 test set ({variant})")
        for fig, surface, files in (("fig7", 2, s2), ("fig8", 3, s3)):
            runs = [(f"fine-tuned with {k:g} %", read(files[k])) for k in sorted(files)]
            panels(runs, os.path.join(out, f"{fig}_surface{surface}_{variant}.png"),
                   f"Fig. {7 if surface == 2 else 8}: surface {surface} test sets ({variant})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
