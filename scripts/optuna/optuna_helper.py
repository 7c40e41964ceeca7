#!/usr/bin/python3
"""The Optuna side of a model-based `cnclab sweep` (methods tpe, cmaes, nsga2, qmc).

One process per sweep worker. It reads one JSON object per line on stdin and
answers each with one JSON object per line on stdout: {"ok": true, ...} or
{"ok": false, "error": "..."}. A malformed or unknown message gets an error
answer and the helper goes on; end of input ends it (exit 0).

The study lives in Optuna's JournalFileStorage (a journal file in the sweep
folder), so several workers (Slurm array tasks) share one study, and running
the sweep again continues it.

Messages (field "op"):
  hello                      -> {"optuna": version}
  check {sampler, pruner, params}  -> {} when open would accept them (nothing written)
  open {journal, study, directions, sampler{name, seed, options{...}}, pruner{name, ...},
        params[{name, type float|int|categorical, low, high, log, step, choices}],
        holder{host, pid}}   -> {"reaped": [numbers failed because their holder died]}
  ask {limit}                -> {"number": n, "params": {...}} or {"number": null}
                                when complete + pruned + running trials reach limit
  report {number, step, value}  -> {"prune": bool}
  attrs {number, attrs}      -> {} (user attributes of a trial asked here)
  tell {number, state complete|pruned|fail, values, attrs}  -> {}
  count                      -> {"complete", "pruned", "running", "failed"}
  trials                     -> {"trials": [{number, state, params, values, user_attrs}]}
  importance                 -> {"parameter": [...], "value": [...]} (fANOVA, descending)
  pareto                     -> {"numbers": [...]} (the study's best trials)

Holders: a trial asked here records the host and pid of the cnclab process
that runs it (user attributes cnclab_host, cnclab_pid). Journal storage has no
heartbeat in Optuna 3.1, so `open` fails every running trial whose holder is on
this host and no longer runs, by the rule of cnclab's lock files
(src/cnclab/io/lock_file.cpp): another host's holder cannot be checked and is
left alone.
"""
import json
import math
import os
import socket
import sys
import warnings

try:
    import optuna
    from optuna.storages import JournalFileStorage, JournalStorage
    from optuna.trial import TrialState
except Exception as e:  # noqa: BLE001 - any import failure means the package is unusable
    sys.stdout.write(json.dumps({"ok": False, "missing": "python3-optuna",
                                 "error": "import optuna failed: %s" % e}) + "\n")
    sys.stdout.flush()
    sys.exit(2)

warnings.simplefilter("ignore")  # Experimental-feature notes would reach cnclab's log
optuna.logging.set_verbosity(optuna.logging.ERROR)

STATES = {"complete": TrialState.COMPLETE, "pruned": TrialState.PRUNED, "fail": TrialState.FAIL}


class Bad(Exception):
    """A message the helper cannot act on; answered with its text."""


def process_ended(pid):
    """cnclab's rule (lock_file.cpp): no such process, or a zombie."""
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return True
    except PermissionError:
        return False
    try:
        with open("/proc/%d/stat" % pid) as f:
            stat = f.read()
    except OSError:
        return True
    paren = stat.rfind(")")
    return paren >= 0 and stat[paren + 2:paren + 3] in ("Z", "X")


# Each sampler's options a sweep block may set (sweep.sampler), with their
# types: Optuna 3.1's keyword arguments that take a plain value (callables,
# other samplers and trial lists are left out). Optuna's defaults otherwise.
SAMPLERS = {
    "tpe": (optuna.samplers.TPESampler, {
        "n_startup_trials": int, "n_ei_candidates": int, "multivariate": bool, "group": bool,
        "constant_liar": bool, "consider_endpoints": bool, "consider_prior": bool,
        "prior_weight": float, "consider_magic_clip": bool}),
    "cmaes": (optuna.samplers.CmaEsSampler, {
        "n_startup_trials": int, "sigma0": float, "restart_strategy": str, "popsize": int,
        "inc_popsize": int, "consider_pruned_trials": bool, "use_separable_cma": bool,
        "with_margin": bool}),
    "nsga2": (optuna.samplers.NSGAIISampler, {
        "population_size": int, "mutation_prob": float, "crossover_prob": float,
        "swapping_prob": float}),
    # Scrambled by default (an unscrambled Sobol sequence starts at the corner).
    "qmc": (optuna.samplers.QMCSampler, {"qmc_type": str, "scramble": bool}),
}


