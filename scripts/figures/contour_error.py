#!/usr/bin/python3
"""Figures like seed 002's Figs. 4, 5, 8-11, 13 and 14 from the NARX study.

Usage: /usr/bin/python3 scripts/figures/contour_error.py [RESULTS_DIR]

Reads the newest complete result of experiments/contour_error/training_methods.yaml
(RESULTS_DIR/contour_error_training_methods/*.h5, written by `cnclab reproduce`),
its validation series (first run: two-stage, seed 1) and the dataset it names,
and writes PNGs to RESULTS_DIR/figures/contour_error/ (each written to a
temporary name, then renamed).
"""
import argparse
import glob
import os
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def newest_result(results):
    files = [f for f in glob.glob(os.path.join(results, "contour_error_training_methods", "*.h5"))
             if not os.path.basename(f).startswith(".")]
    for f in sorted(files, key=os.path.getmtime, reverse=True):
        with h5py.File(f, "r") as h:
            if h.attrs.get("complete", 0) == 1:
                return f
    # Exit 3: inputs missing (scripts/figures/run skips the figure with this note).
    print(f"contour_error.py: no complete result under {results}/contour_error_training_methods;"
          " run `cnclab reproduce experiments/contour_error` first", file=sys.stderr)
    sys.exit(3)


def save(fig, out_dir, name):
    path = os.path.join(out_dir, name)
    tmp = os.path.join(out_dir, "." + name + ".partial.png")
    fig.savefig(tmp, dpi=120, bbox_inches="tight")
    plt.close(fig)
    os.replace(tmp, path)
    print("wrote", path)


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("results", nargs="?", default="results", help="results folder")
    results = parser.parse_args().results
    out_dir = os.path.join(results, "figures", "contour_error")
    os.makedirs(out_dir, exist_ok=True)
    result = newest_result(results)
    with h5py.File(result, "r") as h:
        names = [n.decode() for n in h["series_names"][()]]
        series = {n: h["series"][:, i] for i, n in enumerate(names)}
        dataset_file = h["dataset"].attrs["file"]
        if isinstance(dataset_file, bytes):
            dataset_file = dataset_file.decode()
    with h5py.File(dataset_file, "r") as d:
        meta_names = [n.decode() for n in d["metadata_names"][()]]
        meta = {n: d["metadata"][:, i] for i, n in enumerate(meta_names)}

    # Fig. 4: the random NURBS tool path (reference positions).
    fig, ax = plt.subplots(figsize=(6, 6))
    ax.plot(meta["ref_x"], meta["ref_y"], lw=0.4)
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    ax.set_aspect("equal")
    ax.set_title("Random NURBS tool path (cf. seed 002 Fig. 4)")
    save(fig, out_dir, "fig04_toolpath.png")

    # Fig. 5: axis reference velocities, training and validation halves.
    t = meta["time"]
    fig, axes = plt.subplots(2, 1, figsize=(10, 5), sharex=True)
    half = t[len(t) // 2]
    for ax, axis in zip(axes, "xy"):
        ax.plot(t, meta["v_ref_" + axis], lw=0.3)
        ax.axvline(half, color="k", ls="--", lw=0.8)
        ax.set_ylabel(f"v_{axis} [mm/s]")
    axes[-1].set_xlabel("time [s] (dashed: training | validation)")
    axes[0].set_title("Axial reference velocities, NARX inputs (cf. Fig. 5)")
    save(fig, out_dir, "fig05_velocities.png")

    tv = series["time"]
    for axis, (fig_pred, fig_err) in zip("xy", [(8, 10), (9, 11)]):
        if "e_" + axis not in series:
            continue
        e, e_hat = series["e_" + axis], series["e_hat_" + axis]
        centre = zoom_centre(tv, e)
        series_figure(out_dir, f"fig{fig_pred:02d}_following_error_{axis}.png", tv,
                      [(e, dict(color="tab:blue", label="actual (simulated)")),
                       (e_hat, dict(color="tab:green", label="predicted (closed loop)"))],
                      centre, f"following error {axis.upper()} [µm]",
                      f"Predicted and actual following error, {axis.upper()} axis "
                      f"(cf. Fig. {fig_pred})")
        series_figure(out_dir, f"fig{fig_err:02d}_prediction_error_{axis}.png", tv,
                      [(e_hat - e, dict(color="tab:red"))], centre, "prediction error [µm]",
                      f"Following error prediction error, {axis.upper()} axis "
                      f"(cf. Fig. {fig_err})")

    if "contour_hat" in series and np.isfinite(series["contour_hat"]).any():
        c, c_hat = series["contour_exact"], series["contour_hat"]
        centre = zoom_centre(tv, c)
        series_figure(out_dir, "fig13_contour_error.png", tv,
                      [(c, dict(color="tab:green", label="actual (exact, simulated)")),
                       (c_hat, dict(color="tab:blue", label="predicted (Taylor, NARX)"))],
                      centre, "contour error [µm]",
                      "Predicted and actual contour error, validation set (cf. Fig. 13)")
        series_figure(out_dir, "fig14_contour_prediction_error.png", tv,
                      [(c_hat - c, dict(color="tab:red"))], centre, "prediction error [µm]",
                      "Contour error prediction error, validation set (cf. Fig. 14)")


# Seconds shown in the lower, zoomed panel of the time-series figures: the
# whole validation half (~86 s at 1 ms) is too dense to read, the paper's
# Figs. 8-14 show a few seconds.
ZOOM_SECONDS = 3.0


def zoom_centre(t, y):
    """Where to zoom: the time of the largest |y| (the most telling stretch)."""
    finite = np.where(np.isfinite(y), np.abs(y), -np.inf)
    return float(t[int(np.argmax(finite))])


def series_figure(out_dir, name, t, curves, centre, ylabel, title):
    """Upper panel: the whole series, the zoom window shaded; lower panel: the
    ZOOM_SECONDS around `centre`, y limits fitted to what it shows."""
    lo = max(float(t[0]), centre - ZOOM_SECONDS / 2)
    hi = min(float(t[-1]), lo + ZOOM_SECONDS)
    lo = max(float(t[0]), hi - ZOOM_SECONDS)
    window = (t >= lo) & (t <= hi)
    fig, (ax_all, ax_zoom) = plt.subplots(2, 1, figsize=(10, 6.5))
    for y, style in curves:
        ax_all.plot(t, y, lw=0.3, **style)
        ax_zoom.plot(t[window], y[window], lw=0.9, **style)
    ax_all.axvspan(lo, hi, color="0.5", alpha=0.25, lw=0)
    ax_all.set_ylabel(ylabel)
    ax_all.set_title(title)
    ax_zoom.set_xlim(lo, hi)
    ax_zoom.set_xlabel("time [s]")
    ax_zoom.set_ylabel(ylabel)
    ax_zoom.set_title(f"zoom: {lo:.1f}-{hi:.1f} s (shaded above)", fontsize=9)
    if any("label" in style for _, style in curves):
        ax_zoom.legend(loc="upper right")
    fig.tight_layout()
    save(fig, out_dir, name)


if __name__ == "__main__":
    main()
