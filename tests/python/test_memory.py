"""Results from memory against the command-line program's files: the arrays are the numbers the
CLI printed (each file, line for line, is the arrays printed the CLI's way), they carry the
engine's full precision (they were not read back from the files), and a call without out= makes
no temporary folder and writes nothing."""
import json

import numpy as np
import pytest

import metrosync
from conftest import (EXPERIMENT, MAP_RIG, assert_columns_print_as, cli, printed, read_rows,
                      rig_dict)


def more_digits_than_printed(columns):
    """Some value differs from its 12-digit print: not parsed back from a CSV file."""
    return any(float(printed("", v)) != v for c in columns.values() for v in np.ravel(c)
               if np.isfinite(v))


@pytest.mark.parametrize("model", ["full", "slow"])
def test_run_from_memory_prints_as_the_cli_files(tmp_path, model, no_temporary_folder):
    cli("run", EXPERIMENT, "--quiet", "--no-plot", "--model", model, "--set",
        "simulation.duration=8", "--out", str(tmp_path / "cli"))
    res = metrosync.run(rig_dict(EXPERIMENT), model=model, duration=8)
    assert_columns_print_as(res.envelope, tmp_path / "cli" / "envelope.csv")
    assert more_digits_than_printed(res.envelope)
    if model == "full":
        assert_columns_print_as(res.trajectory, tmp_path / "cli" / "trajectory.csv")
        assert_columns_print_as(res.events, tmp_path / "cli" / "events.csv", ("kind", "who"),
                                tau_digits=12)
        assert more_digits_than_printed(res.trajectory)
    summary = json.load(open(tmp_path / "cli" / "summary.json"))
    for key in ("regime", "final", "counts", "scaled", "resolved_rig", "energy", "complete"):
        assert res.summary.get(key) == summary.get(key), key


def test_out_writes_the_cli_files_beside_the_arrays(tmp_path):
    cli("run", EXPERIMENT, "--quiet", "--no-plot", "--set", "simulation.duration=5", "--out",
        str(tmp_path / "cli"))
    res = metrosync.run(EXPERIMENT, duration=5, out=tmp_path / "py")
    for name in ("trajectory.csv", "envelope.csv", "events.csv"):
        assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes()
    assert_columns_print_as(res.trajectory, tmp_path / "py" / "trajectory.csv")
    assert (tmp_path / "py" / "envelope.png").exists()
    assert res.summary == json.load(open(tmp_path / "py" / "summary.json"))


def test_compare_from_memory_prints_as_the_cli_files(tmp_path, no_temporary_folder):
    cli("compare", EXPERIMENT, "--quiet", "--no-plot", "--set", "simulation.duration=8", "--out",
        str(tmp_path / "cli"))
    res = metrosync.compare(EXPERIMENT, duration=8)
    # comparison.csv's t_s is the CLI's 10-digit tau read back from envelope_full.csv times the
    # time scale; the array's is the engine's tau times it (envelope_full.csv's own t_s)
    assert_columns_print_as(res.comparison, tmp_path / "cli" / "comparison.csv", near=("t_s",))
    np.testing.assert_allclose(res.comparison["t_s"], res.full.envelope["t_s"][1:-1], rtol=1e-15)
    assert_columns_print_as(res.full.envelope, tmp_path / "cli" / "envelope_full.csv")
    assert_columns_print_as(res.slow.envelope, tmp_path / "cli" / "envelope_slow.csv")
    assert_columns_print_as(res.full.trajectory, tmp_path / "cli" / "trajectory.csv")
    summary = json.load(open(tmp_path / "cli" / "summary.json"))
    assert res.summary["models"]["full"]["final"] == summary["models"]["full"]["final"]
    # the CLI compares the files' 12-digit numbers (each off by up to 5e-12 for values below
    # 10), memory the engine's: their differences agree to 2e-11
    ours, theirs = res.summary["comparison"], summary["comparison"]
    assert ours["rows"] == theirs["rows"] > 10
    for key in ("max_abs_dA", "max_abs_dpsi"):
        np.testing.assert_allclose(ours[key], theirs[key], rtol=0, atol=2e-11)
    # ... and where they are, to the 10 digits of tau in the files
    np.testing.assert_allclose(ours["tau_max_dA"], theirs["tau_max_dA"], rtol=1e-9)


def test_sweep_from_memory_prints_as_regimes_csv(tmp_path, no_temporary_folder):
    vary = {"platform.friction.mu": (0.0, 1.5, 4), "metronomes.0.start.phi": [0.0, 1.5, 3.0]}
    cli("sweep", MAP_RIG, "--quiet", "--no-plot", "--jobs", "2", "--set", "simulation.tau=60",
        "--vary", "platform.friction.mu=0:1.5:4", "--vary", "metronomes.0.start.phi=0,1.5,3",
        "--out", str(tmp_path / "cli"))
    res = metrosync.sweep(MAP_RIG, vary=vary, jobs=2, tau=60)
    assert res.shape == (4, 3) and res.keys == list(vary)
    np.testing.assert_array_equal(res.values[0], [0.0, 0.5, 1.0, 1.5])
    header, rows = read_rows(tmp_path / "cli" / "regimes.csv")
    assert list(res.columns) == header
    frame = res.to_pandas()
    assert len(frame) == len(rows) == 12
    for i, row in enumerate(rows):
        for k, name in enumerate(header):
            value = frame[name][i]
            if name in ("regime", "clusters", "message"):
                assert value == row[k], (i, name)
            elif name in ("complete", "index"):
                assert int(value) == int(row[k]), (i, name)
            elif name in vary:
                assert value == float(row[k]), (i, name)
            elif row[k] in ("", "nan"):  # no value: empty (issue 39), nan in older files
                assert np.isnan(value), (i, name)
            else:
                assert printed(name, value) == row[k], (i, name, value, row[k])
    assert len(set(res.regime.ravel())) > 1  # the labels differ across the grid
    assert res["A_1"][2, 1] == frame["A_1"][2 * 3 + 1]  # the grid's shape, first key along axis 0
    status = json.load(open(tmp_path / "cli" / "sweep.json"))
    for key in ("regimes", "model", "engine", "metronomes", "complete"):
        assert res.summary[key] == status[key], key
    for key in ("grid", "done", "failed", "missing"):
        assert res.summary["points"][key] == status["points"][key], key
    values = lambda grid: [a["values"] for a in grid["axes"]]  # the specs' texts may differ
    assert values(res.summary["grid"]) == values(status["grid"])


def test_basin_from_memory_prints_as_basin_csv(tmp_path, no_temporary_folder):
    cli("basin", MAP_RIG, "--quiet", "--no-plot", "--random", "metronomes.0.start.phi=0:2pi",
        "--samples", "12", "--seed", "7", "--jobs", "2", "--set", "simulation.tau=60", "--out",
        str(tmp_path / "cli"))
    res = metrosync.basin(MAP_RIG, random={"metronomes.0.start.phi": "0:2pi"}, samples=12,
                          seed=7, jobs=2, tau=60)
    header, rows = read_rows(tmp_path / "cli" / "basin.csv")
    assert list(res.samples) == header and len(rows) == 12
    for i, row in enumerate(rows):
        for k, name in enumerate(header):
            value = res.samples[name][i]
            if name in ("regime", "sample", "complete"):
                assert str(int(value) if name != "regime" else value) == row[k]
            elif name == "metronomes.0.start.phi":
                assert value == float(row[k])
            else:
                assert printed(name, value) == row[k], (i, name)
    assert res.fractions == json.load(open(tmp_path / "cli" / "basin.json"))["fractions"]
