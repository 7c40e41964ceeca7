"""Smoke test of scripts/figures: on small result files this
test writes itself (the layouts the scripts read: step-error results named by
configs/studies/step_error_tables.yaml, a contour-error sweep with a
two-stage NARX trial and its following-error dataset), `scripts/figures/run`
draws every figure as PDF and as SVG, each a file of that format, with text
kept as text and the large point sets rasterised inside the vector file.
The two formats run in parallel; the test takes ~15 s.

Usage: /usr/bin/python3 figures_smoke_test.py SOURCE_DIR
"""
import os
import shutil
import subprocess
import sys
import tempfile

import h5py
import numpy as np
import yaml

failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


def step_error_results(source, results, rng):
    """One complete result per experiment the manifest names: test
    predictions near the targets, a loss history and the resolved config's
    dropout. Surfaces 2/3 have 2500 test samples (above paper_style.LARGE:
    drawn as hexbin density), the rest 400 (a plain scatter)."""
    import step_error  # scripts/figures, on sys.path

    with open(step_error.MANIFEST) as f:
        manifest = yaml.safe_load(f)
    base = os.path.dirname(step_error.MANIFEST)
    files = set()
    for v in manifest["variants"].values():
        for key in ("surface1", "surface1_no_dropout", "surface2", "surface3", "table2"):
            entry = v.get(key, {})
            files.update(entry.values() if isinstance(entry, dict) else [entry])
    names = {step_error.experiment_name(os.path.normpath(os.path.join(base, f))) for f in files}
    for name in sorted(names):
        n = 2500 if "surface2" in name or "surface3" in name else 400
        target = rng.uniform(0.01, 13.0, n)
        keep = 1.0 if "no_dropout" in name or "tuned_surface1" in name else 0.5
        os.makedirs(os.path.join(results, name))
        with h5py.File(os.path.join(results, name, f"{name}-seed1-0000abcd.h5"), "w") as h:
            h.attrs["status"] = "complete"
            h["config"] = yaml.safe_dump({"model": {"dropout": {"keep_probability": keep}}})
            h["test/targets"] = target[:, None]
            h["test/predictions"] = (target + rng.normal(0, 0.2, n))[:, None]
            h["history/train_loss"] = np.geomspace(1.0, 0.01, 50)
            h["history/test_loss"] = np.geomspace(1.2, 0.02, 50)
    return names


def following_error_dataset(path, steps):
    """A circle at constant speed (C' and C'' in closed form), 1 ms samples,
    following errors of 100 µm amplitude: the metadata columns the contour
    figures read (data/following_error.hpp's names, physical units)."""
    t = np.arange(steps) * 1e-3
    r, w = 50.0, 2.0
    c, s = np.cos(w * t), np.sin(w * t)
    cols = {
        "time": t, "ref_x": r * c, "ref_y": r * s,
        "v_ref_x": -r * w * s, "v_ref_y": r * w * c,
        "d1_x": -r * w * s, "d1_y": r * w * c, "d2_x": -r * w * w * c, "d2_y": -r * w * w * s,
        "e_ref_x": 100.0 * np.sin(3 * t), "e_ref_y": 80.0 * np.cos(5 * t),
    }
    cols["contour_exact"] = np.abs(cols["e_ref_x"] * c + cols["e_ref_y"] * s)
    with h5py.File(path, "w") as d:
        d["metadata_names"] = [n.encode() for n in cols]
        d["metadata"] = np.stack(list(cols.values()), axis=1)
    return cols


def stage(group, mode, termination, epochs, rng):
    g = group.create_group(mode == "open_loop" and "stage0" or "stage1")
    g.attrs["mode"], g.attrs["termination"] = mode, termination
    g["epoch"] = np.arange(1, epochs + 1)
    for name in ("sse", "mu", "curvature", "alpha", "beta", "gamma", "gradient"):
        g[name] = np.geomspace(1.0, 1e-2, epochs) * rng.uniform(0.5, 2.0)
        g.attrs["initial_" + name] = 2.0


def contour_error_results(results, root, rng, steps=10000):
    """The training-methods sweep with one finished two-stage trial (seed 1,
    networks x and y; y's closed-loop stage stopped at mu_max) whose dataset
    path is relative to the folder above RESULTS_DIR, and its contour_rms
    metric computed the way contour_error.py checks it."""
    import contour_error  # scripts/figures

    os.makedirs(os.path.join(root, "datasets"))
    cols = following_error_dataset(os.path.join(root, "datasets", "smoke_fe.h5"), steps)
    sweep = os.path.join(results, contour_error.STUDY, "sweep-0000smok")
    os.makedirs(os.path.join(sweep, "trials"))
    with open(os.path.join(sweep, "sweep.yaml"), "w") as f:
        yaml.safe_dump({"trials": [{"id": "twostage"}]}, f)
    half = steps // 2
    norm = np.stack([2 * (cols[k] - cols[k].min()) / np.ptp(cols[k]) - 1
                     for k in ("e_ref_x", "e_ref_y")], axis=1)
    path = os.path.join(sweep, "trials", "twostage.h5")
    with h5py.File(path, "w") as h:
        h.attrs["status"], h.attrs["complete"] = "complete", 1
        h["config"] = yaml.safe_dump({
            "seed": 1, "model": {"hidden": 4, "input_delays": 2},
            "trainer": {"stages": [{"mode": "open_loop"}, {"mode": "closed_loop"}]}})
        h["model/networks"] = [b"x", b"y"]
        h["validation/targets"] = norm[half:]
        h["validation/predictions"] = norm[half:] + rng.normal(0, 0.01, (steps - half, 2))
        h["validation"].attrs["first_step"] = 2
        h["split/train"] = np.arange(half)
        h["split/validation"] = np.arange(half, steps)
        h.create_group("dataset").attrs["file"] = "datasets/smoke_fe.h5"
        h.create_group("metrics")
        for axis, last in (("x", "max_epochs"), ("y", "mu_max")):
            stage(h.create_group(f"history/{axis}"), "open_loop", "max_epochs", 12, rng)
            stage(h[f"history/{axis}"], "closed_loop", last, 8, rng)
    trial = contour_error.read_trial(path)
    meta = contour_error.read_metadata(trial["dataset"], path, results)
    _, rms = contour_error.validation_series(trial, meta)
    with h5py.File(path, "r+") as h:
        h["metrics"].attrs["validation.contour_rms"] = rms


