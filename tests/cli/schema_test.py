#!/usr/bin/env python3
"""`cnclab schema` checked by an independent validator (python3-jsonschema,
Draft 2020-12).

The schema describes one experiment file as written and as the reader sees
it after `include:` is merged (src/cnclab/experiment/experiment_schema.hpp).
So every file under experiments/ is validated as written (what an editor
checks; the keys an include may supply are required only of a file without
`include:`) and in its resolved form (`cnclab validate FILE`, and with
--profile quick where the file, its includes or a sweep's experiment define
it (read here from the YAML): the config a result stores), each against the
whole schema and against its kind's (`cnclab schema --kind K`). A file that
does not define quick must refuse it (exit 2, "unknown profile"). Misspelt
keys, at the top and in nested sections, must fail, also in a file with
`include:`.

usage: schema_test.py CNCLAB SOURCE_DIR
"""
import copy
import json
import pathlib
import re
import subprocess
import sys

import jsonschema
import yaml

CNCLAB, SOURCE = sys.argv[1], pathlib.Path(sys.argv[2])

failures = []


class Yaml12Loader(yaml.SafeLoader):
    """YAML 1.2 floats (PyYAML's 1.1 rules read 1e-05 as a string)."""


Yaml12Loader.yaml_implicit_resolvers = {
    k: [r for r in v if r[0] != "tag:yaml.org,2002:float"]
    for k, v in yaml.SafeLoader.yaml_implicit_resolvers.items()}
Yaml12Loader.add_implicit_resolver(
    "tag:yaml.org,2002:float",
    re.compile(r"^(?:[-+]?(?:\.[0-9]+|[0-9]+(?:\.[0-9]*)?)(?:[eE][-+]?[0-9]+)?"
               r"|[-+]?\.(?:inf|Inf|INF)|\.(?:nan|NaN|NAN))$"),
    list("-+0123456789."))


def load(text):
    return yaml.load(text, Loader=Yaml12Loader)


def run(*args):
    return subprocess.run([CNCLAB, *args], cwd=SOURCE, capture_output=True, text=True)


def schema_of(*args):
    r = run("schema", *args)
    assert r.returncode == 0, r.stderr
    s = json.loads(r.stdout)
    jsonschema.Draft202012Validator.check_schema(s)
    return jsonschema.Draft202012Validator(s)


def errors(validator, document):
    return [f"{'/'.join(map(str, e.absolute_path)) or '<root>'}: {e.message}"
            for e in validator.iter_errors(document)]


def check(validator, document, what):
    found = errors(validator, document)
    if found:
        failures.append(f"{what}:\n  " + "\n  ".join(found[:5]))


def resolved(path, profile):
    # --full: the config itself (validate abbreviates large arrays for people).
    args = ["validate", "--full", str(path)] + (["--profile", profile] if profile else [])
    r = run(*args)
    if r.returncode != 0:
        failures.append(f"cnclab {' '.join(args)} failed: {r.stderr.strip()}")
        return None
    return load(r.stdout)


def config_path(naming, name):
    """An include or experiment name: beside the naming file, else from the
    source root (configs/...)."""
    beside = naming.parent / name
    return beside if beside.is_file() else SOURCE / name


def declared_profiles(path):
    """The profile names a file defines: its `profiles:`, its includes', and
    for a `kind: sweep` file its experiment's (whose trials load with it)."""
    raw = load(path.read_text()) or {}
    names = set(raw.get("profiles") or {})
    includes = raw.get("include") or []
    for name in [includes] if isinstance(includes, str) else includes:
        names |= declared_profiles(config_path(path, name))
    if raw.get("kind") == "sweep" and "experiment" in raw:
        names |= declared_profiles(config_path(path, raw["experiment"]))
    return names


def refuses_profile(path, profile):
    r = run("validate", str(path), "--profile", profile)
    if r.returncode != 2 or f"unknown profile '{profile}'" not in r.stderr:
        failures.append(f"{path} defines no profile {profile}, yet validate --profile {profile}: "
                        f"exit {r.returncode}, {r.stderr.strip()}")


validator = schema_of()
kind_validators = {}
checked = 0
refused = 0
kinds = set()
train_example = None
for path in sorted((SOURCE / "experiments").rglob("*.yaml")):
    rel = path.relative_to(SOURCE)
    raw = load(path.read_text())
    kind = raw.get("kind", "train")
    kinds.add(kind)
    if kind not in kind_validators:
        kind_validators[kind] = schema_of("--kind", kind)
    docs = [(raw, "as written")]
    for profile in ("", "quick"):
        if profile and profile not in declared_profiles(path):
            refuses_profile(rel, profile)
            refused += 1
            continue
        doc = resolved(rel, profile)
        if doc is not None:
            docs.append((doc, f"resolved{' --profile ' + profile if profile else ''}"))
    for doc, what in docs:
        check(validator, doc, f"{rel} {what}")
        check(kind_validators[kind], doc, f"{rel} {what}, against --kind {kind}")
        checked += 1
    if kind == "train" and train_example is None:
        example = resolved(rel, "")
        # A job may include another (kind comes from the included file).
        if example is not None and example.get("model", {}).get("type") == "mlp":
            train_example = example

