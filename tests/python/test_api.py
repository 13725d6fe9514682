"""The calls as a numpy/pandas user meets them: each takes a dict, a path or a Rig with the same
result; to_pandas() is a DataFrame; an error in a dict rig names the dict's key and says what is
wrong in Python terms; overrides act like the CLI's --set, wildcards included."""
import json
import os
import subprocess
import traceback

import numpy as np
import pandas as pd
import pytest

import metrosync
from conftest import EXPERIMENT, F44, MAP_RIG, cli, rig_dict

# Each call on a rig given three ways, with arguments that keep it short (well under a second).
CALLS = {
    "run": (EXPERIMENT, lambda rig: metrosync.run(rig, duration=6)),
    "run-slow": (MAP_RIG, lambda rig: metrosync.run(rig, model="slow", tau=40)),
    "compare": (EXPERIMENT, lambda rig: metrosync.compare(rig, duration=6)),
    "sweep": (MAP_RIG, lambda rig: metrosync.sweep(
        rig, vary={"platform.friction.mu": (0.0, 1.0, 3)}, jobs=2, tau=40)),
    "basin": (MAP_RIG, lambda rig: metrosync.basin(
        rig, random={"metronomes.0.start.phi": (0.0, 6.283185307179586)}, samples=4, jobs=2,
        tau=40)),
    "continue_": (F44, lambda rig: metrosync.continue_(
        rig, param="metronomes.1.alpha", from_=3.0, to=3.5)),
}


def essence(result):
    """What a result says, comparable across calls (arrays as lists)."""
    if isinstance(result, metrosync.CompareResult):
        return essence(result.full), essence(result.slow), essence(result.comparison)
    if isinstance(result, metrosync.Result):
        return result.regime, essence(result.envelope), essence(result.trajectory)
    if isinstance(result, metrosync.ContinuationResult):
        return result.bifurcations, essence(result.branches)
    if isinstance(result, (metrosync.SweepResult, metrosync.BasinResult)):
        return essence(result.to_pandas().to_dict("list"))
    if isinstance(result, dict):  # NaN (e.g. branches.csv's weight off a border) as None
        return {k: [None if isinstance(x, float) and x != x else x
                    for x in np.asarray(v).tolist()] for k, v in result.items()}
    return result


@pytest.mark.parametrize("call", sorted(CALLS))
def test_each_call_takes_a_dict_a_path_and_a_rig(call):
    path, do = CALLS[call]
    from_path = essence(do(path))
    assert from_path == essence(do(metrosync.load_rig(path)))
    assert from_path == essence(do(rig_dict(path)))


def test_fit_takes_a_dict_a_path_and_a_rig_and_recovers_the_truth(tmp_path):
    # data made by the engine: the fit must find the rig's own mu from a start 40% off
    truth = metrosync.run(EXPERIMENT, duration=8).trajectory
    data = {k: truth[k][::5] for k in ("t", "theta_1", "theta_2")}
    overrides = {"simulation.duration": 8, "platform.friction.mu": 0.00091}
    fits = [metrosync.fit(metrosync.load_rig(rig, overrides), data, free="platform.friction.mu")
            for rig in (EXPERIMENT, rig_dict(EXPERIMENT), metrosync.load_rig(EXPERIMENT))]
    assert fits[0].values == fits[1].values == fits[2].values
    mu = fits[0].values["platform.friction.mu"]
    assert mu == pytest.approx(6.5e-4, rel=1e-6)
    assert fits[0].rig.to_dict()["platform"]["friction"]["mu"] == mu
    # the same as the CLI's fit.json on the same data
    pd.DataFrame(data).to_csv(tmp_path / "data.csv", index=False, float_format="%.17g")
    cli("fit", EXPERIMENT, str(tmp_path / "data.csv"), "--free", "platform.friction.mu", "--set",
        "simulation.duration=8", "--set", "platform.friction.mu=0.00091", "--out",
        str(tmp_path / "cli"), "-q", "--no-plot")
    assert json.load(open(tmp_path / "cli" / "fit.json"))["values"] == fits[0].values


def test_to_pandas_is_a_data_frame_of_the_trajectory():
    res = metrosync.run(EXPERIMENT, duration=5)
    frame = res.to_pandas()
    assert isinstance(frame, pd.DataFrame)
    assert list(frame.columns) == ["t", "x", "xdot", "theta_1", "thetadot_1", "theta_2",
                                   "thetadot_2", "platform"]
    np.testing.assert_array_equal(frame["theta_2"].to_numpy(), res.trajectory["theta_2"])
    env = res.envelope_frame()
    assert list(env.columns[:5]) == ["tau", "A_1", "A_2", "psi_2", "r"]
    assert len(env) == len(res.envelope["tau"]) > 5
    events = res.events_frame()
    assert set(events["kind"]) <= {"tick", "stick", "slip"} and (events["kind"] == "tick").any()
    # the slow flow has no trajectory: its time series is the envelope
    slow = metrosync.run(MAP_RIG, model="slow", tau=20)
    assert slow.trajectory is None and slow.events_frame() is None
    pd.testing.assert_frame_equal(slow.to_pandas(), slow.envelope_frame())


