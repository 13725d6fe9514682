"""metrosync from Python: coupled metronomes on a platform with dry friction.

    import metrosync
    rig = metrosync.load_rig("yaml/rigs/experiment.yaml", {"platform.friction.mu": 0.3})
    res = metrosync.run(rig, model="full")
    res.envelope["A_1"], res.regime, res.summary["final"]
    grid = metrosync.sweep(rig, vary={"platform.friction.mu": (0, 1, 21)})
    grid.regime, grid["A_1"]          # arrays shaped by the grid

Every call runs the command-line program's own code in-process (the same C++ functions, the same
rows), so a result here equals the files `metrosync run` writes, value for value. docs/python.md
is the reference.
"""

import csv
import json
import os
import shutil
import tempfile

import numpy as np

from . import _metrosync as _core

__all__ = ["Rig", "Result", "CompareResult", "SweepResult", "ContinuationResult", "RigError",
           "SimulationError", "load_rig", "run", "compare", "sweep", "continue_", "fit",
           "version"]

RigError = _core.RigError  # a bad rig or option: the CLI's message (file:line:col: key: what)


class SimulationError(RuntimeError):
    """The simulation failed (the CLI's exit code 3). `.result` holds what it computed so far."""

    def __init__(self, message, result):
        super().__init__(message)
        self.result = result


def version():
    """metrosync's version (as `metrosync --version`)."""
    return _core.version()


def _value_text(value):
    if isinstance(value, bool):
        return "true" if value else "false"
    return repr(value) if isinstance(value, float) else str(value)


class Rig:
    """A rig: a YAML file or a dict, and overrides {KEY: value} applied like `--set KEY=value`."""

    def __init__(self, path=None, text=None, overrides=None, name=None):
        self._path = path
        self._text = text
        self.overrides = dict(overrides or {})
        self._scaled = None
        self.name = name

    def _sets(self, extra=None):
        items = list(self.overrides.items()) + list((extra or {}).items())
        return ["%s=%s" % (k, _value_text(v)) for k, v in items]

    def _materialize(self, folder):
        """The rig's file: its own path, or the dict's JSON (JSON is YAML) written into folder."""
        if self._path is not None:
            return self._path
        path = os.path.join(folder, (self.name or "rig") + ".yaml")
        with open(path, "w", encoding="utf-8") as f:
            f.write(self._text)
        return path

    def scaled(self):
        """The scaled parameters: the object `metrosync scale --json` prints."""
        if self._scaled is None:
            folder = tempfile.mkdtemp(prefix="metrosync-")
            try:
                self._scaled = json.loads(_core.scaled_json(self._materialize(folder), self._sets()))
            finally:
                shutil.rmtree(folder, ignore_errors=True)
        return self._scaled

    def __repr__(self):
        s = self.scaled()
        keys = [k for k in ("epsilon", "mu", "c", "nu", "J", "theta_c", "alpha") if k in s]
        body = ", ".join("%s=%s" % (k, s[k]) for k in keys)
        source = self._path if self._path is not None else "<dict>"
        return "Rig(%s%s: %s)" % (source, " + %d overrides" % len(self.overrides)
                                  if self.overrides else "", body)


def load_rig(path_or_dict, overrides=None):
    """A Rig from a YAML file's path or a dict (the YAML's structure); checked at once (RigError)."""
    if isinstance(path_or_dict, dict):
        rig = Rig(text=json.dumps(path_or_dict), overrides=overrides,
                  name=str(path_or_dict.get("name", "rig")))
    else:
        rig = Rig(path=os.fspath(path_or_dict), overrides=overrides)
    rig.scaled()  # loads and checks it: a bad rig raises RigError here
    return rig


def _read_csv(path):
    """A CSV of numbers as {column: numpy array}; None when the file does not exist."""
    if not os.path.exists(path):
        return None
    with open(path, encoding="utf-8") as f:
        header = f.readline().strip().split(",")
    data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    if data.size == 0:
        data = np.zeros((0, len(header)))
    return {name: data[:, k].copy() for k, name in enumerate(header)}