assert checked > 150, f"only {checked} documents checked"
assert refused < checked / 4, f"{refused} files refuse --profile quick"
assert {"train", "sweep", "gcode"} <= kinds, kinds
assert train_example is not None

# A file with include: may leave out what its includes supply; one without
# may not. A misspelt key fails in both, wherever it is (sections whose type
# or generator the include sets included).
included = {"include": "base.yaml", "name": "x"}
check(validator, included, "a file with include: and a name only")
if not errors(validator, {"name": "x"}):
    failures.append("a file without include: and without dataset, model, trainer passes")
if not errors(validator, {"include": "x.yaml", "kind": "sweep", "name": "x", "job": 2}):
    failures.append("a misspelt key in a kind: sweep file with include: passes")
for path, where, mutate in [
    ("experiments/step_error/cad_example.yaml", "top level",
     lambda d: d.__setitem__("descripton", "x")),
    ("experiments/step_error/cad_example.yaml", "dataset.options without a generator",
     lambda d: d["dataset"]["options"].__setitem__("surfac", {"face": 1})),
    ("experiments/step_error/cad_example.yaml", "dataset without a generator",
     lambda d: d["dataset"].__setitem__("option", {})),
    ("experiments/friedman/friedman1_finetune.yaml", "trainer without a type",
     lambda d: d["trainer"].__setitem__("learning_rte", 0.1)),
    ("experiments/step_error/table2_keep_0.6.yaml", "model without a type",
     lambda d: d["model"].__setitem__("hiden", [3])),
    ("experiments/step_error/surface2_ft15_keep.yaml", "init_from",
     lambda d: d["init_from"].__setitem__("normalser", "keep")),
]:
    raw = load((SOURCE / path).read_text())
    assert "include" in raw, path
    check(validator, raw, f"{path} as written")
    bad = copy.deepcopy(raw)
    mutate(bad)
    if not errors(validator, bad):
        failures.append(f"a misspelt key in {where} passes the schema in {path} (with include:)")

# Misspelt keys fail, wherever they are.
for where, mutate in [
    ("top level", lambda d: d.__setitem__("trainr", d.pop("trainer"))),
    ("trainer", lambda d: d["trainer"].__setitem__("learning_rte", 0.1)),
    ("model", lambda d: d["model"].__setitem__("hiden", [3])),
    ("model.init.weights", lambda d: d["model"]["init"]["weights"].__setitem__("sd", 1)),
    ("dataset.options", lambda d: d["dataset"]["options"].__setitem__("sample", 10)),
    ("split", lambda d: d["split"].__setitem__("trian", 0.5)),
]:
    bad = copy.deepcopy(train_example)
    mutate(bad)
    if not errors(validator, bad):
        failures.append(f"a misspelt key in {where} passes the schema")

# Values out of range, not in an enum, or keys where they do not apply fail.
for where, mutate in [
    ("trainer.momentum = 1", lambda d: d["trainer"].__setitem__("momentum", 1.0)),
    ("model.hidden_activation = relux",
     lambda d: d["model"].__setitem__("hidden_activation", "relux")),
    ("normalisation.input_range without minmax",
     lambda d: d["normalisation"].update(inputs="zscore", input_range=[0, 1])),
    ("name with a slash", lambda d: d.__setitem__("name", "a/b")),
]:
    bad = copy.deepcopy(train_example)
    mutate(bad)
    if not errors(validator, bad):
        failures.append(f"{where} passes the schema")

# model.type narx (experiments/contour_error/narx.yaml): trainer.stages, the
# split and normalisation it needs and its sequence metrics.
narx_example = resolved("experiments/contour_error/narx.yaml", "")
assert narx_example is not None and narx_example["model"]["type"] == "narx"
for where, mutate in [
    ("a misspelt key in a stage", lambda d: d["trainer"]["stages"][0].__setitem__("epoch", 5)),
    ("max_fail in a trainbr stage",
     lambda d: d["trainer"]["stages"][0].update(type="trainbr", max_fail=6)),
    ("a stage mode closed", lambda d: d["trainer"]["stages"][0].__setitem__("mode", "closed")),
    ("a misspelt narx model key", lambda d: d["model"].__setitem__("input_delay", 4)),
    ("an mlp key in a narx model", lambda d: d["model"].__setitem__("hidden_activation", "tanh")),
    ("trainer.type beside trainer.stages", lambda d: d["trainer"].__setitem__("type", "trainbr")),
    ("narx without trainer.stages", lambda d: d.__setitem__("trainer", {"type": "trainbr"})),
    ("narx with split.mode random", lambda d: d.__setitem__("split", {"mode": "random"})),
    ("split.train with sequential_halves", lambda d: d["split"].__setitem__("train", 0.5)),
    ("narx with zscore inputs", lambda d: d["normalisation"].__setitem__("inputs", "zscore")),
    ("narx with a regression metric", lambda d: d.__setitem__("metrics", ["mse"])),
]:
    bad = copy.deepcopy(narx_example)
    mutate(bad)
    if not errors(validator, bad):
        failures.append(f"{where} passes the schema")
