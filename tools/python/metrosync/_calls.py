"""The calls: each takes a Rig, a dict or a YAML file's path and runs the command-line program's own
code in-process; keyword arguments set ``simulation.KEY``."""

import contextlib
import difflib
import json
import os
import shutil
import tempfile

import numpy as np

from . import _metrosync as _core
from ._results import (BasinResult, CompareResult, ContinuationResult, FitResult, Result,
                       SimulationError, SweepResult, _read_json)
from ._rig import RigError, _Origin, _short_repr, as_rig, load_rig


# The keys under `simulation:` (yaml/rig_schema.cpp): what a call's keyword arguments set.
_SIMULATION_KEYS = ("accuracy", "duration", "integrator", "sample", "tau")


def _simulation(simulation, call):
    """Keyword arguments as overrides of simulation.KEY, named as the caller wrote them. A name
    that is no simulation key nor a slip of one (``overrides=``) is a TypeError saying so; a slip
    (``durration=``) is left to the loader, whose message says "did you mean"."""
    for k in simulation:
        if k not in _SIMULATION_KEYS and not difflib.get_close_matches(k, _SIMULATION_KEYS):
            raise TypeError(
                "%s() got an unexpected keyword argument %r: its keyword arguments set "
                "simulation.KEY (%s); other rig keys are set by load_rig(rig, overrides={KEY: "
                "value}), whose Rig every call takes (docs/python.md)"
                % (call, k, ", ".join(_SIMULATION_KEYS)))
    return [_Origin("simulation." + k, v, "%s=%s" % (k, _short_repr(v)))
            for k, v in simulation.items()]


def _folder(out):
    return None if out is None else os.fspath(out)


def _jobs(jobs):
    """Threads: a whole number >= 1, or None for one per core."""
    if jobs is not None and (int(jobs) != jobs or jobs < 1):
        raise RigError("jobs=%r: must be a whole number >= 1 (None: one per core)" % (jobs,))
    return int(jobs or 0)


def _checked(result, code):
    """The result, or SimulationError carrying it when the simulation failed (exit code 3)."""
    if code != 0:
        raise SimulationError(result.summary.get("failure", "the simulation failed"), result)
    return result


@contextlib.contextmanager
def _rig_file(rig):
    """A file for the commands that read one (continue, fit, a network's run): the rig's own, or
    a dict's JSON in a temporary folder; RigErrors name the dict, not that file."""
    folder = tempfile.mkdtemp(prefix="metrosync-")
    try:
        path = rig.path
        if path is None:
            path = os.path.join(folder, "rig.yaml")
            with open(path, "w", encoding="utf-8") as f:
                f.write(rig._text)
        try:
            yield path, folder
        except RigError as e:  # the temporary files by what they stand for
            message = str(e).replace(os.path.join(folder, "data.csv"), "data")
            if rig.path is None:
                message = message.replace(path, "rig")
            raise rig._explain(RigError(message)) from None
    finally:
        shutil.rmtree(folder, ignore_errors=True)


def _network_run(rig, model, engine, out, extra):
    """A network of platforms runs from a file into a folder, read back (docs/python.md); its
    options are run's (model="slow" is refused as the command line refuses --model slow)."""
    with _rig_file(rig) as (path, folder):
        target = _folder(out) or os.path.join(folder, "out")
        sets = [o.text for o in rig._origins(extra)]
        code = _core.network_run(path, sets, model or "", engine or "", target, out is not None)
        read = lambda name: _read_csv_table(os.path.join(target, name))
        rows = {"trajectory": read("trajectory.csv"), "envelope": read("envelope.csv"),
                "events": None}
        summary = _read_json(os.path.join(target, "summary.json"))
        return _checked(Result(summary, rows, _folder(out)), code)


def _read_csv_table(path):
    """A CSV of numbers as (names, rows x columns array); None when absent."""
    if not os.path.exists(path):
        return None
    with open(path, encoding="utf-8") as f:
        names = f.readline().strip().split(",")
    values = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    return names, values.reshape(-1, len(names))


def run(rig, model=None, engine=None, out=None, **simulation):
    """Runs a rig (``metrosync run``): the full model (default) or the slow flow.

    rig: a :class:`Rig`, a dict or a YAML file's path. model: "full" or "slow"; engine: "direct"
    (the full model's default), "simbody" or "slowflow". Keyword arguments set
    ``simulation.KEY`` (``duration=30``, ``accuracy=1e-10``, ``tau=200``). The rows stay in
    memory; ``out=DIR`` also writes the CLI's files and plot there. Ctrl-C stops a long run
    (KeyboardInterrupt). Returns a :class:`Result`; a failed simulation raises
    :class:`SimulationError` (its ``.result`` holds the rows until then).

    >>> res = metrosync.run({"units": "scaled", ...}, model="slow", tau=100)
    >>> res = metrosync.run("yaml/rigs/experiment.yaml", duration=60)
    >>> res.regime, res.envelope["psi_2"][-1], res.to_pandas().head()
    """
    rig = as_rig(rig)
    extra = _simulation(simulation, "run")
    if rig._is_network():
        return _network_run(rig, model, engine, out, extra)
    r = rig._call(_core.run, model or "", engine or "", _folder(out), extra=extra)
    return _checked(Result(json.loads(r["summary"]), r, _folder(out)), r["code"])


