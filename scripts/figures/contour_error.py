#!/usr/bin/python3
"""Figures like seed 002's Figs. 4, 5, 8-11, 13 and 14 from the NARX study.

Usage: /usr/bin/python3 scripts/figures/contour_error.py [--format png|pdf|svg]
       [--dpi N] [--out DIR] [--no-title] [RESULTS_DIR]
(scripts/figures/run calls it from the repository root; a relative dataset
path in a result file is taken from there, else from RESULTS_DIR/..).

Reads the sweep of experiments/contour_error/training_methods.yaml
(RESULTS_DIR/contour_error_training_methods/sweep-<plan hash>/, written by
`cnclab reproduce`): of the sweep folders whose planned trials (sweep.yaml)
have all finished (a result file, or an .error note for a trial that stopped
on an error), the one finished last; in it the complete trial trained
in two stages (trainer.stages: open_loop, then closed_loop stages), with a
second try or windows (narx.yaml's default) before plain, with seed 1 (else another seed; see
pick_trial), its closed-loop validation prediction
and the dataset file it names. The contour error is predicted from that with
the Taylor estimate the C++ metric uses (studies/contour_error/narx_metrics.cpp),
and its RMS against the exact one is checked against the trial's contour_rms
metric. Writes fig04_toolpath, fig05_velocities, fig08/09_following_error_<axis>,
fig10/11_prediction_error_<axis>, fig13_contour_error and
fig14_contour_prediction_error to RESULTS_DIR/figures/contour_error/ (or
--out DIR/contour_error/; each to a temporary name, then renamed) in the
style of paper_style.py, titled with seed 002's captions.
"""
import glob
import os
import sys

import h5py
import numpy as np
import yaml
from paper_style import (ACTUAL, DOUBLE, ERROR, PREDICTED, SINGLE, Output, apply,
                         parse_arguments, plt, rasterize_large)

STUDY = "contour_error_training_methods"
MAKE = "cnclab reproduce experiments/contour_error/training_methods.yaml"
# The trial drawn: two-stage training with this weight-initialisation seed.
PREFERRED_SEED = 1
# Our contour RMS against the trial's contour_rms metric, relative.
CONTOUR_RMS_RTOL = 1e-9
# |prediction| above this (normalised units) counts as unstable, as the C++
# metrics' kStableBound (studies/contour_error/narx_metrics.hpp).
STABLE_BOUND = 10.0


class Missing(Exception):
    """Inputs not there (yet): exit 3, scripts/figures/run skips the figures."""


def text(value):
    return value.decode() if isinstance(value, bytes) else str(value)


def finished(path):
    """A trial's result file is finished when its root attribute complete is 1
    (written last, result_file.hpp); its status is then complete or failed."""
    try:
        with h5py.File(path, "r") as h:
            return int(h.attrs.get("complete", 0)) == 1
    except OSError:
        return False


def sweep_trials(sweep_dir):
    """The trial result files sweep.yaml plans, and how many of them are still
    open: neither a finished result file nor an .error note (a trial that
    stopped on an error, sweep_plan.hpp's trial_error_path)."""
    with open(os.path.join(sweep_dir, "sweep.yaml")) as f:
        plan = yaml.safe_load(f) or {}
    paths = [os.path.join(sweep_dir, "trials", f"{t['id']}.h5") for t in plan.get("trials") or []]
    open_trials = sum(1 for p in paths
                      if not finished(p) and not os.path.exists(p[:-len(".h5")] + ".error"))
    return paths, open_trials


def newest_sweep(results, study=STUDY):
    """The study's sweep-* folder whose planned trials all finished, the most
    recently finished one (newest trial file) when there are several, and
    its finished trial files."""
    root = os.path.join(results, study)
    done, notes = [], []
    for d in glob.glob(os.path.join(root, "sweep-*")):
        if not os.path.exists(os.path.join(d, "sweep.yaml")):
            continue
        paths, open_trials = sweep_trials(d)
        if open_trials or not paths:
            notes.append(f"{os.path.basename(d)}: {open_trials} of {len(paths)} trials unfinished")
            continue
        finished_paths = [p for p in paths if os.path.exists(p)]
        done.append((max(os.path.getmtime(p) for p in finished_paths or [d]), d, finished_paths))
    if not done:
        raise Missing(f"no finished sweep under {root}/sweep-*"
                      + (f" ({'; '.join(sorted(notes))})" if notes else ""))
    _, d, paths = max(done)
    return d, paths