EXPECTED = {
    "contour_error": ["fig04_toolpath", "fig05_velocities", "fig08_following_error_x",
                      "fig09_following_error_y", "fig10_prediction_error_x",
                      "fig11_prediction_error_y", "fig13_contour_error",
                      "fig14_contour_prediction_error"],
    "narx_training": ["closed_loop_stage"],
    "feedrate": ["feedrate_eps10um", "feedrate_eps5um"],
}
MAGIC = {"pdf": b"%PDF", "svg": b"<?xml"}


def feedrate_ticks(results, rng, ticks=1500):
    """The per-tick file of the contour-error feedrate job (feedrate_job.hpp):
    per tolerance and method time, feed, simulated and (for the predictor's
    plans) predicted contour error [mm]."""
    folder = os.path.join(results, "contour_error_feedrate")
    os.makedirs(folder)
    with h5py.File(os.path.join(folder, "contour_error_feedrate-0123abcd-ticks.h5"), "w") as f:
        for label, scale in (("eps10um", 1.0), ("eps5um", 0.5)):
            for method, n in (("unconstrained", ticks // 2), ("constrained", ticks),
                              ("uniform", ticks), ("constant", ticks)):
                g = f.create_group(f"{label}/{method}")
                t = np.arange(n) * 1e-3
                g["time"] = t
                g["feed"] = 200 * np.sin(np.pi * t / t[-1]) ** 2
                g["simulated"] = scale * 8e-3 * np.abs(np.sin(9 * t)) + 1e-4 * rng.random(n)
                if method in ("unconstrained", "constrained"):
                    g["predicted"] = scale * 7e-3 * np.abs(np.sin(9 * t))


def main():
    source = os.path.abspath(sys.argv[1])
    sys.path.insert(0, os.path.join(source, "scripts", "figures"))
    tmp = tempfile.mkdtemp(prefix="figures-smoke-")
    try:
        rng = np.random.default_rng(7)
        results = os.path.join(tmp, "results")
        os.makedirs(results)
        step_error_results(source, results, rng)
        contour_error_results(results, tmp, rng)
        feedrate_ticks(results, rng)
        with open(os.path.join(source, "configs/studies/step_error_tables.yaml")) as f:
            variants = list(yaml.safe_load(f)["variants"])
        expected = dict(EXPECTED, step_error=[
            f"{fig}_{v}" for v in variants
            for fig in ("fig5_loss", "fig6_surface1", "fig7_surface2", "fig8_surface3")])
        runs = {fmt: subprocess.Popen(
            [os.path.join(source, "scripts/figures/run"), "--format", fmt, "--dpi", "100",
             "--out", os.path.join(tmp, fmt), results],
            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True) for fmt in MAGIC}
        for fmt, proc in runs.items():
            out = proc.communicate(timeout=120)[0]
            check(proc.returncode == 0 and "skipped" not in out and "FAILED" not in out,
                  f"run --format {fmt}: exit {proc.returncode}, nothing skipped or failed"
                  + ("" if proc.returncode == 0 else "\n" + out))
            for topic, stems in expected.items():
                for stem in stems:
                    path = os.path.join(tmp, fmt, topic, f"{stem}.{fmt}")
                    head = open(path, "rb").read(5) if os.path.exists(path) else b""
                    check(head.startswith(MAGIC[fmt]), f"{topic}/{stem}.{fmt} written")
            leftovers = [n for _, _, files in os.walk(os.path.join(tmp, fmt))
                         for n in files if ".partial." in n]
            check(not leftovers, f"{fmt}: no temporary files left: {leftovers}")
        # SVG: text stays text (svg.fonttype none); the 2500-point hexbins and
        # the 5000-step series (5 s: two panels) are embedded raster images,
        # not vector points.
        svg = os.path.join(tmp, "svg")
        fig7 = open(os.path.join(svg, "step_error", f"fig7_surface2_{variants[0]}.svg")).read()
        check("<text" in fig7 and fig7.count("<image") >= 5,
              f"fig7 SVG: text as text, hexbins rasterised ({fig7.count('<image')} images)")
        fig8 = open(os.path.join(svg, "contour_error", "fig08_following_error_x.svg")).read()
        check("<image" in fig8, "fig08 SVG: the whole series rasterised")
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    if failures:
        print(f"{len(failures)} check(s) failed")
        return 1
    print("figures smoke test: all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