class Result:
    """One run: .trajectory and .envelope ({column: numpy array}, the CSV files' columns; the
    trajectory is None for the slow flow), .summary (summary.json as a dict), .regime."""

    def __init__(self, folder, envelope="envelope.csv"):
        with open(os.path.join(folder, "summary.json"), encoding="utf-8") as f:
            self.summary = json.load(f)
        self.trajectory = _read_csv(os.path.join(folder, "trajectory.csv"))
        self.envelope = _read_csv(os.path.join(folder, envelope))
        self.regime = self.summary.get("regime")

    @property
    def complete(self):
        return bool(self.summary.get("complete", False))

    def to_pandas(self):
        """(trajectory, envelope) as pandas DataFrames, equal to the CSV files (pandas must be
        installed); the trajectory is None for the slow flow."""
        import pandas as pd  # optional dependency
        frame = lambda d: None if d is None else pd.DataFrame(d)
        return frame(self.trajectory), frame(self.envelope)

    def __repr__(self):
        return "Result(regime=%r, complete=%r)" % (self.regime, self.complete)


class CompareResult:
    """`compare`: .full and .slow envelopes, .comparison (comparison.csv), .summary."""

    def __init__(self, folder):
        with open(os.path.join(folder, "summary.json"), encoding="utf-8") as f:
            self.summary = json.load(f)
        self.trajectory = _read_csv(os.path.join(folder, "trajectory.csv"))
        self.full = _read_csv(os.path.join(folder, "envelope_full.csv"))
        self.slow = _read_csv(os.path.join(folder, "envelope_slow.csv"))
        self.comparison = _read_csv(os.path.join(folder, "comparison.csv"))


def _command(command, rig, model, engine, simulation, out, make):
    sets = rig._sets({"simulation." + k: v for k, v in simulation.items()})
    folder = tempfile.mkdtemp(prefix="metrosync-")
    try:
        target = out if out is not None else os.path.join(folder, "out")
        code = _core.run_command(command, rig._materialize(folder), sets, target, model or "",
                                 engine or "")
        result = make(target)
        if code != 0:
            raise SimulationError(result.summary.get("failure", "the simulation failed"), result)
        return result
    finally:
        shutil.rmtree(folder, ignore_errors=True)


def run(rig, model=None, engine=None, out=None, **simulation):
    """Runs a rig (`metrosync run`): model "full" or "slow", engine "direct", "simbody" or
    "slowflow" (default: the model's own); keyword arguments override `simulation.KEY` (e.g.
    duration=30, accuracy=1e-10). `out`: also keep the CLI's files in that folder. Long runs
    release the interpreter and stop on Ctrl-C (KeyboardInterrupt)."""
    return _command("run", rig, model, engine, simulation, out, Result)


def compare(rig, engine=None, out=None, **simulation):
    """The full model and the slow flow on one rig (`metrosync compare`)."""
    return _command("compare", rig, None, engine, simulation, out, CompareResult)


def _vary_text(key, spec):
    """--vary's text for one axis: (from, to, count[, "open"]), a list of values, or the CLI's
    own text ("0:2pi:100:open")."""
    if isinstance(spec, str):
        return "%s=%s" % (key, spec)
    if isinstance(spec, tuple):  # a range; a list (or an array) lists the values
        if len(spec) not in (3, 4) or float(spec[2]) != int(spec[2]):
            raise RigError("vary %s: a tuple is (from, to, count[, 'open']) with a whole count; "
                           "list the values in a list" % key)
        fields = [_value_text(float(spec[0])), _value_text(float(spec[1])), str(int(spec[2]))]
        if len(spec) == 4:
            if spec[3] != "open":
                raise RigError("vary %s: the fourth item may only be 'open'" % key)
            fields.append("open")
        return "%s=%s" % (key, ":".join(fields))
    values = [float(v) for v in np.atleast_1d(np.asarray(spec, dtype=float))]
    if not values:
        raise RigError("vary %s: no values" % key)
    if len(values) == 1:
        return "%s=%s:%s:1" % (key, _value_text(values[0]), _value_text(values[0]))
    return "%s=%s" % (key, ",".join(_value_text(v) for v in values))