def two_stage_seed(path):
    """(two-stage kind, seed) of a complete trial, from its resolved config:
    kind "windows" (open_loop, then closed_loop stages of which one has a
    horizon or a fallback_horizon: narx.yaml's default), "plain" (the paper
    as printed) or None."""
    with h5py.File(path, "r") as h:
        if text(h.attrs.get("status", "")) != "complete":
            return None, None
        config = yaml.safe_load(resolved_yaml(h)) or {}
    stages = (config.get("trainer") or {}).get("stages") or []
    modes = [s.get("mode") for s in stages]
    if len(modes) < 2 or modes[0] != "open_loop" or any(m != "closed_loop" for m in modes[1:]):
        return None, config.get("seed")
    windows = any(s.get("horizon", 0) or s.get("fallback_horizon", 0) for s in stages)
    return ("windows" if windows else "plain"), config.get("seed")


def resolved_yaml(h):
    """The trial's resolved config: the string dataset /config."""
    if "config" not in h:
        raise Missing(f"{h.filename}: no /config (not a cnclab result file?)")
    return text(h["config"][()])


def pick_trial(trials):
    """The two-stage trial with windows (a second try or a windowed start)
    and seed PREFERRED_SEED, else another seed, else the same for plain
    two-stage trials."""
    found = {"windows": [], "plain": []}
    for path in trials:
        kind, seed = two_stage_seed(path)
        if kind:
            found[kind].append((seed != PREFERRED_SEED, path))
    for kind in ("windows", "plain"):
        if found[kind]:
            return min(found[kind])[1]
    raise Missing("no complete two-stage trial (trainer.stages open_loop, then closed_loop)")


def read_trial(path):
    """A narx result's validation part (result_narx.hpp): predictions and
    targets (steps x networks, the dataset's normalised target units), the
    number of leading measured steps, the network axes, the split and metrics."""
    with h5py.File(path, "r") as h:
        trial = {
            "file": path,
            "axes": [text(a) for a in h["model/networks"][()]],
            "predictions": h["validation/predictions"][()],
            "targets": h["validation/targets"][()],
            "first_step": int(h["validation"].attrs["first_step"]),
            "train": h["split/train"][()],
            "validation": h["split/validation"][()],
            "dataset": text(h["dataset"].attrs["file"]),
            "metrics": {k: float(v) for k, v in h["metrics"].attrs.items() if k != "units"},
        }
    # The runner predicts the tail after the training half (sequential halves).
    half, steps = len(trial["train"]), trial["predictions"].shape[0]
    if not np.array_equal(trial["validation"], np.arange(half, half + steps)):
        sys.exit(f"contour_error.py: {path}: /split/validation is not the {steps} samples "
                 f"after the {half} training samples (split.mode sequential_halves expected)")
    trial["half"] = half
    return trial


def read_metadata(dataset_file, trial_file, results):
    """The dataset's metadata columns (physical units, data/following_error.hpp).
    A relative path is the run's: taken from the working directory, else from
    the folder holding RESULTS_DIR (where `cnclab reproduce` ran)."""
    candidates = [dataset_file]
    if not os.path.isabs(dataset_file):
        candidates.append(os.path.join(os.path.dirname(os.path.abspath(results)), dataset_file))
    found = [c for c in candidates if os.path.exists(c)]
    if not found:
        raise Missing(f"{trial_file} names the dataset {dataset_file}, which is not there "
                      f"(looked in {' and '.join(candidates)})")
    with h5py.File(found[0], "r") as d:
        names = [text(n) for n in d["metadata_names"][()]]
        return {n: d["metadata"][:, i] for i, n in enumerate(names)}


def to_physical(y, column):
    """Inverse mapminmax (following_error.hpp): min + (y + 1) (max - min) / 2,
    the range being [min, max] of the physical column over the whole run."""
    lo, hi = float(np.min(column)), float(np.max(column))
    return lo + (y + 1.0) * 0.5 * (hi - lo)