for where, mutate in [
    ("trainer.stages with an mlp",
     lambda d: d["trainer"].__setitem__("stages", [{"mode": "open_loop", "type": "lm"}])),
    ("a sequence metric with an mlp",
     lambda d: d.__setitem__("metrics", [narx_example["metrics"][0]])),
]:
    bad = copy.deepcopy(train_example)
    mutate(bad)
    if not errors(validator, bad):
        failures.append(f"{where} passes the schema")

# The job kinds (gcode, step_error_timing, sweep) and the machine map reject
# misspelt keys too.
for path, where, mutate in [
    ("experiments/ik_search/search_x.yaml", "kind sweep",
     lambda d: d.__setitem__("job", 2)),
    ("experiments/ik_search/search_x.yaml", "kind sweep, sweep block",
     lambda d: d["sweep"].__setitem__("repeat", 2)),
    ("experiments/ik_search/search_x.yaml", "kind sweep, objective mode",
     lambda d: d["sweep"]["objective"].__setitem__("mode", "minimum")),
    ("experiments/contour_error/narx.yaml", "a machine map",
     lambda d: d["dataset"]["options"].__setitem__("machine", {"axes": {"x": {"backlsh": 0.01}}})),
    ("experiments/trochoid/groove_table2.yaml", "gcode program",
     lambda d: d["program"].__setitem__("feeed", 1)),
    ("experiments/trochoid/groove_table2.yaml", "gcode entry mode spiral",
     lambda d: d["entry"].__setitem__("mode", "spiral")),
    ("experiments/step_error/table8_timing.yaml", "step_error_timing iterative",
     lambda d: d["iterative"].__setitem__("max_pass", 3)),
]:
    job = resolved(path, "")
    assert job is not None, path
    check(validator, job, path)
    bad = copy.deepcopy(job)
    mutate(bad)
    if not errors(validator, bad):
        failures.append(f"{where} passes the schema")

# A training experiment's sweep block: declared keys, an open parameters map.
swept = copy.deepcopy(train_example)
swept["sweep"] = {"repeats": 2, "objective": {"metric": "rmse", "mode": "min"},
                  "parameters": {"trainer.learning_rate": [0.1, 0.2], "model.hidden": "[3],[5]"}}
check(validator, swept, "a train file with a sweep block")
swept["sweep"]["repeat"] = 2
if not errors(validator, swept):
    failures.append("a misspelt key in a train file's sweep block passes the schema")

# A machine is a file name or a map of declared keys.
narx_machine = copy.deepcopy(narx_example)
narx_machine["dataset"]["options"]["machine"] = {"timing": {"integration_step": 2.5e-5},
                                                 "axes": {"y": {"backlash": 0.01}}}
check(validator, narx_machine, "narx with a machine map")
narx_machine["dataset"]["options"]["machine"] = "configs/machines/biaxial_router.yaml"
check(validator, narx_machine, "narx with a machine file")

# --kind gives one kind's schema; an unknown kind is a usage error.
check(schema_of("--kind", "train"), train_example, "train example against --kind train")
if run("schema", "--kind", "trian").returncode != 2:
    failures.append("cnclab schema --kind trian does not exit 2")

# The README's key table ("An experiment, key by key") and the declarations
# agree: every key it lists is declared, every declared top-level key and
# section key is listed.
def properties(schema):
    """The properties of a schema, with those its if/then alternatives add
    (a key's own schema first: a then may repeat it with requirements only)."""
    props = dict(schema.get("properties", {}))
    for case in schema.get("allOf", []):
        for key, sub in case.get("then", {}).get("properties", {}).items():
            props.setdefault(key, sub)
    return props


def declared(schema, dotted):
    for part in dotted.split("."):
        props = properties(schema)
        if part not in props:
            return False
        schema = props[part]
    return True


readme = (SOURCE / "README.md").read_text().split("## An experiment, key by key", 1)[1]
readme = readme.split("\n## ", 1)[0]
listed = []
for row in readme.splitlines():
    if not row.startswith("| `"):
        continue
    previous = ""
    for key in re.findall(r"`([a-z0-9_.]+)`", row.split("|")[1]):
        if key.startswith(".") and previous:  # `.validation_count` after `split.train_count`
            key = previous.rsplit(".", 1)[0] + key
        listed.append(key)
        previous = key
train = json.loads(run("schema", "--kind", "train").stdout)
for key in listed:
    if not declared(train, key):
        failures.append(f"README key table lists {key}, which is not declared")
for key, sub in properties(train).items():
    if not any(k == key or k.startswith(key + ".") for k in listed):
        failures.append(f"declared key {key} is missing from the README key table")
    for child in properties(sub):
        dotted = f"{key}.{child}"
        if key not in ("trainer", "dataset", "model", "split", "normalisation", "init_from"):
            continue
        if not any(k == dotted or k.startswith(dotted + ".") for k in listed):
            failures.append(f"declared key {dotted} is missing from the README key table")

if failures:
    print("\n".join(failures))
    sys.exit(1)
print(f"ok: {checked} documents valid, misspelt keys rejected")