def test_an_error_in_a_dict_rig_names_the_dict_key():
    rig = rig_dict(EXPERIMENT)
    rig["metronomes"][1]["pendulum"]["mass"] = -0.02
    with pytest.raises(metrosync.RigError) as e:
        metrosync.run(rig)
    assert str(e.value) == "rig['metronomes'][1]['pendulum']['mass'] = -0.02: must be > 0"
    rig = rig_dict(EXPERIMENT)
    rig["platform"]["friction"]["mu"] = "low"
    with pytest.raises(metrosync.RigError) as e:
        metrosync.load_rig(rig)
    assert str(e.value) == "rig['platform']['friction']['mu'] = 'low': must be a number"
    del rig["platform"]
    with pytest.raises(metrosync.RigError, match=r"^rig\['platform'\]: missing"):
        metrosync.load_rig(rig)


def test_an_error_in_an_override_or_option_is_said_in_python_terms():
    rig = rig_dict(EXPERIMENT)
    cases = [
        (lambda: metrosync.load_rig(rig, {"platform.friction.mu": -1}),
         "overrides['platform.friction.mu'] = -1: must be >= 0"),
        (lambda: metrosync.run(rig, duration=-1), "duration=-1: must be > 0"),
        (lambda: metrosync.run(rig, engine="bogus"),
         "engine='bogus': unknown engine (one of: direct, simbody, slowflow)"),
        (lambda: metrosync.sweep(rig, vary={"platform.friction.mu": (-1, 1, 3)}),
         "vary['platform.friction.mu'] at -1: must be >= 0"),
        (lambda: metrosync.continue_(rig, param="platform.friction.mu", to=-0.3),
         "param='platform.friction.mu' at -0.3: must be >= 0"),
    ]
    for call, said in cases:
        with pytest.raises(metrosync.RigError) as e:
            call()
        message = str(e.value)
        assert message.split("\n")[0] == said
        for word in ("--set", "--to", "--vary", "--param", "--engine", "/tmp", "metrosync-"):
            assert word not in message, message


def test_an_error_is_a_value_error_named_as_the_package_names_it():
    with pytest.raises(ValueError) as e:
        metrosync.load_rig(EXPERIMENT, {"platform.friction.mu": -1})
    assert isinstance(e.value, metrosync.RigError)
    said = traceback.format_exception_only(type(e.value), e.value)[-1]
    assert said.startswith("metrosync.RigError: " + EXPERIMENT + ": overrides["), said