def taylor_contour_error(ref, d1, d2, actual):
    """Signed eps_c of seed 002's Taylor estimate (Eqs. 3-6: Eq. 3 with c and
    c^ of Eq. 4), per row, as motion/contour_error.cpp's taylor_contour_error
    computes it (motion/contour_error.hpp says why Eq. 4's denominator is |c|
    and Eq. 3's is 1 + kappa (c.n), not the printed forms):
      t = C'/|C'|, kappa = |C' x C''| / |C'|^3, n = +-left normal of t
      towards the turn (the sign of C' x C''), e = R - P, c = e - (e.t) t,
      c^ = c/|c| (n where c = 0),
      eps_c = -c^.e - (1/2) kappa (c^.n) (e.t)^2 / (1 + kappa (c.n)).
    ref, d1, d2, actual: (steps, 2) arrays in mm."""
    speed = np.linalg.norm(d1, axis=1)
    tangent = d1 / speed[:, None]
    z = d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]
    kappa = np.abs(z) / speed**3
    left = np.stack([-tangent[:, 1], tangent[:, 0]], axis=1)
    normal = np.where((z < 0)[:, None], -left, left)
    e = ref - actual
    et = np.sum(e * tangent, axis=1)
    c = e - et[:, None] * tangent
    c_norm = np.linalg.norm(c, axis=1)
    with np.errstate(invalid="ignore", divide="ignore"):
        c_hat = np.where((c_norm > 0)[:, None], c / c_norm[:, None], normal)
    c_hat_n = np.sum(c_hat * normal, axis=1)
    c_n = np.sum(c * normal, axis=1)
    return -np.sum(c_hat * e, axis=1) - 0.5 * kappa * c_hat_n * et**2 / (1.0 + kappa * c_n)


def validation_series(trial, meta):
    """The validation half as the figures draw it, in µm: time, e_<axis>
    (measured), e_hat_<axis> (closed-loop prediction), contour_exact and
    contour_hat (Taylor estimate from the predictions; NaN on the leading
    measured steps and when a network's closed loop is unstable), plus the
    contour RMS of contour_hat - contour_exact over the predicted steps as
    narx_metrics.cpp's contour_rms (NaN when unstable)."""
    half, first = trial["half"], trial["first_step"]
    steps = trial["predictions"].shape[0]
    k = slice(half, half + steps)
    series = {"time": meta["time"][k], "contour_exact": meta["contour_exact"][k]}
    stable = True
    for a, axis in enumerate(trial["axes"]):
        y = trial["predictions"][:, a]
        tail = y[first:]
        stable = stable and bool(np.all(np.isfinite(tail)) and np.all(np.abs(tail) <= STABLE_BOUND))
        series["e_" + axis] = to_physical(trial["targets"][:, a], meta["e_ref_" + axis])
        series["e_hat_" + axis] = to_physical(y, meta["e_ref_" + axis])
    contour_hat = np.full(steps, np.nan)
    rms = float("nan")
    if stable and {"x", "y"} <= set(trial["axes"]):
        def xy(prefix):
            return np.stack([meta[prefix + "x"][k], meta[prefix + "y"][k]], axis=1)

        ref = xy("ref_")
        e_mm = np.stack([series["e_hat_x"], series["e_hat_y"]], axis=1) / 1000.0
        # P = R - e as the C++ metric forms it (then e = R - P again inside).
        eps = taylor_contour_error(ref, xy("d1_"), xy("d2_"), ref - e_mm)
        contour_hat[first:] = np.abs(eps[first:]) * 1000.0
        diff = contour_hat[first:] - series["contour_exact"][first:]
        rms = float(np.sqrt(np.mean(diff**2)))
    series["contour_hat"] = contour_hat
    return series, rms