def _number(text):
    try:
        return float(text)
    except ValueError:
        return float("nan")


def _read_mixed_csv(path):
    """A CSV with text columns as {column: array}: float where every value is a number, str
    otherwise; None when the file does not exist."""
    if not os.path.exists(path):
        return None
    with open(path, encoding="utf-8", newline="") as f:
        rows = list(csv.reader(f))
    header, rows = rows[0], rows[1:]
    out = {}
    for k, name in enumerate(header):
        col = [r[k] for r in rows]
        try:
            out[name] = np.array([float(v) for v in col])
        except ValueError:
            out[name] = np.array(col, dtype=str)
    return out


class SweepResult:
    """A sweep (`metrosync sweep`): every column of regimes.csv as an array shaped by the grid
    (first varied key along axis 0). .keys, .values (each axis's values), .shape, .regime (str
    array), .columns {name: array} (numbers as float, regime/clusters/message as str),
    res["A_1"]; .summary is sweep.json; .to_pandas() the rows of regimes.csv."""

    _TEXT = ("regime", "clusters", "message")

    def __init__(self, folder):
        with open(os.path.join(folder, "sweep.json"), encoding="utf-8") as f:
            self.summary = json.load(f)
        axes = self.summary["grid"]["axes"]
        self.keys = [a["key"] for a in axes]
        self.values = [np.array([float(v) for v in a["values"]]) for a in axes]
        self.shape = tuple(len(v) for v in self.values)
        size = int(np.prod(self.shape))
        with open(os.path.join(folder, "regimes.csv"), encoding="utf-8", newline="") as f:
            rows = list(csv.reader(f))
        header, rows = rows[0], rows[1:]
        self._header = header
        self._rows = rows
        at = header.index("index")
        cols = {}
        for k, name in enumerate(header):
            if name in self._TEXT:
                a = np.full(size, "", dtype=object)
            else:
                a = np.full(size, np.nan)
            for r in rows:
                a[int(r[at])] = r[k] if name in self._TEXT else _number(r[k])
            if name in self._TEXT:
                a = a.astype(str)
            cols[name] = a.reshape(self.shape)
        self.columns = cols
        self.regime = cols["regime"]

    def __getitem__(self, name):
        return self.columns[name]

    @property
    def complete(self):
        return bool(self.summary.get("complete", False))

    def to_pandas(self):
        """regimes.csv as a pandas DataFrame (one row per grid point, in grid order)."""
        import pandas as pd  # optional dependency
        data = {}
        for k, name in enumerate(self._header):
            col = [r[k] for r in self._rows]
            data[name] = col if name in self._TEXT else [_number(v) for v in col]
        return pd.DataFrame(data)

    def __repr__(self):
        return "SweepResult(%s, shape=%r)" % (", ".join(self.keys), self.shape)


def sweep(rig, vary, model=None, engine=None, jobs=None, out=None, **simulation):
    """A grid of runs (`metrosync sweep`, the same C++ code): vary = {KEY: (from, to, count),
    KEY2: [v1, v2, ...]} (one key or more, in order; (from, to, count, "open") leaves `to`
    out). model "slow" (default) or "full"; jobs: threads (default: the cores). Keyword
    arguments set `simulation.KEY` for every point. Returns a SweepResult. `out`: keep the
    CLI's files (with its maps) there. Ctrl-C stops it (KeyboardInterrupt)."""
    if not vary:
        raise RigError("sweep: vary needs at least one key")
    texts = [_vary_text(k, v) for k, v in vary.items()]
    sets = rig._sets({"simulation." + k: v for k, v in simulation.items()})
    folder = tempfile.mkdtemp(prefix="metrosync-")
    try:
        target = out if out is not None else os.path.join(folder, "out")
        _core.sweep_command(rig._materialize(folder), sets, texts, target, model or "",
                            engine or "", int(jobs or 0), out is not None)
        return SweepResult(target)
    finally:
        shutil.rmtree(folder, ignore_errors=True)


