"""An installed cnclab with a project folder, the repository out of reach:
`cmake --install BUILD --prefix P` into a temporary
prefix, then, from another temporary folder with an environment that names
neither the source nor the build tree:

- `cnclab version` names P/share/cnclab as its shared files;
- `cnclab init proj` makes the project (a second init is exit 2 unless
  --force, which keeps every existing file);
- the starters validate with their includes from the installed configs, and
  a config of the same name in the project's configs/ overrides one;
- a missing include lists every place looked, the project's and the
  installed ones, and none in the repository;
- `cnclab reproduce --quick` in the project runs every starter: exit 0, one
  result per training starter (its config read back with h5py names the
  project, not the repository) and the G-code job's program, whose point
  table matches the paper's Table 3 file beside it in the share folder, and
  no note about a paper table it did not print (the starters are not the
  studies).

Usage: /usr/bin/python3 install_test.py BUILD_DIR SOURCE_DIR
"""
import glob
import os
import shutil
import subprocess
import sys
import tempfile

import h5py
import yaml

BUILD, SOURCE = (os.path.realpath(p) for p in sys.argv[1:3])
STARTERS = ["step_error/surface1.yaml", "contour_error/narx.yaml", "five_axis/ik_x.yaml"]
JOB = "five_axis/trochoid_groove.yaml"

failures = []


def check(ok, message):
    if not ok:
        failures.append(message)
        print("FAIL:", message)


def outside_repository(path):
    real = os.path.realpath(path)
    return all(os.path.commonpath([real, tree]) != tree for tree in (SOURCE, BUILD))


def run(args, cwd, env, expect=0):
    p = subprocess.run(args, cwd=cwd, env=env, capture_output=True, text=True, timeout=600)
    text = p.stdout + p.stderr
    if expect is not None and p.returncode != expect:
        print(text[-6000:])
        raise SystemExit(f"{' '.join(args)} in {cwd}: exit {p.returncode}, expected {expect}")
    # Nothing the installed cnclab prints may point into the repository.
    for tree in (SOURCE, BUILD):
        check(tree not in text, f"{' '.join(args)}: output names {tree}:\n{text[-2000:]}")
    return p


def main():
    top = tempfile.mkdtemp(prefix="cnclab_install_test_")
    try:
        prefix, work = os.path.join(top, "prefix"), os.path.join(top, "work")
        os.makedirs(work)
        if not outside_repository(top):
            raise SystemExit(f"{top}: the temporary folder lies inside the repository")
        subprocess.run(["cmake", "--install", BUILD, "--prefix", prefix], check=True,
                       stdout=subprocess.DEVNULL)
        share = os.path.join(prefix, "share", "cnclab")
        for rel in ["configs/trainers/lm.yaml", "configs/surfaces/surface1.yaml",
                    "configs/machines/biaxial_router.yaml", "configs/studies/ik_table5.yaml",
                    "results/reference/ik_table5.yaml", "results/reference/trochoid_table3.csv",
                    "experiments/step_error/surface1.yaml", "scripts/figures/step_error.py",
                    "templates/project/README.md"] + \
                   [f"templates/project/experiments/{s}" for s in STARTERS + [JOB]]:
            check(os.path.isfile(os.path.join(share, rel)), f"not installed: {rel}")
        for rel in ["bin/cnclab", "share/cnclab/scripts/figures/run"]:
            check(os.access(os.path.join(prefix, rel), os.X_OK), f"not executable: {rel}")

        # The repository out of reach: a minimal environment.
        env = {"PATH": os.path.join(prefix, "bin") + ":/usr/bin:/bin", "HOME": top,
               "LANG": "C.UTF-8", "TMPDIR": top}
        cnclab = os.path.join(prefix, "bin", "cnclab")
        version = run([cnclab, "version"], work, env).stdout
        check(f"{share} (installed, next to the executable)" in version, version)

        proj = os.path.join(work, "proj")
        out = run([cnclab, "init", "proj"], work, env).stdout
        for rel in ["README.md", ".gitignore", "configs/README.md"] + \
                   [f"experiments/{s}" for s in STARTERS + [JOB]]:
            check(os.path.isfile(os.path.join(proj, rel)), f"init made no {rel}")
            check(rel in out, f"init does not list {rel}: {out}")
        for folder in ["datasets", "results"]:
            check(os.path.isdir(os.path.join(proj, folder)), f"init made no {folder}/")
        again = run([cnclab, "init", "proj"], work, env, expect=2)
        check("is not empty" in again.stderr and "--force" in again.stderr, again.stderr)
        with open(os.path.join(proj, "README.md"), "a") as f:
            f.write("my notes\n")
        forced = run([cnclab, "init", "proj", "--force"], work, env).stdout
        check("README.md (exists: kept)" in forced, forced)
        with open(os.path.join(proj, "README.md")) as f:
            check(f.read().endswith("my notes\n"), "init --force overwrote README.md")

        # Includes resolve to the installed configs; the project's own first.
        for s in STARTERS:
            run([cnclab, "validate", f"experiments/{s}"], proj, env)
        ik = run([cnclab, "validate", "experiments/five_axis/ik_x.yaml"], proj, env).stdout
        check("batch_size: 1" in ik, "installed sgdm_ik_table5.yaml not used:\n" + ik)
        own = os.path.join(proj, "configs", "trainers", "sgdm_ik_table5.yaml")
        os.makedirs(os.path.dirname(own))
        with open(own, "w") as f:
            f.write("trainer: {type: sgdm, batch_size: 7, epochs: 10}\n")
        ik = run([cnclab, "validate", "experiments/five_axis/ik_x.yaml"], proj, env).stdout
        check("batch_size: 7" in ik, "the project's configs/ did not override:\n" + ik)
        os.remove(own)

        with open(os.path.join(work, "missing.yaml"), "w") as f:
            f.write("include: configs/trainers/no_such_trainer.yaml\n")
        missing = run([cnclab, "validate", "missing.yaml"], work, env, expect=2).stderr
        for place in [os.path.join(work, "configs/trainers/no_such_trainer.yaml"),
                      os.path.join(share, "configs/trainers/no_such_trainer.yaml")]:
            check(place in missing, f"{place} not in the error:\n{missing}")

        # The quick reproduce of the starters.
        rep = run([cnclab, "reproduce", "--quick", "--quiet"], proj, env)
        print(rep.stdout[-3000:])
        results = os.path.join(proj, "results", "quick")
        for s in STARTERS:
            with open(os.path.join(proj, "experiments", s)) as f:
                name = yaml.safe_load(f)["name"]
            files = glob.glob(os.path.join(results, name, "*.h5"))
            check(len(files) == 1, f"{name}: {files}")
            for file in files:
                with h5py.File(file, "r") as h5:
                    status = h5["provenance"].attrs.get("status")
                    status = status.decode() if isinstance(status, bytes) else status
                    check(status == "complete", f"{file}: status {status}")
        nc = glob.glob(os.path.join(results, "starter_trochoid_groove", "*.nc"))
        check(len(nc) == 1, f"G-code program: {nc}")
        check("Table 3" in rep.stdout, "the G-code report compares no Table 3:\n" + rep.stdout)
        # The starters are none of the paper studies' files: no table, and no
        # note about a table not printed.
        check("not printed" not in rep.stdout, "notes about studies not here:\n" + rep.stdout)
        check(outside_repository(proj), "project inside the repository")
    finally:
        shutil.rmtree(top, ignore_errors=True)
    if failures:
        raise SystemExit(f"{len(failures)} failure(s)")
    print("install test: ok")


main()
