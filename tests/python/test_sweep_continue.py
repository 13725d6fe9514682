"""continue_ and Ctrl-C against the command-line program: continue_'s bifurcations are
bifurcations.json, and a SIGINT sent while a long run or sweep is in progress ends it within a
couple of seconds as KeyboardInterrupt, with Python's own handler back afterwards."""
import json
import os
import signal
import threading
import time

import numpy as np
import pytest

import metrosync
from conftest import EXPERIMENT, F44, MAP_RIG, cli, read_rows


def test_continue_equals_bifurcations_json(tmp_path):
    cli_out = tmp_path / "cli"
    args = ["--param", "metronomes.1.alpha", "--from", "3.0", "--to", "4.0"]
    cli("continue", F44, "--quiet", *args, "--out", str(cli_out))
    res = metrosync.continue_(metrosync.load_rig(F44), param="metronomes.1.alpha", to=4.0,
                              from_=3.0)
    assert res.bifurcations == json.load(open(cli_out / "bifurcations.json"))
    assert [b["type"] for b in res.bifurcations] == ["fold"]  # docs/continuation.md
    header, rows = read_rows(cli_out / "branches.csv")
    assert len(res.branches["A_1"]) == len(rows)
    np.testing.assert_array_equal(res.branches["A_2"],
                                  [float(r[header.index("A_2")]) for r in rows])
    assert list(res.branches["platform"]) == [r[header.index("platform")] for r in rows]


def test_continue_passes_no_cycles_and_the_second_key(tmp_path):
    # f4.3's in-phase state and its Hopf point at mu = 0.28909 (docs/continuation.md), cycles
    # left out; fold= follows the Hopf point in a second key as the CLI's --fold
    args = ["--param", "platform.friction.mu", "--from", "0.28", "--to", "0.3", "--all",
            "--no-cycles", "--fold", "metronomes.1.alpha", "--to2", "0.05"]
    f43 = F44.replace("f4.4-alpha4", "f4.3-mu0.2")
    cli("continue", f43, "--quiet", *args, "--out", str(tmp_path / "cli"))
    res = metrosync.continue_(f43, param="platform.friction.mu", from_=0.28, to=0.3, all=True,
                              no_cycles=True, fold="metronomes.1.alpha", to2=0.05)
    assert res.bifurcations == json.load(open(tmp_path / "cli" / "bifurcations.json"))
    assert [b["type"] for b in res.bifurcations] == ["hopf"]
    assert res.cycles is None or len(res.cycles.get("cycle", [])) == 0
    header, rows = read_rows(tmp_path / "cli" / "hopf_curve.csv")
    assert len(rows) > 2 and len(res.hopf_curve["metronomes.1.alpha"]) == len(rows)
    np.testing.assert_array_equal(res.hopf_curve["platform.friction.mu"],
                                  [float(r[header.index("platform.friction.mu")]) for r in rows])


def test_continue_follows_the_full_models_orbits(tmp_path):
    # f4.3's in-phase orbit at epsilon = 0.073 loses stability at a torus point, then folds
    # (docs/continuation.md); the same files as `continue --model full`
    f43 = F44.replace("f4.4-alpha4", "f4.3-mu0.2")
    args = ["--model", "full", "--param", "platform.friction.mu", "--to", "0.3"]
    cli("continue", f43, "--quiet", *args, "--out", str(tmp_path / "cli"))
    res = metrosync.continue_(f43, model="full", param="platform.friction.mu", to=0.3)
    assert res.bifurcations == json.load(open(tmp_path / "cli" / "bifurcations.json"))
    assert [b["type"] for b in res.bifurcations] == ["torus", "fold"]
    header, rows = read_rows(tmp_path / "cli" / "branches.csv")
    assert "period" in header and len(res.branches["period"]) == len(rows)


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
