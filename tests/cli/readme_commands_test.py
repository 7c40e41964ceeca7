#!/usr/bin/env python3
"""The README's command lines checked against the CLI.

1. Every `cnclab ...` line of the README's code blocks parses: `cnclab
   --parse-only ...` (main.cpp: CLI11 parses, nothing runs) exits 0, so no
   unknown command or flag. Synopsis lines get real values for their
   placeholders (EXPERIMENT.yaml, N, K/N, [--flag], a|b); a path that does not
   exist in the sandbox becomes an empty file or folder first.
2. Every `--flag` the README names in backticks is a flag of some command
   (`cnclab --help-all`).
3. The cheap lines run for real in a sandbox (the repository's experiments/
   and configs/, a small sweep made first) on small inputs: fewer epochs,
   samples, trials and repeats; they exit 0. An example shown with its output
   (`$ cnclab ...` and the error it prints) prints that error, exit 2.
4. The README's exit-code table: every command with a missing input exits 2
   naming it, and with an unknown flag exits 2 naming the flag; the list
   below covers every command `cnclab --help` lists.

usage: readme_commands_test.py CNCLAB SOURCE_DIR
"""
import os
import pathlib
import re
import shlex
import subprocess
import sys
import tempfile

CNCLAB, SOURCE = sys.argv[1], pathlib.Path(sys.argv[2])
failures = []

# Placeholders of the synopsis lines and what stands in for them (per
# command where it differs); "{result}", "{dataset}": made by setup().
PLACEHOLDERS = {
    "EXPERIMENT.yaml": "experiments/friedman/friedman1_mlp.yaml",
    "RESULT.h5": "{result}",
    "RUN": "results/friedman1_mlp/sweep-1a2b3c4d",  # a sweep folder: runs enough to group
    "SWEEP_DIR": "results/friedman1_mlp/sweep-1a2b3c4d",
    "SWEEP_DIR/summary.h5": "results/friedman1_mlp/sweep-1a2b3c4d/summary.h5",
    "RESULTS_DIR": "results",
    "KEY": "model.dropout.keep_probability",
    "PATH": "experiments/friedman",
    "NAME": "step-error",
    "CONFIG.yaml": "experiments/friedman/friedman1_mlp.yaml",
    "FILE.nc": "groove.nc",
    "part.step": "experiments/step_error/cad_example_part.step",
    "FILE": "out.h5",
    "DATASET.h5": "{dataset}",
    "INPUT": "{dataset}",
    "OUT.h5": "predictions.h5",
    "DIR": "results",
    "N": "2",
    "K/N": "1/2",
    "K": "train",
    "key=value": "trainer.epochs=2",
    "key=v1,v2": "trainer.epochs=2,3",
}
PLACEHOLDERS_BY_COMMAND = {
    ("gcode", "CONFIG.yaml"): "experiments/trochoid/groove_table2.yaml",
    ("init", "DIR"): "new_project",
}

# Commands cheap enough to run for real (first words after cnclab); run and
# sweep only of the Friedman experiments, shrunk by shrink().
CHEAP = {"run", "validate", "show", "sweep", "compare", "status", "schema", "version", "init",
         "gcode", "dataset", "predict", "export"}


def cnclab(args, cwd, env=None):
    return subprocess.run([CNCLAB, *args], cwd=cwd, capture_output=True, text=True, env=env)


def code_block_lines(readme):
    """(line number, command text, shown output lines) of every cnclab line
    in a fenced code block; backslash continuations joined, comments cut."""
    out, block, pending, start = [], False, "", 0
    lines = readme.split("\n")
    for i, line in enumerate(lines, 1):
        if line.startswith("```"):
            block, pending = not block, ""
            continue
        if not block:
            continue
        if not pending:
            start = i
        pending += " " + line.strip() if pending else line
        if pending.rstrip().endswith("\\"):
            pending = pending.rstrip()[:-1]
            continue
        text, pending = pending.strip(), ""
        shown = []
        if text.startswith("$ "):
            text = text[2:]
            for follow in lines[i:]:
                if not follow.strip() or follow.startswith(("$ ", "```")):
                    break
                shown.append(follow)
        text = re.sub(r"\s+#\s.*$", "", text)
        for part in text.split("&&"):
            part = part.strip()
            if part.startswith("cnclab "):
                out.append((start, part, shown))
    return out


def expand(words):
    """A synopsis line's words with its placeholders filled in."""
    command = words[1] if len(words) > 1 else ""
    argv = []
    for w in words:
        if w.startswith("["):
            w = w[1:]
        if w.endswith("]") and not re.search(r"=\[.*\]$", w):
            w = w[:-1]
        if w in ("...", ""):
            continue
        if "|" in w:
            w = w.split("|")[0]
        w = PLACEHOLDERS_BY_COMMAND.get((command, w), PLACEHOLDERS.get(w, w))
        argv.append(w)
    return argv