def option_value(sampler, key, value, kind):
    """value as kind (an integer stands for a float; a bool is not an integer)."""
    if kind is float and isinstance(value, int) and not isinstance(value, bool):
        return float(value)
    if isinstance(value, kind) and not (kind is int and isinstance(value, bool)):
        return value
    raise Bad("sampler %s: option %s must be %s (got %r)" % (
        sampler, key, {int: "an integer", float: "a number", bool: "true or false",
                       str: "a word"}[kind], value))


def make_sampler(spec):
    """spec: {name, seed, options{...}}."""
    name = spec.get("name")
    if name not in SAMPLERS:
        raise Bad("unknown sampler %r (known: %s)" % (name, ", ".join(SAMPLERS)))
    cls, known = SAMPLERS[name]
    options = {"scramble": True} if name == "qmc" else {}
    for key, value in (spec.get("options") or {}).items():
        if key not in known:
            raise Bad("sampler %s: unknown option %r (known: %s)" % (
                name, key, ", ".join(sorted(known))))
        options[key] = option_value(name, key, value, known[key])
    try:
        return cls(seed=spec.get("seed"), **options)
    except (TypeError, ValueError) as e:
        raise Bad("sampler %s: %s" % (name, e))


PRUNERS = {
    "median": (optuna.pruners.MedianPruner, ("n_startup_trials", "n_warmup_steps",
                                             "interval_steps")),
    "successive_halving": (optuna.pruners.SuccessiveHalvingPruner,
                           ("min_resource", "reduction_factor", "min_early_stopping_rate")),
    "hyperband": (optuna.pruners.HyperbandPruner, ("min_resource", "max_resource",
                                                   "reduction_factor")),
}


def make_pruner(spec):
    name = spec.get("name", "none")
    options = {k: v for k, v in spec.items() if k != "name"}
    if name == "none":
        if options:
            raise Bad("pruner none takes no options (got %s)" % ", ".join(sorted(options)))
        return optuna.pruners.NopPruner()
    if name not in PRUNERS:
        raise Bad("unknown pruner %r (known: none, median, successive_halving, hyperband)" % name)
    cls, known = PRUNERS[name]
    for key in options:
        if key not in known:
            raise Bad("pruner %s: unknown option %r (known: %s)" % (name, key, ", ".join(known)))
    try:
        return cls(**options)
    except (TypeError, ValueError) as e:
        raise Bad("pruner %s: %s" % (name, e))


def distribution(p):
    kind = p.get("type")
    if kind == "float":
        return optuna.distributions.FloatDistribution(p["low"], p["high"], log=bool(p.get("log")))
    if kind == "int":
        return optuna.distributions.IntDistribution(p["low"], p["high"], step=p.get("step", 1))
    if kind == "categorical":
        return optuna.distributions.CategoricalDistribution(list(p["choices"]))
    raise Bad("parameter %r: unknown type %r" % (p.get("name"), kind))


def plain(v):
    """JSON has no NaN: NaN and infinities are null."""
    return v if not isinstance(v, float) or math.isfinite(v) else None


