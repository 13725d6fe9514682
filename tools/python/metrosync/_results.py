"""What the calls return: the CLI's files' columns as numpy arrays, their JSON as dicts."""

import csv
import json
import os

import numpy as np


class SimulationError(RuntimeError):
    """The simulation failed (the CLI's exit code 3): the message says when and why;
    ``.result`` holds what was computed until then (its summary says ``complete: False``)."""

    def __init__(self, message, result):
        super().__init__(message)
        self.result = result


def _columns(table):
    """(names, rows x columns array) as {name: contiguous column}, in the names' order."""
    if table is None:
        return None
    names, values = table
    by_column = np.ascontiguousarray(values.T)  # one copy: each column contiguous
    return {name: by_column[k] for k, name in enumerate(names)}


def _events(table):
    """events.csv's columns: the numbers, with kind and who (text) after t and tau."""
    if table is None:
        return None
    names, values, kinds, who = table
    numbers = _columns((names, values))
    out = {"t": numbers.pop("t"), "tau": numbers.pop("tau"),
           "kind": np.array(kinds, dtype=str), "who": np.array(who, dtype=str)}
    out.update(numbers)
    return out


def _frame(columns):
    import pandas as pd  # an optional dependency: only these methods need it
    return pd.DataFrame(columns)


class Result:
    """One run of one model (:func:`metrosync.run`, and each model of :func:`metrosync.compare`).

    ``.trajectory``, ``.envelope``, ``.events``: the columns of trajectory.csv, envelope.csv and
    events.csv as ``{name: numpy array}`` (docs/outputs.md; the engine's numbers, which the files
    print to 12 significant digits); the slow flow has no trajectory and no events (None).
    ``.summary``: summary.json as a dict; ``.regime``, ``.complete``, ``.model``, ``.engine``.

    >>> res = metrosync.run("yaml/rigs/experiment.yaml", duration=60)
    >>> res.regime, res.envelope["A_1"][-1]
    ('antiphase', ...)
    >>> res.to_pandas().plot(x="t", y=["theta_1", "theta_2"])
    """

    def __init__(self, summary, rows, out=None):
        self.summary = summary
        self.trajectory = _columns(rows["trajectory"])
        self.envelope = _columns(rows["envelope"])
        self.events = _events(rows["events"])
        self.out = out  # the folder of the CLI's files, when asked for one

    regime = property(lambda self: self.summary.get("regime") or
                      self.summary.get("network", {}).get("regime"),
                      doc="the regime (docs/regimes.md); a network's label for a network")
    complete = property(lambda self: bool(self.summary.get("complete", False)),
                        doc="False when the run stopped early")
    model = property(lambda self: self.summary.get("model"), doc="'full' or 'slow'")
    engine = property(lambda self: self.summary.get("engine"), doc="the engine that ran")

    def to_pandas(self):
        """The run's time series as a pandas DataFrame: the trajectory (t, x, xdot, theta_i,
        thetadot_i, platform) for the full model; the envelope for the slow flow, which has no
        trajectory.

        >>> traj = metrosync.run(rig, duration=30).to_pandas()
        >>> traj[traj.t < 5].plot(x="t", y="theta_1")
        """
        return _frame(self.trajectory if self.trajectory is not None else self.envelope)

    def envelope_frame(self):
        """envelope.csv as a DataFrame: tau, A_1..A_N, psi_2..psi_N, r (and t_s for a
        physical rig).

        >>> env = metrosync.run(rig).envelope_frame()
        >>> env.plot(x="tau", y=["A_1", "A_2"])
        """
        return _frame(self.envelope)

    def events_frame(self):
        """events.csv as a DataFrame (full model): every tick and platform switch with the states
        just before and after it; None for the slow flow.

        >>> ev = metrosync.run(rig).events_frame()
        >>> (ev.kind == "tick").sum()
        """
        return None if self.events is None else _frame(self.events)

    def __repr__(self):
        rows = len(next(iter(self.envelope.values()))) if self.envelope else 0
        return "Result(%s, regime=%r, complete=%r, %d envelope rows)" % (
            self.model, self.regime, self.complete, rows)


class CompareResult:
    """The full model and the slow flow on one rig (:func:`metrosync.compare`): ``.full`` and
    ``.slow`` (each a :class:`Result`), ``.comparison`` (comparison.csv's columns: tau, A_i_full,
    A_i_slow, psi_j_full, psi_j_slow), ``.summary`` (summary.json: ``comparison`` holds the
    largest differences).

    >>> c = metrosync.compare("yaml/rigs/paper/f4.3-mu0.3.yaml")
    >>> c.summary["comparison"]["max_abs_dA"], c.full.regime, c.slow.regime
    >>> c.to_pandas().plot(x="tau", y=["A_1_full", "A_1_slow"])
    """

    def __init__(self, summary, rows, out=None):
        self.summary = summary
        models = summary.get("models", {})
        self.full = Result(models.get("full", {}), rows["full"], out)
        self.slow = Result(models.get("slow", {}), rows["slow"], out)
        self.comparison = _columns(rows["comparison"])
        self.out = out

    complete = property(lambda self: bool(self.summary.get("complete", False)))

    def to_pandas(self):
        """comparison.csv as a DataFrame: the two models' envelopes side by side on one tau grid.

        >>> metrosync.compare(rig).to_pandas().head()
        """
        return _frame(self.comparison)

    def __repr__(self):
        return "CompareResult(full %r, slow %r)" % (self.full.regime, self.slow.regime)


