"""sweep, continue_, Ctrl-C and to_pandas against the command-line program: a sweep's arrays
are regimes.csv's rows placed on the grid, continue_'s bifurcations are bifurcations.json, a
SIGINT sent while a long run is in progress ends it within a couple of seconds as
KeyboardInterrupt, and to_pandas() equals the CSV files read by pandas."""
import csv
import json
import os
import signal
import subprocess
import threading
import time

import numpy as np
import pytest

import metrosync

SRC = os.environ["METROSYNC_SOURCE_DIR"]
BIN = os.environ["METROSYNC_BINARY"]
MAP_RIG = os.path.join(SRC, "yaml/rigs/experiment-map.yaml")
F44 = os.path.join(SRC, "yaml/rigs/paper/f4.4-alpha4.yaml")
F43 = os.path.join(SRC, "yaml/rigs/paper/f4.3-mu0.2.yaml")
EXPERIMENT = os.path.join(SRC, "yaml/rigs/experiment.yaml")


def read_rows(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], rows[1:]


@pytest.mark.parametrize("model", ["slow", "full"])
def test_sweep_shape_and_labels_equal_regimes_csv(tmp_path, model):
    # a range across and a list up, as the CLI takes them
    vary = {"platform.friction.mu": (0.0, 1.5, 4), "metronomes.0.start.phi": [0.0, 1.5, 3.0]}
    cli = tmp_path / "cli"
    subprocess.run([BIN, "sweep", MAP_RIG, "--quiet", "--model", model, "--jobs", "2",
                    "--set", "simulation.tau=60",
                    "--vary", "platform.friction.mu=0:1.5:4",
                    "--vary", "metronomes.0.start.phi=0,1.5,3", "--out", str(cli)], check=True)
    res = metrosync.sweep(metrosync.load_rig(MAP_RIG), vary=vary, model=model, jobs=2, tau=60)
    assert res.shape == (4, 3)
    assert res.regime.shape == (4, 3)
    assert res.keys == list(vary)
    np.testing.assert_array_equal(res.values[0], [0.0, 0.5, 1.0, 1.5])
    np.testing.assert_array_equal(res.values[1], [0.0, 1.5, 3.0])
    header, rows = read_rows(cli / "regimes.csv")
    assert len(rows) == 12
    at = header.index("index")
    for r in rows:
        i, j = divmod(int(r[at]), 3)
        assert res.regime[i, j] == r[header.index("regime")]
        assert res["platform.friction.mu"][i, j] == res.values[0][i]
        for name in ("A_1", "A_2", "psi_2", "r", "tau"):
            assert res[name][i, j] == float(r[header.index(name)]), name
    # more than one regime on this grid: the labels are not all one value by accident
    assert len(set(res.regime.ravel())) > 1
    values = lambda grid: [a["values"] for a in grid["axes"]]  # the spec's text may differ
    assert values(json.load(open(cli / "sweep.json"))["grid"]) == values(res.summary["grid"])


def test_continue_equals_bifurcations_json(tmp_path):
    cli = tmp_path / "cli"
    args = ["--param", "metronomes.1.alpha", "--from", "3.0", "--to", "4.0"]
    subprocess.run([BIN, "continue", F44, "--quiet", *args, "--out", str(cli)], check=True)
    res = metrosync.continue_(metrosync.load_rig(F44), param="metronomes.1.alpha", to=4.0,
                              from_=3.0)
    assert res.bifurcations == json.load(open(cli / "bifurcations.json"))
    assert [b["type"] for b in res.bifurcations] == ["fold"]  # docs/continuation.md
    header, rows = read_rows(cli / "branches.csv")
    assert len(res.branches["A_1"]) == len(rows)
    np.testing.assert_array_equal(res.branches["A_2"],
                                  [float(r[header.index("A_2")]) for r in rows])
    assert list(res.branches["platform"]) == [r[header.index("platform")] for r in rows]


def test_continue_cycles_and_curves_equal_the_files(tmp_path):
    """continue_ returns the cycles (cycles.csv) and the two-parameter curves (fold_curve.csv,
    hopf_curve.csv) the command writes; no_cycles=True follows none."""
    cli = tmp_path / "cli"
    args = ["--param", "platform.friction.mu", "--to", "0.35", "--fold", "metronomes.*.nu",
            "--to2", "0.8"]
    subprocess.run([BIN, "continue", F43, "--quiet", *args, "--out", str(cli)], check=True)
    rig = metrosync.load_rig(F43)
    res = metrosync.continue_(rig, param="platform.friction.mu", to=0.35,
                              fold="metronomes.*.nu", to2=0.8)
    for name, got in (("cycles.csv", res.cycles), ("hopf_curve.csv", res.hopf_curve)):
        header, rows = read_rows(cli / name)
        assert len(rows) > 0, name
        for k, column in enumerate(header):
            np.testing.assert_array_equal(got[column], [float(r[k]) for r in rows], err_msg=name)
    assert len(res.summary["cycles"]) > 0
    none = metrosync.continue_(rig, param="platform.friction.mu", to=0.35, no_cycles=True)
    assert none.summary["cycles"] == []
    assert none.cycles is None or len(next(iter(none.cycles.values()))) == 0


def interrupted_within(call, delay=0.5):
    """Sends SIGINT from another thread `delay` s into call(); returns the seconds from the
    signal to KeyboardInterrupt."""
    sent = []

    def send():
        sent.append(time.monotonic())
        os.kill(os.getpid(), signal.SIGINT)

    timer = threading.Timer(delay, send)
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            call()
    finally:
        timer.cancel()
    assert sent, "the run ended before the signal: not a long run"
    return time.monotonic() - sent[0]


def test_ctrl_c_stops_a_long_run(tmp_path):
    # ~30 s of computing uninterrupted (600 s of the experiment take ~0.35 s)
    rig = metrosync.load_rig(EXPERIMENT, {"simulation.duration": 30000})
    late = interrupted_within(lambda: metrosync.run(rig, model="full", out=str(tmp_path / "o")))
    assert late < 2.0
    # the files kept are marked incomplete, as the CLI's after a SIGINT
    assert json.load(open(tmp_path / "o" / "summary.json"))["complete"] is False
    # and Python's own handler is back: a later SIGINT is Python's KeyboardInterrupt again
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler


def test_ctrl_c_stops_a_long_sweep():
    # 400 full-model points on one thread: ~15 s uninterrupted
    rig = metrosync.load_rig(MAP_RIG)
    vary = {"platform.friction.mu": (0.0, 3.0, 20), "metronomes.0.start.phi": (0.0, 6.0, 20)}
    late = interrupted_within(lambda: metrosync.sweep(rig, vary=vary, model="full", jobs=1))
    assert late < 2.0


def test_to_pandas_equals_the_csv(tmp_path):
    import pandas as pd  # tools/setup.sh installs python3-pandas
    out = tmp_path / "o"
    res = metrosync.run(metrosync.load_rig(EXPERIMENT, {"simulation.duration": 8}), model="full",
                        out=str(out))
    trajectory, envelope = res.to_pandas()
    for frame, name in ((trajectory, "trajectory.csv"), (envelope, "envelope.csv")):
        cli = pd.read_csv(out / name, float_precision="round_trip")
        assert len(cli) > 10
        pd.testing.assert_frame_equal(frame, cli.astype(float), check_exact=True)
