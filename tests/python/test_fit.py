"""metrosync.fit against `metrosync fit` (issue 27): the same data and starts give fit.json's
values to the last bit, from a file or from a dict of columns; the answer is the truth the data
were made with; bad keys raise RigError with the CLI's message."""
import json
import os
import subprocess

import numpy as np
import pytest

import metrosync

SRC = os.environ["METROSYNC_SOURCE_DIR"]
BIN = os.environ["METROSYNC_BINARY"]
RIG = os.path.join(SRC, "yaml/rigs/experiment.yaml")
NOISE = 1e-3  # rad, a good camera's
STARTS = {"platform.friction.mu": 3.9e-4, "metronomes.*.pendulum.decay_rate": 0.3}  # 40% low
TRUTH = {"platform.friction.mu": 6.5e-4, "metronomes.*.pendulum.decay_rate": 0.5}


def record():
    """8 s of the experiment's pair at 100 Hz from the model, with the camera's noise."""
    res = metrosync.run(metrosync.load_rig(RIG), duration=8, sample=0.01)
    rng = np.random.default_rng(5)
    return {"t": res.trajectory["t"],
            "theta_1": res.trajectory["theta_1"] + rng.normal(0, NOISE, len(res.trajectory["t"])),
            "theta_2": res.trajectory["theta_2"] + rng.normal(0, NOISE, len(res.trajectory["t"]))}


def test_fit_equals_the_cli_and_finds_the_truth(tmp_path):
    data = record()
    csv = tmp_path / "data.csv"
    with open(csv, "w") as f:
        f.write("t,theta_1,theta_2\n")
        for row in zip(data["t"], data["theta_1"], data["theta_2"]):
            f.write(",".join(repr(float(v)) for v in row) + "\n")
    args = [BIN, "fit", RIG, str(csv), "--quiet", "--no-plot", "--out", str(tmp_path / "cli")]
    for key, start in STARTS.items():
        args += ["--free", key, "--set", "%s=%r" % (key, start)]
    subprocess.run(args, check=True)
    cli = json.load(open(tmp_path / "cli" / "fit.json"))
    py = metrosync.fit(metrosync.load_rig(RIG, STARTS), data, list(STARTS)).summary
    for field in ("values", "std_errors", "identifiable", "rms", "noise", "converged", "note",
                  "optima", "start_from", "keys"):
        assert py[field] == cli[field], field
    assert py["converged"]
    for key, truth in TRUTH.items():
        assert abs(py["values"][key] - truth) < 3 * py["std_errors"][key], key
    # the shared key sets both metronomes' decay rates
    assert py["keys"]["metronomes.*.pendulum.decay_rate"] == [
        "metronomes.0.pendulum.decay_rate", "metronomes.1.pendulum.decay_rate"]


def write_csv(path, data):
    with open(path, "w") as f:
        f.write("t,theta_1,theta_2\n")
        for row in zip(data["t"], data["theta_1"], data["theta_2"]):
            f.write(",".join(repr(float(v)) for v in row) + "\n")


def test_fit_options_are_the_clis(tmp_path):
    """noise, starts, local and profile do in Python what --noise, --starts, --local and
    --profile do in the CLI: the same fit.json, field for field."""
    data = record()
    csv = tmp_path / "data.csv"
    write_csv(csv, data)
    args = [BIN, "fit", RIG, str(csv), "--quiet", "--no-plot", "--out", str(tmp_path / "cli"),
            "--noise", "0.002", "--starts", "2", "--local", "--profile"]
    for key, start in STARTS.items():
        args += ["--free", key, "--set", "%s=%r" % (key, start)]
    subprocess.run(args, check=True)
    cli = json.load(open(tmp_path / "cli" / "fit.json"))
    py = metrosync.fit(metrosync.load_rig(RIG, STARTS), data, list(STARTS), noise=0.002,
                       starts=2, local=True, profile=True).summary
    for field in ("values", "std_errors", "rms", "noise", "noise_from", "converged", "note",
                  "optima", "strategy", "profile", "evaluations"):
        assert py[field] == cli[field], field
    # the options took effect: the noise given (not estimated), no windows, every key profiled
    assert py["noise_from"] == "--noise" and py["noise"]["theta_1"] == 0.002
    assert py["strategy"] == "the whole record"
    assert all(py["profile"][key] is not None for key in STARTS)


def test_bad_options_raise_value_error():
    data = {"t": [0.0, 0.01, 0.02, 0.03], "theta_1": [0.78, 0.77, 0.76, 0.75]}
    with pytest.raises(ValueError, match="noise must be > 0"):
        metrosync.fit(RIG, data, "platform.friction.mu", noise=0)
    with pytest.raises(ValueError, match="starts must be at least 1"):
        metrosync.fit(RIG, data, "platform.friction.mu", starts=0)


def test_bad_key_raises_rig_error():
    with pytest.raises(metrosync.RigError, match="platform.friction.law"):
        metrosync.fit(RIG, {"t": [0.0, 0.01, 0.02, 0.03], "theta_1": [0.78, 0.77, 0.76, 0.75]},
                      "platform.friction.law")