class Helper:
    def __init__(self):
        self.study = None
        self.space = {}
        self.trials = {}  # number -> optuna.Trial asked here
        self.holder = None

    def need_study(self):
        if self.study is None:
            raise Bad("no study open (send open first)")
        return self.study

    def op_hello(self, m):
        return {"optuna": optuna.__version__}

    def settings(self, m, what):
        """The sampler, pruner and space of message m (Bad on any error)."""
        try:
            return (make_sampler(m.get("sampler", {})), make_pruner(m.get("pruner", {})),
                    {p["name"]: distribution(p) for p in m["params"]})
        except KeyError as e:
            raise Bad("%s: missing field %s" % (what, e))
        except (TypeError, ValueError) as e:
            raise Bad("%s: %s" % (what, e))

    def op_check(self, m):
        self.settings(m, "check")
        return {}

    def op_open(self, m):
        # Settings first: a bad option is answered before the journal exists.
        sampler, pruner, self.space = self.settings(m, "open")
        try:
            storage = JournalStorage(JournalFileStorage(m["journal"]))
            directions = m.get("directions", ["minimize"])
            holder = m.get("holder", {})
            self.holder = (str(holder.get("host", socket.gethostname())),
                           int(holder.get("pid", os.getppid())))
        except KeyError as e:
            raise Bad("open: missing field %s" % e)
        except (TypeError, ValueError) as e:
            raise Bad("open: %s" % e)
        self.study = optuna.create_study(study_name=m.get("study", "cnclab"), storage=storage,
                                         sampler=sampler, pruner=pruner,
                                         directions=directions, load_if_exists=True)
        # A continued study (a rerun to more trials, a resubmitted or restarted
        # worker): its sampler with the first run's seed would draw that run's
        # points again, and a point equal to a finished trial's config is that
        # trial again (a trial spent on nothing). The seed is offset by the
        # trials already in the journal: a fresh study keeps the given seed, and
        # a continued one is as reproducible as the journal it continues.
        existing = len(self.study.get_trials(deepcopy=False))
        spec = dict(m.get("sampler", {}))
        if existing and spec.get("seed") is not None:
            spec["seed"] = (int(spec["seed"]) + existing) % 2**32
            self.study.sampler = make_sampler(spec)
        if [d.name.lower() for d in self.study.directions] != [d.lower() for d in directions]:
            raise Bad("the journal's study has directions %s, not %s" % (
                [d.name.lower() for d in self.study.directions], directions))
        return {"reaped": self.reap()}

    def reap(self):
        reaped = []
        host = self.holder[0]
        for t in self.study.get_trials(deepcopy=False, states=(TrialState.RUNNING,)):
            if t.user_attrs.get("cnclab_host") != host:
                continue
            pid = int(t.user_attrs.get("cnclab_pid", 0))
            if pid > 0 and process_ended(pid):
                self.study._storage.set_trial_user_attr(
                    t._trial_id, "cnclab_failure", "its worker (host %s, pid %d) ended" % (host, pid))
                self.study._storage.set_trial_state_values(t._trial_id, TrialState.FAIL)
                reaped.append(t.number)
        return reaped

    def counts(self):
        c = {"complete": 0, "pruned": 0, "running": 0, "failed": 0, "waiting": 0}
        names = {TrialState.COMPLETE: "complete", TrialState.PRUNED: "pruned",
                 TrialState.RUNNING: "running", TrialState.FAIL: "failed",
                 TrialState.WAITING: "waiting"}
        for t in self.need_study().get_trials(deepcopy=False):
            c[names[t.state]] += 1
        return c

    def taken(self, below=None):
        """Complete, pruned and running trials (numbered below `below`)."""
        n = 0
        for t in self.need_study().get_trials(deepcopy=False):
            if t.state in (TrialState.COMPLETE, TrialState.PRUNED, TrialState.RUNNING) and (
                    below is None or t.number < below):
                n += 1
        return n

    def op_count(self, m):
        return self.counts()

    def op_ask(self, m):
        study = self.need_study()
        limit = m.get("limit")
        if limit is not None and self.taken() >= limit:
            return {"number": None}
        trial = study.ask(self.space)
        storage = study._storage
        storage.set_trial_user_attr(trial._trial_id, "cnclab_host", self.holder[0])
        storage.set_trial_user_attr(trial._trial_id, "cnclab_pid", self.holder[1])
        # Another worker may have asked meanwhile: a trial beyond the limit
        # (counting the trials numbered before it) is given up at once.
        if limit is not None and self.taken(below=trial.number) >= limit:
            storage.set_trial_user_attr(trial._trial_id, "cnclab_failure",
                                        "surplus: the study had its trials")
            study.tell(trial.number, state=TrialState.FAIL)
            return {"number": None}
        self.trials[trial.number] = trial
        return {"number": trial.number, "params": trial.params}

    def trial(self, m):
        number = m.get("number")
        if not isinstance(number, int) or number not in self.trials:
            raise Bad("no running trial %r asked by this helper" % (number,))
        return self.trials[number]

    def op_report(self, m):
        trial = self.trial(m)
        step, value = m.get("step"), m.get("value")
        if not isinstance(step, int) or step < 0:
            raise Bad("report: step must be a non-negative integer (got %r)" % (step,))
        if value is not None and not isinstance(value, (int, float)):
            raise Bad("report: value must be a number or null (got %r)" % (value,))
        if len(self.study.directions) > 1:
            return {"prune": False}  # Optuna prunes single-objective studies only
        trial.report(float("nan") if value is None else float(value), step)
        return {"prune": bool(trial.should_prune())}

    def op_attrs(self, m):
        trial = self.trial(m)
        attrs = m.get("attrs")
        if not isinstance(attrs, dict):
            raise Bad("attrs: expected an object of user attributes")
        for key, value in attrs.items():
            self.study._storage.set_trial_user_attr(trial._trial_id, str(key), value)
        return {}

    def op_tell(self, m):
        trial = self.trial(m)
        state = m.get("state")
        if state not in STATES:
            raise Bad("tell: state must be one of complete, pruned, fail (got %r)" % (state,))
        for key, value in (m.get("attrs") or {}).items():
            self.study._storage.set_trial_user_attr(trial._trial_id, str(key), value)
        values = None
        if state == "complete":
            values = [float("nan") if v is None else float(v) for v in m.get("values", [])]
            if len(values) != len(self.study.directions) or any(math.isnan(v) for v in values):
                raise Bad("tell: complete needs %d finite value(s) (got %r)" % (
                    len(self.study.directions), m.get("values")))
        self.study.tell(trial.number, values, state=STATES[state])
        del self.trials[trial.number]
        return {}

    def op_trials(self, m):
        out = []
        for t in self.need_study().get_trials(deepcopy=False):
            out.append({"number": t.number, "state": t.state.name.lower(), "params": t.params,
                        "values": [plain(v) for v in (t.values or [])],
                        "user_attrs": t.user_attrs})
        return {"trials": out}

    def op_importance(self, m):
        study = self.need_study()
        done = study.get_trials(deepcopy=False, states=(TrialState.COMPLETE,))
        if len(done) < 2:
            raise Bad("importance needs at least 2 complete trials (have %d)" % len(done))
        target = (lambda t: t.values[0]) if len(study.directions) > 1 else None
        evaluator = optuna.importance.FanovaImportanceEvaluator(seed=int(m.get("seed", 0)))
        imp = optuna.importance.get_param_importances(study, evaluator=evaluator, target=target)
        ranked = sorted(imp.items(), key=lambda kv: -kv[1])
        return {"parameter": [k for k, _ in ranked], "value": [float(v) for _, v in ranked],
                "evaluator": "fanova"}

    def op_pareto(self, m):
        return {"numbers": sorted(t.number for t in self.need_study().best_trials)}


def main():
    helper = Helper()
    for line in sys.stdin:
        if not line.strip():
            continue
        try:
            message = json.loads(line)
            if not isinstance(message, dict):
                raise Bad("expected a JSON object")
            handler = getattr(helper, "op_%s" % message.get("op"), None)
            if handler is None:
                raise Bad("unknown op %r" % (message.get("op"),))
            answer = {"ok": True}
            answer.update(handler(message))
        except json.JSONDecodeError as e:
            answer = {"ok": False, "error": "not JSON: %s" % e}
        except Bad as e:
            answer = {"ok": False, "error": str(e)}
        except Exception as e:  # noqa: BLE001 - Optuna's own errors, reported to cnclab
            answer = {"ok": False, "error": "%s: %s" % (type(e).__name__, e)}
        sys.stdout.write(json.dumps(answer, allow_nan=False, default=str) + "\n")
        sys.stdout.flush()
    return 0


if __name__ == "__main__":
    sys.exit(main())