def test_a_bad_rig_file_is_named_with_its_line(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text(open(EXPERIMENT).read().replace("mass: 0.0226", "mass: -0.0226", 1))
    with pytest.raises(metrosync.RigError) as e:
        metrosync.run(str(bad))
    assert str(e.value).startswith(str(bad) + ":14:")
    assert str(e.value).endswith("metronomes.0.pendulum.mass = -0.0226: must be > 0")
    # continue_ reads the file itself: still named by its path
    with pytest.raises(metrosync.RigError) as e:
        metrosync.continue_(EXPERIMENT, param="platform.friction.mu", to=-0.3)
    assert str(e.value) == EXPERIMENT + ": param='platform.friction.mu' at -0.3: must be >= 0"


def test_overrides_act_like_set():
    a = metrosync.load_rig(EXPERIMENT, {"platform.friction.mu": 0.3}).scaled()
    out = cli("scale", "--json", EXPERIMENT, "--set", "platform.friction.mu=0.3")
    assert json.loads(out) == a
    assert a["mu"] != metrosync.load_rig(EXPERIMENT).scaled()["mu"]


def test_wildcard_overrides_set_every_metronome():
    # on a dict rig, through every call that takes overrides: the same as one key per index
    each = {"metronomes.0.start.rate": 0.1, "metronomes.1.start.rate": 0.1}
    rig = rig_dict(EXPERIMENT)
    wild = metrosync.load_rig(rig, {"metronomes.*.start.rate": 0.1})
    assert wild.to_dict() == metrosync.load_rig(rig, each).to_dict()
    assert wild.to_dict() != metrosync.load_rig(rig).to_dict()
    a = metrosync.run(wild, duration=3)
    b = metrosync.run(metrosync.load_rig(rig, each), duration=3)
    np.testing.assert_array_equal(a.trajectory["theta_2"], b.trajectory["theta_2"])
    assert not np.array_equal(a.envelope["A_1"], metrosync.run(rig, duration=3).envelope["A_1"])
    # a wildcard axis of a sweep varies every metronome at once
    grid = metrosync.sweep(MAP_RIG, vary={"metronomes.*.nu": [0.5, 0.8]}, tau=30)
    one = metrosync.sweep(MAP_RIG, vary={"metronomes.0.nu": [0.5, 0.8]},
                          **{"tau": 30})
    assert grid["metronomes.*.nu"].tolist() == [0.5, 0.8]
    assert grid["A_2"].tolist() != one["A_2"].tolist()


def test_a_network_rig_runs_from_a_path_and_a_dict():
    # two boards joined by a spring (docs/networks.md): the network's own columns
    path = EXPERIMENT.replace("experiment.yaml", "two-boards-rollers.yaml")
    a = metrosync.run(path, duration=4)
    b = metrosync.run(rig_dict(path), duration=4)
    assert "x_left" in a.trajectory and "x_right" in a.trajectory
    np.testing.assert_array_equal(a.envelope["A_3"], b.envelope["A_3"])
    assert a.regime == b.regime == a.summary["network"]["regime"]
    bad = rig_dict(path)
    bad["platforms"][1]["mass"] = -1
    with pytest.raises(metrosync.RigError) as e:
        metrosync.load_rig(bad)
    assert str(e.value) == "rig['platforms'][1]['mass'] = -1: must be > 0"


def test_a_rig_round_trips_through_to_dict():
    rig = metrosync.load_rig(EXPERIMENT, {"platform.friction.mu": 0.002})
    again = metrosync.load_rig(rig.to_dict())
    assert again.scaled() == rig.scaled()
    assert rig.name == again.name == "experiment"


def test_a_failed_simulation_raises_with_the_partial_result():
    # an event storm (yaml/rigs/hard/storm.yaml): the CLI exits 3 with its rows kept
    storm = os.path.join(os.path.dirname(EXPERIMENT), "hard", "storm.yaml")
    with pytest.raises(metrosync.SimulationError) as e:
        metrosync.run(storm)
    assert "event storm" in str(e.value)
    assert e.value.result.complete is False
    assert len(e.value.result.trajectory["t"]) >= 1


# Issue 37, item 6: an argument a call does not take is said as such, with the way to do what
# was meant; a slip of a simulation key is still the loader's "did you mean".
def test_a_call_refuses_an_argument_it_does_not_take():
    with pytest.raises(TypeError) as e:
        metrosync.run(EXPERIMENT, overrides={"platform.friction.mu": 0.003})
    said = str(e.value)
    assert "run() got an unexpected keyword argument 'overrides'" in said
    assert "load_rig(rig, overrides={KEY: value})" in said
    for name in ("accuracy", "duration", "integrator", "sample", "tau"):
        assert name in said
    with pytest.raises(TypeError, match=r"^sweep\(\) got an unexpected keyword argument 'sets'"):
        metrosync.sweep(MAP_RIG, vary={"platform.friction.mu": (0, 1, 2)}, sets=["x=1"])
    with pytest.raises(metrosync.RigError, match="did you mean 'duration'"):
        metrosync.run(EXPERIMENT, durration=3)


def test_rig_error_says_what_it_is():
    doc = metrosync.RigError.__doc__ or ""
    assert "before anything runs" in doc and "SimulationError" in doc
    assert issubclass(metrosync.RigError, ValueError)


def test_every_option_is_the_same_on_a_network_or_refused_as_the_cli_refuses_it():
    # run(model="slow") on a network ran the full model and said model='full' (issue 38): it is
    # refused as `metrosync run --model slow` is, with the command line's reason
    path = EXPERIMENT.replace("experiment.yaml", "chimera-swings.yaml")
    calls = [
        ("run --model slow", lambda: metrosync.run(path, model="slow", duration=1)),
        ("run --engine slowflow", lambda: metrosync.run(path, engine="slowflow", duration=1)),
        ("sweep --model slow --vary couplings.0.k=1:5:2",
         lambda: metrosync.sweep(path, vary={"couplings.0.k": (1.0, 5.0, 2)}, model="slow",
                                 duration=1)),
        ("basin --model slow --random couplings.0.k=1:5 --samples 2",
         lambda: metrosync.basin(path, random={"couplings.0.k": (1.0, 5.0)}, samples=2,
                                 model="slow", duration=1)),
    ]
    for args, call in calls:
        words = args.split(" ")
        c = subprocess.run([os.environ["METROSYNC_BINARY"], words[0], path, *words[1:], "-q",
                            "--out", os.devnull + "/none"], capture_output=True, text=True)
        assert c.returncode == 2, (args, c.stderr)
        reason = "the full model only"  # in the CLI's words and in Python's
        assert reason in c.stderr, (args, c.stderr)
        with pytest.raises(metrosync.RigError) as e:
            call()
        assert reason in str(e.value), (args, str(e.value))
    # the full model asked for by name runs, and says so
    assert metrosync.run(path, model="full", duration=1).summary["model"] == "full"