def compare(rig, engine=None, out=None, **simulation):
    """The full model and the slow flow on one rig (``metrosync compare``), their envelopes
    matched row by row. Arguments as :func:`run`. Returns a :class:`CompareResult`.

    >>> c = metrosync.compare("yaml/rigs/paper/f4.3-mu0.3.yaml")
    >>> c.summary["comparison"]["max_abs_dA"], c.full.regime, c.slow.regime
    """
    rig = as_rig(rig)
    r = rig._call(_core.compare, engine or "", _folder(out),
                  extra=_simulation(simulation, "compare"))
    return _checked(CompareResult(json.loads(r["summary"]), r, _folder(out)), r["code"])


def _vary_text(key, spec):
    """``--vary``'s text for one axis: (from, to, count[, "open"|"log"]), a list of values, or the
    CLI's own text ("0:2pi:100:open")."""
    if isinstance(spec, str):
        return "%s=%s" % (key, spec)
    if isinstance(spec, tuple):  # a range; a list (or an array) lists the values
        if len(spec) not in (3, 4) or float(spec[2]) != int(spec[2]):
            raise RigError("vary[%r] = %r: a tuple is (from, to, count[, 'open' or 'log']) with a "
                           "whole count; list the values in a list" % (key, spec))
        fields = [repr(float(spec[0])), repr(float(spec[1])), str(int(spec[2]))]
        if len(spec) == 4:
            if spec[3] not in ("open", "log"):
                raise RigError("vary[%r] = %r: the fourth item may be 'open' or 'log'"
                               % (key, spec))
            fields.append(spec[3])
        return "%s=%s" % (key, ":".join(fields))
    values = [float(v) for v in np.atleast_1d(np.asarray(spec, dtype=float))]
    if not values:
        raise RigError("vary[%r]: no values" % key)
    if len(values) == 1:
        return "%s=%r:%r:1" % (key, values[0], values[0])
    return "%s=%s" % (key, ",".join(repr(v) for v in values))


def sweep(rig, vary, model=None, engine=None, jobs=None, out=None, **simulation):
    """A grid of runs (``metrosync sweep``, the same C++ code, on threads).

    vary: {KEY: (from, to, count), KEY2: [v1, v2, ...], ...}, one key or more in order (the first
    along axis 0); ``(from, to, count, "open")`` leaves `to` out, ``"log"`` spaces the values in
    log; a string is the CLI's ``FROM:TO:COUNT[:open]``; ``metronomes.*.KEY`` sets every
    metronome. model: "slow" (default) or "full"; jobs: threads (default: the cores). Keyword
    arguments set ``simulation.KEY`` at every point. ``out=DIR`` also writes regimes.csv,
    sweep.json and the maps. Ctrl-C stops it (KeyboardInterrupt). Returns a :class:`SweepResult`.

    >>> grid = metrosync.sweep("yaml/rigs/experiment-map.yaml",
    ...                        vary={"platform.friction.mu": (0, 3, 31)}, model="slow")
    >>> grid.regime, grid["A_1"]
    """
    rig = as_rig(rig)
    if not vary:
        raise RigError("sweep: vary needs at least one key")
    texts = [_vary_text(k, v) for k, v in vary.items()]
    r = rig._call(_core.sweep, texts, model or "", engine or "", _jobs(jobs), _folder(out),
                  extra=_simulation(simulation, "sweep"))
    return SweepResult(json.loads(r["summary"]), r["points"], _folder(out))


def basin(rig, random, samples, seed=1, model=None, engine=None, jobs=None, out=None,
          **simulation):
    """Basin stability (``metrosync basin``): `samples` random starts, each key of `random`
    drawn uniformly from (from, to) (a phase, a key ending in phi or psi, on the circle), each
    run as a sweep point; the fraction of each regime with its 95% Wilson interval. Sample k's
    draws depend only on (seed, k). Returns a :class:`BasinResult`.

    >>> b = metrosync.basin("yaml/rigs/experiment-map.yaml",
    ...                     random={"metronomes.0.start.phi": (0, 6.283185307179586)}, samples=100)
    >>> b.fraction("antiphase"), b.to_pandas().head()
    """
    rig = as_rig(rig)
    if not random:
        raise RigError("basin: random needs at least one key")
    texts = []
    for key, spec in random.items():
        spec = spec.split(":") if isinstance(spec, str) else spec
        if len(spec) != 2:
            raise RigError("random[%r] = %r: give (from, to)" % (key, spec))
        texts.append("%s=%s:%s" % (key, *(v if isinstance(v, str) else repr(float(v))
                                          for v in spec)))
    r = rig._call(_core.basin, texts, int(samples), int(seed), model or "", engine or "",
                  _jobs(jobs), _folder(out), extra=_simulation(simulation, "basin"))
    return BasinResult(json.loads(r["summary"]), r["points"], r["drawn"], _folder(out))


