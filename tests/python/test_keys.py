"""Overrides speak the key language of the command line (docs/keys.md): a wildcard sets every
element as one override per index would, a dict rig takes them too, a bad key raises RigError with
the words `--set` gets, the override named as Python's."""
import os
import subprocess

import numpy as np
import pytest

import metrosync

SRC = os.environ["METROSYNC_SOURCE_DIR"]
BIN = os.environ["METROSYNC_BINARY"]
SCALED = os.path.join(SRC, "yaml/rigs/experiment-scaled.yaml")


def test_a_wildcard_override_sets_every_metronome():
    every = metrosync.load_rig(SCALED, {"metronomes.*.nu": 0.55}).scaled()
    each = metrosync.load_rig(SCALED, {"metronomes.0.nu": 0.55, "metronomes.1.nu": 0.55}).scaled()
    assert every == each
    assert every["nu"] == [0.55, 0.55]
    assert metrosync.load_rig(SCALED).scaled()["nu"] != every["nu"]


def test_a_dict_rig_takes_wildcards_and_names():
    rig = {"units": "physical", "name": "net",
           "platforms": [{"name": name, "mass": 0.15, "friction": {"law": "coulomb", "mu": 0.01},
                          "metronomes": [{"box_mass": 0.06,
                                          "pendulum": {"mass": 0.0226, "length": 0.0225,
                                                       "decay_rate": 0.5},
                                          "escapement": {"angle": 0.244,
                                                         "steady_amplitude": 0.785},
                                          "start": {"angle": 0.5}}]}
                         for name in ("left", "right")],
           "couplings": [{"between": ["left", "right"], "k": 2.0}],
           "simulation": {"duration": 2}}
    named = metrosync.run(metrosync.load_rig(rig, {"platforms.right.friction.mu": 0.02,
                                                   "metronomes.*.start.rate": 0.1}))
    indexed = metrosync.run(metrosync.load_rig(rig, {"platforms.1.friction.mu": 0.02,
                                                     "platforms.0.metronomes.0.start.rate": 0.1,
                                                     "platforms.1.metronomes.0.start.rate": 0.1}))
    assert named.summary["resolved_rig"] == indexed.summary["resolved_rig"]
    assert set(named.envelope) == set(indexed.envelope)
    for k in named.envelope:
        np.testing.assert_array_equal(named.envelope[k], indexed.envelope[k])


def test_a_bad_key_raises_the_words_of_set():
    cli = subprocess.run([BIN, "scale", SCALED, "--set", "metronomes.*.nuu=1"],
                         capture_output=True, text=True)
    assert cli.returncode == 2
    with pytest.raises(metrosync.RigError) as e:
        metrosync.load_rig(SCALED, {"metronomes.*.nuu": 1})
    # the CLI's words after its "--set KEY=VALUE: KEY", the override as Python names it
    what = cli.stderr.split("metronomes.*.nuu: ")[-1].strip()
    assert what == "unknown key (did you mean 'nu'?)"
    assert str(e.value) == SCALED + ": overrides['metronomes.*.nuu'] = 1: " + what


def test_a_single_rig_answers_the_keys_of_its_one_platform():
    # a single rig is a network of one platform named "platform" (docs/keys.md, issue 38)
    experiment = os.path.join(SRC, "yaml/rigs/experiment.yaml")
    own = metrosync.load_rig(experiment, {"platform.friction.mu": 0.01})
    for key in ("platforms.0.friction.mu", "platforms.platform.friction.mu",
                "platforms.*.friction.mu"):
        rig = metrosync.load_rig(experiment, {key: 0.01})
        assert rig.to_dict() == own.to_dict()
        assert rig.scaled() == own.scaled()
    assert own.scaled() != metrosync.load_rig(experiment).scaled()
    # another platform's name: RigError (not IndexError) naming the one the rig has
    with pytest.raises(metrosync.RigError) as e:
        metrosync.load_rig(experiment, {"platforms.left.friction.mu": 0.01})
    assert ("overrides['platforms.left.friction.mu'] = 0.01: platforms.left: no entry of "
            "platforms is named 'left' (names: platform;") in str(e.value)
