#!/usr/bin/python3
"""`cnclab sweep --method tpe` end to end, read back with h5py and Optuna.

Checks: a TPE study with a pruner runs to its count of complete or pruned
trials; pruned trials keep their history (fewer epochs than configured,
status "pruned") and are excluded from the ranking (recomputed here from the
complete trials with numpy); summary.h5 holds the importance layout (group
importance, strings parameter, doubles value of the same length, descending,
attribute evaluator = "fanova"); the journal read by Optuna itself lists the
same trials and states as the summary; running again with more trials
continues the same study without retraining; a Python without Optuna is exit
2 naming python3-optuna while grid search still works; a misspelt sampler
option is exit 2 naming it, and sampler options on a grid are refused.

Usage: model_search_test.py CNCLAB SOURCE_DIR
"""
import os
import subprocess
import sys
import tempfile
import time
import warnings

import h5py
import numpy as np

warnings.simplefilter("ignore")
import optuna  # noqa: E402
from optuna.storages import JournalFileStorage, JournalStorage  # noqa: E402

cnclab, source = sys.argv[1], sys.argv[2]
experiment = os.path.join(source, "experiments/friedman/friedman1_mlp.yaml")
failures = []


def text(v):
    """An HDF5 string attribute as str (h5py gives bytes for fixed-length strings)."""
    return v.decode() if isinstance(v, (bytes, np.bytes_)) else str(v)


def check(ok, what):
    if not ok:
        failures.append(what)
        print("FAIL", what)


def run(args, env=None, cwd=None):
    p = subprocess.run([cnclab] + args, cwd=cwd, env=env, capture_output=True, text=True,
                       timeout=900)
    return p.returncode, p.stdout, p.stderr


def sweep_args(trials, extra=()):
    return ["sweep", experiment, "trainer.epochs=8", "dataset.options.samples=300",
            "model.hidden=[8]", "trainer.learning_rate=log_uniform(1e-4,3e-1)",
            "model.dropout.keep_probability=uniform(0.5,1.0)", "description=choice(a,b)",
            "sweep.pruner={name: median, n_startup_trials: 3, n_warmup_steps: 2}",
            "--method", "tpe", "--trials", str(trials), "--jobs", "1", "--sweep-seed", "3",
            "--data-dir", "data", "--dir", "study", "--quiet"] + list(extra)