def continue_(rig, param, to, from_=None, start=None, step=None, max_points=500, all=False,
              no_cycles=False, fold=None, to2=None, model="slow", out=None):
    """Locked states followed in one rig key (``metrosync continue``, docs/continuation.md):
    `param` from the rig's value (or `from_`) to `to`, with their stability and bifurcations;
    model "slow" (the slow flow's fixed points, default) or "full" (the full model's periodic
    orbits, their Floquet multipliers; branches.csv has the full model's columns). start:
    (A_1..A_N, psi_2..psi_N) to start from; all: every locked state at the start; no_cycles: do
    not follow the limit cycle born at each Hopf point; fold=KEY2 with to2: each fold and Hopf
    point followed in two keys (``.fold_curve``, ``.hopf_curve``). Returns a
    :class:`ContinuationResult`.

    >>> c = metrosync.continue_("yaml/rigs/paper/f4.4-alpha4.yaml", param="metronomes.1.alpha",
    ...                         from_=3.0, to=4.0)
    >>> c.bifurcations[0]["type"], c.to_pandas().head()
    >>> full = metrosync.continue_("yaml/rigs/paper/f4.3-mu0.2.yaml", model="full",
    ...                            param="platform.friction.mu", to=0.35)
    """
    rig = as_rig(rig)
    if (fold is None) != (to2 is None):
        raise RigError("continue_: fold and to2 go together")
    start_text = "" if start is None else ",".join(repr(float(v)) for v in start)
    with _rig_file(rig) as (path, folder):
        target = _folder(out) or os.path.join(folder, "out")
        _core.continue_command(path, [o.text for o in rig._origins()], model, param, float(to),
                               target,
                               None if from_ is None else float(from_), start_text,
                               float(step or 0.0), int(max_points), bool(all), bool(no_cycles),
                               fold or "", float(to2 or 0.0))
        return ContinuationResult(target, _folder(out))


def _data_file(data, folder):
    """A data file's path: `data` itself, or a mapping of columns (a dict, a DataFrame) written
    as CSV (a NaN is a missing sample: an empty cell)."""
    if isinstance(data, (str, bytes, os.PathLike)):
        return os.fsdecode(data)
    columns = {str(k): np.asarray(v, dtype=float) for k, v in dict(data).items()}
    path = os.path.join(folder, "data.csv")
    with open(path, "w", encoding="utf-8") as f:
        f.write(",".join(columns) + "\n")
        for row in zip(*columns.values()):
            f.write(",".join("" if np.isnan(v) else repr(float(v)) for v in row) + "\n")
    return path


def fit(rig, data, free, model="full", out=None, noise=None, starts=6, local=False,
        profile=False):
    """Rig keys estimated from measured data by least squares (``metrosync fit``, docs/fit.md).

    data: a CSV file's path, or columns {"t": seconds, "theta_1": rad, ..., "x": m} (a dict or a
    DataFrame; NaN for a missing sample). free: the keys to estimate (the rig holds their
    starting values, used as given). model: "full" (every sample) or "slow" (the swings'
    amplitudes). The options of ``metrosync fit``: noise (``--noise``: the angles' noise in rad;
    None: estimated from the data), starts (``--starts``: at most this many starting points),
    local (``--local``: no growing windows), profile (``--profile``: profile every key). Returns a
    :class:`FitResult`, whose ``.summary`` is the CLI's fit.json; ``.rig`` is the fitted rig.

    >>> f = metrosync.fit("rig.yaml", {"t": t, "theta_1": th1, "theta_2": th2},
    ...                   free=["platform.friction.mu", "metronomes.0.pendulum.decay_rate"])
    >>> f.values, f.std_errors, f.rms
    """
    if noise is not None and not float(noise) > 0:
        raise ValueError("noise must be > 0 (the angles' noise in rad), not %r" % (noise,))
    if int(starts) < 1:
        raise ValueError("starts must be at least 1, not %r" % (starts,))
    rig = as_rig(rig)
    free = [free] if isinstance(free, str) else list(free)
    with _rig_file(rig) as (path, folder):
        target = _folder(out) or os.path.join(folder, "out")
        code = _core.fit_command(path, _data_file(data, folder), free,
                                 [o.text for o in rig._origins()], model, target, out is not None,
                                 None if noise is None else float(noise), int(starts), bool(local),
                                 bool(profile))
        if code != 0:
            raise SimulationError("the model fails at the starting values", None)
        summary = _read_json(os.path.join(target, "fit.json"))
    fitted = {k: v for k, v in summary["values"].items() if v is not None}
    return FitResult(summary, load_rig(rig, fitted), _folder(out))
