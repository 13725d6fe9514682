"""The Python module against the command-line program: the same rig gives the same files' values
(the CLI's envelope.csv and trajectory.csv read back equal the module's arrays exactly), a bad rig
raises RigError with the CLI's located message, overrides act like --set."""
import json
import os
import subprocess

import numpy as np
import pytest

import metrosync

SRC = os.environ["METROSYNC_SOURCE_DIR"]
BIN = os.environ["METROSYNC_BINARY"]
RIG = os.path.join(SRC, "yaml/rigs/experiment.yaml")


def cli_run(tmp_path, *args):
    out = tmp_path / "cli"
    subprocess.run([BIN, "run", RIG, "--quiet", "--out", str(out), *args], check=True)
    return out


def read_csv(path):
    with open(path) as f:
        header = f.readline().strip().split(",")
    data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    return {h: data[:, k] for k, h in enumerate(header)}


@pytest.mark.parametrize("model", ["full", "slow"])
def test_run_equals_the_cli(tmp_path, model):
    out = cli_run(tmp_path, "--model", model, "--set", "simulation.duration=8")
    res = metrosync.run(metrosync.load_rig(RIG, {"simulation.duration": 8}), model=model)
    cli_env = read_csv(out / "envelope.csv")
    assert set(cli_env) == set(res.envelope)
    for k in cli_env:
        np.testing.assert_array_equal(res.envelope[k], cli_env[k])
    if model == "full":
        cli_traj = read_csv(out / "trajectory.csv")
        for k in cli_traj:
            np.testing.assert_array_equal(res.trajectory[k], cli_traj[k])
    else:
        assert res.trajectory is None
    summary = json.load(open(out / "summary.json"))
    assert res.regime == summary["regime"]
    assert res.summary["final"] == summary["final"]


def test_overrides_act_like_set():
    a = metrosync.load_rig(RIG, {"platform.friction.mu": 0.3}).scaled()
    b = metrosync.load_rig(RIG).scaled()
    assert a["mu"] != b["mu"]
    out = subprocess.run([BIN, "scale", "--json", RIG, "--set", "platform.friction.mu=0.3"],
                         check=True, capture_output=True, text=True).stdout
    assert json.loads(out) == a


def test_bad_rig_raises_rig_error_with_the_line(tmp_path):
    bad = tmp_path / "bad.yaml"
    text = open(RIG).read().replace("mass:", "mass: -", 1)
    bad.write_text(text)
    cli = subprocess.run([BIN, "scale", str(bad)], capture_output=True, text=True)
    assert cli.returncode == 2
    with pytest.raises(metrosync.RigError) as e:
        metrosync.load_rig(str(bad))
    assert str(e.value) in cli.stderr
    assert str(bad) + ":" in str(e.value)