class ContinuationResult:
    """`metrosync continue`: .branches (branches.csv as {column: array}), .bifurcations
    (bifurcations.json: a list of dicts), .summary (summary.json), .cycles (cycles.csv: the limit
    cycles born at Hopf points; None with no_cycles=True), .families (families.csv: each neutral
    family's extent, None without one), .fold_curve and .hopf_curve (fold_curve.csv and
    hopf_curve.csv: the two-parameter curves, None without fold=)."""

    def __init__(self, folder):
        with open(os.path.join(folder, "summary.json"), encoding="utf-8") as f:
            self.summary = json.load(f)
        with open(os.path.join(folder, "bifurcations.json"), encoding="utf-8") as f:
            self.bifurcations = json.load(f)
        self.branches = _read_mixed_csv(os.path.join(folder, "branches.csv"))
        self.cycles = _read_mixed_csv(os.path.join(folder, "cycles.csv"))
        self.families = _read_mixed_csv(os.path.join(folder, "families.csv"))
        self.fold_curve = _read_mixed_csv(os.path.join(folder, "fold_curve.csv"))
        self.hopf_curve = _read_mixed_csv(os.path.join(folder, "hopf_curve.csv"))

    def __repr__(self):
        return "ContinuationResult(%d points, %d special points)" % (
            len(next(iter(self.branches.values()))) if self.branches else 0,
            len(self.bifurcations))


def continue_(rig, param, to, from_=None, start=None, step=None, max_points=500, all=False,
              fold=None, to2=None, no_cycles=False, out=None):
    """The slow flow's locked states followed in one rig key (`metrosync continue`, the same
    C++ code): param KEY from the rig's value (or from_) to `to`; start: (A_1..A_N,
    psi_2..psi_N); all: every locked state at the start; fold=KEY2, to2: each fold followed in
    two keys; no_cycles: the limit cycles born at Hopf points not followed. Returns a
    ContinuationResult."""
    if (fold is None) != (to2 is None):
        raise RigError("continue_: fold and to2 go together")
    folder = tempfile.mkdtemp(prefix="metrosync-")
    try:
        target = out if out is not None else os.path.join(folder, "out")
        start_text = "" if start is None else ",".join(repr(float(v)) for v in start)
        _core.continue_command(rig._materialize(folder), rig._sets(), param, float(to), target,
                               None if from_ is None else float(from_), start_text,
                               float(step or 0.0), int(max_points), bool(all), fold or "",
                               float(to2 or 0.0), bool(no_cycles))
        return ContinuationResult(target)
    finally:
        shutil.rmtree(folder, ignore_errors=True)


def _write_data(columns, path):
    """A mapping of columns (t, theta_1, ..., x: equal-length sequences; NaN = a missing sample)
    as the CSV file `metrosync fit` reads."""
    names = list(columns)
    values = [np.asarray(columns[n], dtype=float) for n in names]
    with open(path, "w") as f:
        f.write(",".join(names) + "\n")
        for row in zip(*values):
            f.write(",".join("" if np.isnan(v) else repr(float(v)) for v in row) + "\n")


def fit(rig, data, free, model=None, noise=None, starts=6, local=False, profile=False):
    """Rig keys from measured data (`metrosync fit`, the same C++ code; docs/fit.md): `data` is a
    CSV file's path or a mapping of columns ({"t": ..., "theta_1": ..., "x": ...}, a pandas
    DataFrame too); `free` one key or a list (metronomes.*.X: one shared value); the rig's
    overrides give the starting values, as --set does. Returns fit.json's dictionary: values,
    std_errors, identifiable, rms, noise, converged and its note, optima, ..."""
    rig = rig if isinstance(rig, Rig) else load_rig(rig)
    free = [free] if isinstance(free, str) else list(free)
    folder = tempfile.mkdtemp(prefix="metrosync-")
    try:
        if isinstance(data, (str, os.PathLike)):
            data_path = os.fspath(data)
        else:
            data_path = os.path.join(folder, "data.csv")
            _write_data(data, data_path)
        text = _core.fit_json(rig._materialize(folder), data_path, free, rig._sets(),
                              model or "", None if noise is None else float(noise), int(starts),
                              bool(local), bool(profile))
        return json.loads(text)
    finally:
        shutil.rmtree(folder, ignore_errors=True)