def _points(points, size):
    """A sweep's or basin's points ({"numbers": (names, array), "regime", "clusters",
    "message"}) as {column: array of `size`} placed by their index (NaN, '' where none ran)."""
    names, values = points["numbers"]
    index = values[:, names.index("index")].astype(np.int64)
    out = {}
    for k, name in enumerate(names):
        column = np.full(size, np.nan)
        column[index] = values[:, k]
        out[name] = column
    for name in ("regime", "clusters", "message"):
        column = np.full(size, "", dtype=object)
        column[index] = points[name]
        out[name] = column.astype(str)
    out["complete"] = out["complete"] == 1.0
    out["index"] = np.arange(size)
    return out, np.sort(index)


class SweepResult:
    """A grid of runs (:func:`metrosync.sweep`): every column of regimes.csv as an array shaped
    by the grid (the first key of ``vary`` along axis 0): ``res["A_1"]``, ``.regime`` (str),
    ``.columns`` {name: array}; ``.keys``, ``.values`` (each axis's values), ``.shape``;
    ``.summary`` (sweep.json's status: grid, points done and failed, regime counts);
    ``.to_pandas()`` regimes.csv's rows.

    >>> grid = metrosync.sweep(rig, vary={"platform.friction.mu": (0, 1, 11),
    ...                                   "metronomes.0.start.phi": [0.0, 3.14]})
    >>> grid.shape, grid.regime[:, 1], grid["psi_2"][3, 0]
    """

    def __init__(self, summary, points, out=None):
        self.summary = summary
        axes = summary["grid"]["axes"]
        self.keys = [a["key"] for a in axes]
        self.values = [np.array([float(v) for v in a["values"]]) for a in axes]
        self.shape = tuple(len(v) for v in self.values)
        flat, self._done = _points(points, int(np.prod(self.shape)))
        cols = {}
        for axis, grid_values in zip(self.keys, np.meshgrid(*self.values, indexing="ij")):
            cols[axis] = grid_values
        for name, column in flat.items():
            cols[name] = column.reshape(self.shape)
        n = summary["metronomes"]
        order = (self.keys + ["regime"] + ["A_%d" % i for i in range(1, n + 1)]
                 + ["psi_%d" % j for j in range(2, n + 1)] + ["r", "s", "clusters", "tau"]
                 + ["complete", "index", "message"])
        self.columns = {name: cols[name] for name in order}  # regimes.csv's order
        self.regime = self.columns["regime"]
        self.out = out

    def __getitem__(self, name):
        return self.columns[name]

    complete = property(lambda self: bool(self.summary.get("complete", False)))

    def to_pandas(self):
        """regimes.csv as a DataFrame: one row per grid point that ran, in grid order.

        >>> df = metrosync.sweep(rig, vary={"platform.friction.mu": (0, 1, 11)}).to_pandas()
        >>> df.groupby("regime").size()
        """
        return _frame({name: c.reshape(-1)[self._done] for name, c in self.columns.items()})

    def __repr__(self):
        return "SweepResult(%s, shape=%r)" % (", ".join(self.keys), self.shape)


class BasinResult:
    """Basin stability (:func:`metrosync.basin`): ``.samples`` (basin.csv's columns: sample, the
    drawn values by key, regime, A_i, psi_j, complete), ``.fractions`` (each regime's count,
    fraction and 95% Wilson interval ``ci95``), ``.summary`` (basin.json's account).

    >>> b = metrosync.basin(rig, random={"metronomes.0.start.phi": (0, 6.283)}, samples=200)
    >>> b.fraction("in-phase"), b.fractions[0]
    """

    def __init__(self, summary, points, drawn, out=None):
        self.summary = summary
        samples = summary["samples"]
        flat, done = _points(points, samples)
        n = summary["metronomes"]
        cols = {"sample": flat["index"][done]}
        names, values = drawn
        for k, key in enumerate(names):
            cols[key] = values[:, k]
        for name in (["regime"] + ["A_%d" % i for i in range(1, n + 1)]
                     + ["psi_%d" % j for j in range(2, n + 1)] + ["complete"]):
            cols[name] = flat[name][done]
        self.samples = cols
        self.fractions = summary["fractions"]
        self.out = out

    def fraction(self, regime):
        """The fraction of samples that ended in `regime` (0 when none did)."""
        return next((f["fraction"] for f in self.fractions if f["regime"] == regime), 0.0)

    def to_pandas(self):
        """basin.csv as a DataFrame: one row per sample.

        >>> metrosync.basin(rig, random=..., samples=100).to_pandas().regime.value_counts()
        """
        return _frame(self.samples)

    def __repr__(self):
        return "BasinResult(%d samples: %s)" % (self.summary["samples"], ", ".join(
            "%s %.3g" % (f["regime"], f["fraction"]) for f in self.fractions))