def check_contour_rms(trial, rms):
    """Our contour RMS against the trial's own metric: the two computations
    of one formula must agree, else the figures would not show the trial."""
    # validation.contour_rms (a narx run's metrics are of its validation
    # half); results written before metrics per split name it contour_rms.
    metrics = trial["metrics"]
    theirs = metrics.get("validation.contour_rms", metrics.get("contour_rms", float("nan")))
    if np.isnan(rms) and np.isnan(theirs):
        print("contour_rms check: both NaN (a closed loop was unstable)")
        return
    rel = abs(rms - theirs) / abs(theirs) if theirs else abs(rms - theirs)
    print(f"contour_rms check: computed {rms:.12g} µm, trial {theirs:.12g} µm, "
          f"relative difference {rel:.3g} (tolerance {CONTOUR_RMS_RTOL:g})")
    if not rel <= CONTOUR_RMS_RTOL:
        sys.exit(f"contour_error.py: {trial['file']}: predicted contour RMS {rms!r} µm differs "
                 f"from the trial's contour_rms {theirs!r} µm by {rel:.3g} relative; the Taylor "
                 "estimate here no longer matches studies/contour_error/narx_metrics.cpp")


def load(results):
    """The trial to draw, its series and the dataset metadata; exit 3 with a
    note naming the command that makes them when they are missing."""
    try:
        sweep_dir, trials = newest_sweep(results)
        trial = read_trial(pick_trial(trials))
        meta = read_metadata(trial["dataset"], trial["file"], results)
    except Missing as e:
        # Exit 3: inputs missing (scripts/figures/run skips the figure with this note).
        print(f"contour_error.py: {e}; run `{MAKE}` (with --out {results}) first",
              file=sys.stderr)
        sys.exit(3)
    print(f"contour_error.py: sweep {sweep_dir}, trial {trial['file']}, "
          f"dataset {trial['dataset']}")
    series, rms = validation_series(trial, meta)
    check_contour_rms(trial, rms)
    return series, meta


def main():
    args = parse_arguments(__doc__)
    series, meta = load(args.results)
    apply()
    out = Output(args, args.results, "contour_error")
    toolpath_figure(out, meta)
    velocity_figure(out, meta)

    tv = series["time"]
    for axis, (fig_pred, fig_err) in zip("xy", [(8, 10), (9, 11)]):
        if "e_" + axis not in series:
            continue
        e, e_hat = series["e_" + axis], series["e_hat_" + axis]
        centre = zoom_centre(tv, e)
        series_figure(out, f"fig{fig_pred:02d}_following_error_{axis}", tv,
                      [(e, dict(color=ACTUAL, label="actual")),
                       (e_hat, dict(color=PREDICTED, label="predicted"))],
                      centre, "following error (µm)",
                      f"Predicted and actual following error in the {axis.upper()} axis")
        series_figure(out, f"fig{fig_err:02d}_prediction_error_{axis}", tv,
                      [(e_hat - e, dict(color=ERROR))], centre, "prediction error (µm)",
                      f"Following error prediction error in the {axis.upper()} axis")

    if "contour_hat" in series and np.isfinite(series["contour_hat"]).any():
        c, c_hat = series["contour_exact"], series["contour_hat"]
        centre = zoom_centre(tv, c)
        # Seed 002's Fig. 13 swaps the colours: predicted blue, actual green.
        series_figure(out, "fig13_contour_error", tv,
                      [(c, dict(color=PREDICTED, label="actual")),
                       (c_hat, dict(color=ACTUAL, label="predicted"))],
                      centre, "contour error (µm)",
                      "Predicted and actual contour error for the validation set")
        series_figure(out, "fig14_contour_prediction_error", tv,
                      [(c_hat - c, dict(color=ERROR))], centre, "prediction error (µm)",
                      "Contour error prediction error for the validation set")


def toolpath_figure(out, meta):
    """Seed 002's Fig. 4: the random NURBS tool path (reference positions)."""
    fig, ax = plt.subplots(figsize=(SINGLE, SINGLE), layout="constrained")
    (line,) = ax.plot(meta["ref_x"], meta["ref_y"], lw=0.4)
    rasterize_large(line, len(meta["ref_x"]))
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    ax.set_aspect("equal")
    out.title(fig, "Randomly generated NURBS toolpath")
    out.save(fig, "fig04_toolpath")