def command_words(text):
    words = shlex.split(text)
    if ">" in words:
        words = words[:words.index(">")]
    return expand(words)


def fill(argv, made):
    """Values made by setup() in; ~ as the sandbox's home."""
    return [os.path.expanduser(a.format(**made) if a.startswith("{") else a) for a in argv]


def shrink(argv):
    """Small inputs: 2 epochs, 200 samples, an 8-unit network, 2 trials, 1 repeat."""
    out, skip = [], False
    for i, a in enumerate(argv):
        if skip:
            skip = False
            continue
        if re.fullmatch(r"trainer\.epochs=\d+", a):
            a = "trainer.epochs=2"
        if a in ("--trials", "--repeats", "--jobs") and i + 1 < len(argv):
            out += [a, "1" if a == "--repeats" else "2"]
            skip = True
            continue
        out.append(a)
    if not any(a.startswith("trainer.epochs=") for a in out):
        out.append("trainer.epochs=2")
    return out + ["dataset.options.samples=200", "model.hidden=[8]"]


def cheap(argv, sandbox):
    if argv[1] not in CHEAP or "--slurm" in argv:
        return False
    if argv[1] in ("run", "sweep") and not argv[2].startswith("experiments/friedman/"):
        return False
    if argv[1] == "dataset" and argv[2] == "generate" and "friedman" not in argv[3]:
        return False  # seed 000's surface: not small
    if argv[1] == "init":
        return True  # its folder is made
    paths = [a for a in argv[2:] if "/" in a and "=" not in a and "*" not in a]
    return all((sandbox / p).exists() for p in paths if not p.startswith("-"))


def make_placeholders(argv, sandbox):
    """Paths the parse check needs that the sandbox lacks: empty files
    (names with an extension) or folders."""
    fixed = []
    for a in argv:
        if "/" in a and "=" not in a and not a.startswith(("-", "~")):
            a = a.replace("*", "x")
            p = sandbox / a
            if not p.exists():
                if p.suffix:
                    p.parent.mkdir(parents=True, exist_ok=True)
                    p.touch()
                else:
                    p.mkdir(parents=True, exist_ok=True)
        fixed.append(a)
    return fixed


def setup(sandbox):
    for name in ("experiments", "configs"):
        (sandbox / name).symlink_to(SOURCE / name)
    small = ["trainer.epochs=2", "dataset.options.samples=200", "model.hidden=[8]", "--jobs", "2",
             "--quiet"]
    for args in (["model.dropout.keep_probability=0.9,1.0", "--repeats", "2", "--dir",
                  "results/friedman1_mlp/sweep-1a2b3c4d"],
                 ["trainer.learning_rate=1e-3,1e-2", "--dir", "results/friedman1_mlp/lr-sweep"]):
        r = cnclab(["sweep", "experiments/friedman/friedman1_mlp.yaml", *small, *args], sandbox)
        assert r.returncode == 0, r.stderr
    r = cnclab(["dataset", "generate", "experiments/friedman/friedman1_mlp.yaml",
                "dataset.options.samples=200", "--out", "datasets/friedman1.h5", "-q"], sandbox)
    assert r.returncode == 0, r.stderr
    results = sorted((sandbox / "results/friedman1_mlp").glob("friedman1_mlp-seed*.h5"))
    assert results, "the setup sweeps published no result"
    return {"result": str(results[0].relative_to(sandbox)), "dataset": "datasets/friedman1.h5"}


def check_runs(lines, sandbox, made, env):
    ran = 0
    for number, text, shown in lines:
        argv = fill(command_words(text), made)
        if not cheap(argv, sandbox):
            continue
        if argv[1] in ("run", "sweep") and not shown:
            argv = shrink(argv)
        r = cnclab(argv[1:], sandbox, env)
        ran += 1
        if shown:
            expected = shown[0].split("...")[0]
            if r.returncode != 2 or not r.stderr.startswith(expected):
                failures.append(f"README:{number}: `{text}` printed\n  {r.stderr.strip()}\n"
                                f"  (exit {r.returncode}), the README shows\n  {shown[0]}")
        elif r.returncode != 0:
            failures.append(f"README:{number}: `{' '.join(argv)}` exit {r.returncode}: "
                            f"{r.stderr.strip()[-400:]}")
    return ran


def check_parses(lines, sandbox, made, env):
    for number, text, _ in lines:
        argv = make_placeholders(fill(command_words(text), made), sandbox)
        r = cnclab(["--parse-only", *argv[1:]], sandbox, env)
        if r.returncode != 0:
            failures.append(f"README:{number}: `{text}` does not parse "
                            f"(`cnclab --parse-only {' '.join(argv[1:])}`, exit "
                            f"{r.returncode}): {r.stderr.strip()}")