def _read_mixed_csv(path):
    """A CSV with text columns as {column: array}: float where every value is a number, str
    otherwise; None when the file does not exist."""
    if not os.path.exists(path):
        return None
    with open(path, encoding="utf-8", newline="") as f:
        rows = list(csv.reader(f))
    if not rows:
        return None
    header, rows = rows[0], rows[1:]
    out = {}
    for k, name in enumerate(header):
        column = [r[k] for r in rows]
        try:
            out[name] = np.array([float(v) for v in column])
        except ValueError:
            out[name] = np.array(column, dtype=str)
    return out


def _read_json(path):
    with open(path, encoding="utf-8") as f:
        return json.load(f)


class ContinuationResult:
    """The slow flow's locked states followed in a rig key (:func:`metrosync.continue_`):
    ``.branches`` (branches.csv's columns), ``.bifurcations`` (bifurcations.json: a list of
    dicts with type, value, A, psi, eigenvalues, ...), ``.cycles`` (cycles.csv: the limit cycle
    born at each Hopf point), ``.summary``; with ``fold=``: ``.fold_curve`` and ``.hopf_curve``
    (the two-parameter curves).

    >>> c = metrosync.continue_("yaml/rigs/paper/f4.4-alpha4.yaml", param="metronomes.1.alpha",
    ...                         from_=3.0, to=4.0)
    >>> [(b["type"], b["value"]) for b in c.bifurcations]
    [('fold', 3.9068...)]
    """

    def __init__(self, folder, out=None):
        self.summary = _read_json(os.path.join(folder, "summary.json"))
        self.bifurcations = _read_json(os.path.join(folder, "bifurcations.json"))
        self.branches = _read_mixed_csv(os.path.join(folder, "branches.csv"))
        self.cycles = _read_mixed_csv(os.path.join(folder, "cycles.csv"))
        self.fold_curve = _read_mixed_csv(os.path.join(folder, "fold_curve.csv"))
        self.hopf_curve = _read_mixed_csv(os.path.join(folder, "hopf_curve.csv"))
        # families.csv: the neutral families (None when the continuation met none)
        self.families = _read_mixed_csv(os.path.join(folder, "families.csv"))
        self.out = out

    def to_pandas(self):
        """branches.csv as a DataFrame: one row per point, along each branch.

        >>> c.to_pandas().plot(x="metronomes.1.alpha", y="A_1")
        """
        return _frame(self.branches)

    def __repr__(self):
        points = len(next(iter(self.branches.values()))) if self.branches else 0
        return "ContinuationResult(%d points, %d special points)" % (
            points, len(self.bifurcations))


class FitResult:
    """Rig keys estimated from measured data (:func:`metrosync.fit`): ``.summary`` is fit.json
    (values, std_errors, identifiable, correlation, rms, converged, ...); ``.values``,
    ``.std_errors``, ``.identifiable`` by key; ``.rms``, ``.converged``; ``.rig`` the fitted rig.

    >>> f = metrosync.fit(rig, "data.csv", free=["platform.friction.mu"])
    >>> f.values["platform.friction.mu"], f.std_errors["platform.friction.mu"]
    """

    def __init__(self, summary, rig, out=None):
        self.summary = summary
        self.values = summary["values"]
        self.std_errors = summary["std_errors"]
        self.identifiable = summary["identifiable"]
        self.rig = rig
        self.out = out

    rms = property(lambda self: self.summary["rms"], doc="the rms residual (rad; m for x alone)")
    converged = property(lambda self: bool(self.summary["converged"]))

    def to_pandas(self):
        """One row per free key: value, std_error, identifiable, start.

        >>> metrosync.fit(rig, "data.csv", free=[...]).to_pandas()
        """
        import pandas as pd
        keys = self.summary["free"]
        return pd.DataFrame({"value": [self.values[k] for k in keys],
                             "std_error": [self.std_errors[k] for k in keys],
                             "identifiable": [self.identifiable[k] for k in keys],
                             "start": [self.summary["start"][k] for k in keys]}, index=keys)

    def __repr__(self):
        return "FitResult(%s, rms=%.3g)" % (", ".join(
            "%s=%.6g" % (k, v) for k, v in self.values.items() if v is not None), self.rms)