def velocity_figure(out, meta):
    """Seed 002's Fig. 5: axial reference velocities (the NARX inputs), the
    training half, then the validation half."""
    t = meta["time"]
    half = t[len(t) // 2]
    fig, axes = plt.subplots(2, 1, figsize=(DOUBLE, 3.0), sharex=True, sharey=True,
                             layout="constrained")
    for ax, axis in zip(axes, "xy"):
        (line,) = ax.plot(t, meta["v_ref_" + axis], lw=0.3)
        rasterize_large(line, len(t))
        ax.axvline(half, color="k", ls="--", lw=0.8)
        ax.set_ylabel(f"$v_{axis}$ (mm/s)")
        ax.set_xlim(t[0], t[-1])
    for x, text_, ha in ((half, "training ", "right"), (half, " validation", "left")):
        axes[0].text(x, 1.02, text_, transform=axes[0].get_xaxis_transform(), ha=ha,
                     va="bottom", fontsize=7)
    axes[-1].set_xlabel("time (s)")
    out.title(fig, "Axial velocity profiles used as NARX network inputs")
    out.save(fig, "fig05_velocities")


# Seconds shown in the lower, zoomed panel of the time-series figures: the
# whole validation half (~86 s at 1 ms) is too dense to read, the paper's
# Figs. 8-14 show a few seconds.
ZOOM_SECONDS = 3.0


def zoom_centre(t, y):
    """Where to zoom: the time of the largest |y| (the most telling stretch)."""
    finite = np.where(np.isfinite(y), np.abs(y), -np.inf)
    return float(t[int(np.argmax(finite))])


def series_figure(out, stem, t, curves, centre, ylabel, title):
    """Upper panel: the whole series, the zoom window shaded; lower panel: the
    ZOOM_SECONDS around `centre`, y limits fitted to what it shows (one panel
    when the series is short). Double column; the whole-series lines are
    rasterised in vector output."""
    if float(t[-1] - t[0]) <= 1.5 * ZOOM_SECONDS:
        # Short (the quick profile): the whole series is readable, no zoom.
        fig, ax = plt.subplots(figsize=(DOUBLE, 2.2), layout="constrained")
        for y, style in curves:
            (line,) = ax.plot(t, y, lw=0.8, **style)
            rasterize_large(line, len(t))
        ax.set_xlim(t[0], t[-1])
        ax.set_xlabel("time (s)")
        ax.set_ylabel(ylabel)
        if any("label" in style for _, style in curves):
            ax.legend(loc="lower right", bbox_to_anchor=(1.0, 1.0), ncol=2, frameon=False,
                      borderaxespad=0.1)
        out.title(fig, title)
        out.save(fig, stem)
        return
    lo = max(float(t[0]), centre - ZOOM_SECONDS / 2)
    hi = min(float(t[-1]), lo + ZOOM_SECONDS)
    lo = max(float(t[0]), hi - ZOOM_SECONDS)
    window = (t >= lo) & (t <= hi)
    fig, (ax_all, ax_zoom) = plt.subplots(2, 1, figsize=(DOUBLE, 3.6), layout="constrained")
    for y, style in curves:
        (line,) = ax_all.plot(t, y, lw=0.3, **style)
        rasterize_large(line, len(t))
        (line,) = ax_zoom.plot(t[window], y[window], lw=0.8, **style)
        rasterize_large(line, int(window.sum()))
    ax_all.axvspan(lo, hi, color="0.5", alpha=0.25, lw=0)
    ax_all.set_xlim(t[0], t[-1])
    ax_all.set_ylabel(ylabel)
    ax_all.set_xlabel("time (s); shaded: the zoom below")
    ax_zoom.set_xlim(lo, hi)
    ax_zoom.set_xlabel("time (s)")
    ax_zoom.set_ylabel(ylabel)
    if any("label" in style for _, style in curves):
        # Above the panels: inside, it would hide the curves it names.
        ax_all.legend(*ax_zoom.get_legend_handles_labels(), loc="lower right",
                      bbox_to_anchor=(1.0, 1.0), ncol=2, frameon=False,
                      borderaxespad=0.1)
    out.title(fig, title)
    out.save(fig, stem)


if __name__ == "__main__":
    main()