with tempfile.TemporaryDirectory() as work:
    os.chdir(work)
    code, out, err = run(sweep_args(8))
    check(code == 0, "tpe sweep exit 0 (got %d): %s %s" % (code, out[-2000:], err[-2000:]))
    with h5py.File("study/summary.h5", "r") as f:
        check(text(f.attrs["method"]) == "tpe", "method recorded")
        status = [s.decode() for s in f["trials/status"][:]]
        done = sum(s in ("complete", "pruned") for s in status)
        check(done == 8, "8 complete or pruned trials (got %s)" % status)
        check("pruned" in status, "the pruner pruned some trial (got %s)" % status)
        check(int(f.attrs["pruned"]) == status.count("pruned"), "pruned count attribute")
        # Pruned trials keep their history: fewer epochs than configured.
        for s, rf in zip(status, f["trials/result_file"][:]):
            with h5py.File(os.path.join("study", rf.decode()), "r") as r:
                check(text(r.attrs["status"]) == s, "result status %s" % s)
                epochs = len(r["history/epoch"][:]) if "history/epoch" in r \
                    else None
                if s == "pruned" and epochs is not None:
                    check(epochs < 8, "a pruned trial stopped early (%d epochs)" % epochs)
        # Ranking from the complete trials only, recomputed here.
        metric = text(f.attrs["objective_metric"])
        rmse = f["trials/metrics/" + metric][:]
        point = f["trials/point"][:]
        means = {}
        for p in set(point):
            vals = [rmse[i] for i in range(len(point)) if point[i] == p and status[i] == "complete"]
            if vals:
                means[p] = np.mean(vals)
        expected = sorted(means, key=lambda p: means[p])
        ranked = [p for p in f["points/point"][:] if p in means]
        check(ranked == expected, "ranking by complete trials: %s vs %s" % (ranked, expected))
        best = text(f.attrs["best_trial"])
        ids = [s.decode() for s in f["trials/id"][:]]
        check(status[ids.index(best)] == "complete", "the best trial is complete")
        # Importance layout.
        g = f["importance"]
        check(text(g.attrs["evaluator"]) == "fanova", "importance evaluator fanova")
        names = [s.decode() for s in g["parameter"][:]]
        values = g["value"][:]
        check(g["value"].dtype == np.float64 and len(names) == len(values) == 3,
              "importance: 3 parameters and doubles")
        check(all(values[i] >= values[i + 1] for i in range(len(values) - 1)),
              "importance sorted descending")
    # Optuna itself reads the same study from the journal.
    study = optuna.load_study(study_name="cnclab",
                              storage=JournalStorage(JournalFileStorage("study/study.journal")))
    states = [t.state.name for t in study.trials]
    check(states.count("COMPLETE") + states.count("PRUNED") == 8, "journal: 8 finished trials")
    check(states.count("PRUNED") == status.count("pruned"), "journal and summary agree on pruned")
    numbers = [t.number for t in study.trials]
    check(len(numbers) == len(set(numbers)), "no trial number twice")
    inodes = {p: os.stat(os.path.join("study/trials", p)).st_ino
              for p in os.listdir("study/trials") if p.endswith(".h5")}

    # Again with more trials: the same study continues, nothing retrained.
    code, out, err = run(sweep_args(10))
    check(code == 0, "continued sweep exit 0: %s %s" % (out[-1500:], err[-1500:]))
    study = optuna.load_study(study_name="cnclab",
                              storage=JournalStorage(JournalFileStorage("study/study.journal")))
    finished = [t for t in study.trials if t.state.name in ("COMPLETE", "PRUNED")]
    check(len(finished) == 10, "continued to 10 trials (got %d)" % len(finished))
    # The continued trials are new points, not the first run's drawn again.
    points = {tuple(sorted(t.params.items())) for t in finished}
    check(len(points) == 10, "10 different points (got %d)" % len(points))
    for p, ino in inodes.items():
        check(os.stat(os.path.join("study/trials", p)).st_ino == ino, "trial %s kept" % p)

    # Without Optuna: model-based methods are exit 2 naming the package; grid works.
    with open("python-without-site", "w") as f:
        f.write("#!/bin/sh\nexec /usr/bin/python3 -S \"$@\"\n")
    os.chmod("python-without-site", 0o755)
    env = dict(os.environ, CNCLAB_PYTHON=os.path.abspath("python-without-site"))
    code, out, err = run(sweep_args(2)[:-3] + ["--dir", "other", "--quiet"], env=env)
    check(code == 2 and "python3-optuna" in err, "no optuna: exit 2 naming python3-optuna "
          "(got %d: %s)" % (code, err[-500:]))
    code, out, err = run(["sweep", experiment, "trainer.epochs=2", "dataset.options.samples=300",
                          "model.hidden=[8]", "trainer.learning_rate=1e-3,1e-2",
                          "--data-dir", "data", "--dir", "grid", "--quiet"], env=env)
    check(code == 0, "grid without optuna exit 0 (got %d: %s)" % (code, err[-500:]))

    # Sampler options: a misspelt one is exit 2 naming it, before any trial;
    # on a grid (no sampler) exit 2 as well.
    code, out, err = run(sweep_args(2)[:-3] + ["sweep.sampler={multivariat: true}",
                                               "--dir", "misspelt", "--quiet"])
    no_trial = not os.path.isdir("misspelt/trials") or not os.listdir("misspelt/trials")
    check(code == 2 and "multivariat" in err and no_trial,
          "misspelt sampler option: exit 2 naming it, no trial (got %d: %s)" % (code, err[-500:]))
    code, out, err = run(["sweep", experiment, "trainer.learning_rate=1e-3,1e-2",
                          "sweep.sampler={multivariate: true}", "--data-dir", "data",
                          "--dir", "grid-sampler", "--quiet"])
    check(code == 2 and "model-based" in err,
          "sampler options on a grid: exit 2 (got %d: %s)" % (code, err[-500:]))

    # Two workers on one study (as two Slurm array tasks), one killed with
    # SIGKILL while it trains: the other ends, a restarted worker fails the
    # dead worker's trial (its holder pid has ended) and completes the study;
    # no trial number twice.
    worker = [cnclab, "sweep", experiment, "trainer.epochs=300", "dataset.options.samples=1500",
              "model.hidden=[32,16]", "trainer.learning_rate=log_uniform(1e-4,3e-1)",
              "model.dropout.keep_probability=uniform(0.5,1.0)", "--method", "tpe",
              "--trials", "6", "--jobs", "1", "--data-dir", "data", "--dir", "shared", "--quiet"]
    a = subprocess.Popen(worker, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    b = subprocess.Popen(worker, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                         env=dict(os.environ, SLURM_ARRAY_TASK_ID="1"))
    deadline = time.time() + 300
    while time.time() < deadline:  # until b holds a running trial
        time.sleep(0.5)
        if not os.path.exists("shared/study.journal"):
            continue
        s = optuna.load_study(study_name="cnclab",
                              storage=JournalStorage(JournalFileStorage("shared/study.journal")))
        if any(t.state.name == "RUNNING" and t.user_attrs.get("cnclab_pid") == b.pid
               for t in s.trials):
            break
    b.kill()
    b.wait()
    a.wait(timeout=600)
    code, out, err = run(worker[1:])
    check(code == 0, "restarted worker completes the study (got %d: %s)" % (code, err[-800:]))
    s = optuna.load_study(study_name="cnclab",
                          storage=JournalStorage(JournalFileStorage("shared/study.journal")))
    numbers = [t.number for t in s.trials]
    check(len(numbers) == len(set(numbers)), "shared study: no trial number twice")
    finished = [t for t in s.trials if t.state.name in ("COMPLETE", "PRUNED")]
    check(len(finished) == 6, "shared study: 6 finished trials (got %d)" % len(finished))
    check(not any(t.state.name == "RUNNING" for t in s.trials), "shared study: none left running")
    check(any(t.state.name == "FAIL" and t.user_attrs.get("cnclab_pid") == b.pid
              for t in s.trials), "the killed worker's trial was failed")

print("%d failure(s)" % len(failures))
sys.exit(1 if failures else 0)