# Flags of other tools the README names: sbatch's, scripts'.
OTHER_TOOLS = {"--dependency": "sbatch", "--parsable": "sbatch", "--requeue": "sbatch",
               "--in-process": "scripts/bench_cad_step_error", "--no-title": "scripts/figures/run"}


def check_flags(readme, sandbox):
    """Every --flag in backticks is some command's flag."""
    help_all = cnclab(["--help-all"], sandbox).stdout
    known = set(re.findall(r"(--[a-z][a-z0-9-]*)", help_all)) | set(OTHER_TOOLS)
    unknown = {}
    for span in re.findall(r"`([^`\n]+)`", readme):
        for flag in re.findall(r"(?:^|\s)(--[a-z][a-z0-9-]*)", span):
            if flag not in known:
                unknown.setdefault(flag, span)
    for flag, span in unknown.items():
        failures.append(f"README names `{flag}` (in `{span}`), which no command has")


# Every command: (words, valid arguments, arguments naming a missing input
# or None when it takes none).
def command_table(made):
    exp, sweep_dir = "experiments/friedman/friedman1_mlp.yaml", PLACEHOLDERS["SWEEP_DIR"]
    return [
        (["run"], [exp], ["missing.yaml"]),
        (["validate"], [exp], ["missing.yaml"]),
        (["show"], [made["result"]], ["missing.h5"]),
        (["reproduce"], [exp], ["missing.yaml"]),
        (["compare"], [made["result"], made["result"]], ["missing.h5", made["result"]]),
        (["runs"], [], ["missing_dir"]),
        (["gc"], [], ["missing_dir"]),
        (["report"], [made["result"], "-o", "r.html"], ["missing.h5", "-o", "r.html"]),
        (["sweep"], [exp], ["missing.yaml"]),
        (["sweep", "merge"], [sweep_dir], ["missing_dir"]),
        (["status"], [sweep_dir], ["missing_dir"]),
        (["tables"], [], ["step-error", "--results", "missing_dir"]),
        (["gcode"], ["trochoid", "experiments/trochoid/groove_table2.yaml", "-o", "g.nc"],
         ["trochoid", "missing.yaml", "-o", "g.nc"]),
        (["schema"], [], None),
        (["version"], [], None),
        (["init"], ["fresh_project"], None),
        (["dataset", "generate"], [exp], ["missing.yaml"]),
        (["dataset", "show"], [made["dataset"]], ["missing.h5"]),
        (["predict"], [made["result"], made["dataset"], "-o", "p.h5"],
         ["missing.h5", made["dataset"], "-o", "p.h5"]),
        (["export"], [made["result"], "--format", "c", "-o", "exported"],
         ["missing.h5", "--format", "c", "-o", "exported"]),
        (["surface", "show"], ["experiments/step_error/cad_example_part.step"], ["missing.step"]),
        (["surface", "export"], ["configs/surfaces/surface1.yaml", "--out", "x.step"],
         ["missing.yaml", "--out", "x.step"]),
        (["surface", "example-part"], ["--out", "p.step"],
         ["--freeform", "missing.yaml", "--out", "p.step"]),
    ]


def check_exit_codes(sandbox, made):
    table = command_table(made)
    listed = set(re.findall(r"^\s{2}([a-z][a-z-]*)\s", cnclab(["--help"], sandbox).stdout, re.M))
    missing = listed - {words[0] for words, _, _ in table}
    if missing:
        failures.append(f"commands without an exit-code check here: {sorted(missing)}")
    for words, valid, absent in table:
        name = " ".join(words)
        r = cnclab([*words, *valid, "--no-such-flag"], sandbox)
        if r.returncode != 2 or "--no-such-flag" not in r.stderr:
            failures.append(f"cnclab {name} --no-such-flag: exit {r.returncode} "
                            f"(2 expected, naming the flag): {r.stderr.strip()}")
        if absent is None:
            continue
        r = cnclab([*words, *absent], sandbox)
        missing_name = next(a for a in absent if a.startswith("missing"))
        if r.returncode != 2 or missing_name not in r.stderr:
            failures.append(f"cnclab {name} {' '.join(absent)}: exit {r.returncode} "
                            f"(2 expected, naming {missing_name}): {r.stderr.strip()}")


readme = (SOURCE / "README.md").read_text()
lines = code_block_lines(readme)
assert len(lines) > 40, f"only {len(lines)} command lines found"
with tempfile.TemporaryDirectory() as tmp:
    sandbox = pathlib.Path(tmp)
    os.environ["HOME"] = str(sandbox / "home")  # `cnclab init ~/studies/mill` (expanduser)
    env = dict(os.environ)
    made = setup(sandbox)
    ran = check_runs(lines, sandbox, made, env)
    check_exit_codes(sandbox, made)
    check_flags(readme, sandbox)
    check_parses(lines, sandbox, made, env)

if failures:
    print("\n".join(failures))
    sys.exit(1)
print(f"ok: {len(lines)} README command lines parse, {ran} of them ran")
