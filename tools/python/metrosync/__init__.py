"""metrosync from Python: coupled metronomes on a platform with dry friction.

    import metrosync
    rig = metrosync.load_rig("yaml/rigs/experiment.yaml", {"platform.friction.mu": 0.3})
    res = metrosync.run(rig, model="full")
    res.envelope["A_1"], res.regime, res.summary["final"]

Every call runs the command-line program's own code in-process (the same C++ functions, the same
rows), so a result here equals the files `metrosync run` writes, value for value. docs/python.md
is the reference.
"""

import json
import os
import shutil
import tempfile

import numpy as np

from . import _metrosync as _core

__all__ = ["Rig", "Result", "CompareResult", "RigError", "SimulationError", "load_rig", "run",
           "compare", "version"]

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
        """(trajectory, envelope) as pandas DataFrames (pandas must be installed)."""
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
