#!/usr/bin/env python3
"""The measured examples of docs/fit.md, made again: each record (the direct or the Simbody engine,
Python's random.gauss noise with the seed the page names) and each fit, with what the page quotes
from it -- the fit's summary, its model runs and runs of the derivatives, its CPU seconds, and for
the tables each key's error in standard errors. CPU is the fit process's own (getrusage of the
child), not wall time: the page quotes no wall time.

    python3 tools/bench/fit_examples.py [BUILD_DIR] [--only NAME]

Scratch files go to a temporary directory; nothing in the tree is written.
"""
import csv
import json
import os
import random
import resource
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
args = [a for a in sys.argv[1:] if not a.startswith("--")]
BIN = os.path.join(args[0] if args else os.path.join(ROOT, "build"), "metrosync")
ONLY = sys.argv[sys.argv.index("--only") + 1] if "--only" in sys.argv else None
WORK = tempfile.mkdtemp(prefix="metrosync-fit-examples-")


def rig(name):
    return os.path.join(ROOT, "yaml", "rigs", name)


def run(rig_path, sets, out, engine=None):
    cmd = [BIN, "run", rig_path, "--out", out, "--no-plot", "-q"] + sum((["--set", s] for s in sets), [])
    if engine:
        cmd += ["--engine", engine]
    subprocess.run(cmd, check=True)


def noisy(src, dst, cols, sigma, seed):
    random.seed(seed)
    with open(dst, "w") as f:
        f.write("t,%s\n" % ",".join(cols))
        for r in csv.DictReader(open(src)):
            f.write("%s,%s\n" % (r["t"], ",".join("%.6f" % (float(r[c]) + random.gauss(0, sigma))
                                                 for c in cols)))


def fit(rig_path, data, free, starts, extra=()):
    """metrosync fit; its stdout, fit.json and CPU seconds."""
    out = os.path.join(WORK, "fit")
    cmd = [BIN, "fit", rig_path, data, "--out", out, "--no-plot"] + list(extra)
    for k in free:
        cmd += ["--free", k]
    for k, v in starts.items():
        cmd += ["--set", "%s=%r" % (k, v)]
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    p = subprocess.run(cmd, check=True, capture_output=True, text=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime + after.ru_stime) - (before.ru_utime + before.ru_stime)
    return p.stdout, json.load(open(os.path.join(out, "fit.json"))), cpu


def report(name, stdout, j, cpu, truth=None):
    print("== %s" % name)
    print(stdout.rstrip())
    line = "CPU %.2f s, %d model runs, %d with derivatives, %d optima" % (
        cpu, j["evaluations"], j.get("jacobians", 0), len(j["optima"]))
    if truth:
        errs = []
        for k, t in truth.items():
            v, se = j["values"].get(k), j["std_errors"].get(k)
            errs.append("n/i" if v is None else "%+.2f" % ((v - t) / se))
        line += "; errors in standard errors " + " ".join(errs)
    print(line + "; strategy: " + j["strategy"])
    print(flush=True)


def wanted(name):
    return ONLY is None or ONLY == name


MU, BETA, ASTAR = 6.5e-4, 0.5, 0.785
FIVE = ["platform.friction.mu", "metronomes.0.pendulum.decay_rate",
        "metronomes.1.pendulum.decay_rate", "metronomes.0.escapement.steady_amplitude",
        "metronomes.1.escapement.steady_amplitude"]


def two_keys():
    d = os.path.join(WORK, "two")
    run(rig("experiment.yaml"), ["simulation.duration=20", "simulation.sample=0.01"], d)
    noisy(d + "/trajectory.csv", d + "/data.csv", ["theta_1", "theta_2"], 1e-3, 2)
    keys = ["platform.friction.mu", "metronomes.0.pendulum.decay_rate"]
    report("two keys, 20 s", *fit(rig("experiment.yaml"), d + "/data.csv", keys,
                                   dict(zip(keys, (1e-3, 0.4)))), dict(zip(keys, (MU, BETA))))


PAPER_KEYS = ["platform.friction.mu", "metronomes.0.pendulum.damping",
              "metronomes.1.pendulum.damping", "metronomes.0.escapement.impulse",
              "metronomes.1.escapement.impulse"]
PAPER_SETS = ["metronomes.*.pendulum={mass: 0.0226, length: 0.0225, damping: 0.0226}",
              "metronomes.*.escapement={angle: 0.244, impulse: 1.4844e-5}"]
PAPER_TRUTH = dict(zip(PAPER_KEYS, [MU, 0.0226, 0.0226, 1.4844e-5, 1.4844e-5]))


def paper_rig(duration, d):
    """yaml/rigs/experiment.yaml with the paper's keys (damping, impulse), as a file."""
    os.makedirs(d, exist_ok=True)
    text = open(rig("experiment.yaml")).read()
    text = text.replace("decay_rate: 0.5", "damping: 0.0226").replace(
        "steady_amplitude: 0.785", "impulse: 1.4844e-5").replace("duration: 200",
                                                                 "duration: %g" % duration)
    path = os.path.join(d, "rig.yaml")
    open(path, "w").write(text)
    return path


def five_keys():
    d = os.path.join(WORK, "five")
    r = paper_rig(60, d)
    run(r, ["simulation.sample=0.01"], d + "/truth", engine="simbody")
    noisy(d + "/truth/trajectory.csv", d + "/data.csv", ["theta_1", "theta_2"], 1e-3, 2)
    starts = dict(zip(PAPER_KEYS, [3.9e-4, 0.0149, 0.0149, 1.2e-5, 1.2e-5]))
    report("five keys from rough guesses, 60 s", *fit(r, d + "/data.csv", PAPER_KEYS, starts),
           PAPER_TRUTH)
    r15 = paper_rig(15, d + "/15")
    run(r15, ["simulation.sample=0.01"], d + "/15/truth", engine="simbody")
    noisy(d + "/15/truth/trajectory.csv", d + "/15/data.csv", ["theta_1", "theta_2"], 1e-3, 7)
    starts = dict(zip(PAPER_KEYS, [1.95e-4, 0.00678, 0.00678, 4.45e-6, 4.45e-6]))
    report("the 15 s pair from 0.3 of the truth", *fit(r15, d + "/15/data.csv", PAPER_KEYS, starts),
           PAPER_TRUTH)


def record(name, d, sets=()):
    """30 s of the shipped rig `name` by the Simbody engine, 1e-3 rad of noise, seed 7."""
    run(rig(name), ["simulation.duration=30", "simulation.sample=0.01"] + list(sets), d,
        engine="simbody")
    noisy(d + "/trajectory.csv", d + "/data.csv", ["theta_1", "theta_2"], 1e-3, 7)
    return d + "/data.csv"


def table():
    exp = record("experiment.yaml", os.path.join(WORK, "exp30"))
    truth = dict(zip(FIVE, [MU, BETA, BETA, ASTAR, ASTAR]))

    def off(pcts, base=(MU, BETA, BETA, ASTAR, ASTAR)):
        return {k: b * (1 + p / 100) for k, b, p in zip(FIVE, base, pcts)}

    for pcts in ([50, -50, 50, -50, 50], [208, -70, 200, -54, 104], [-69, -70, -70, -54, -54]):
        report("experiment %s" % pcts, *fit(rig("experiment.yaml"), exp, FIVE, off(pcts)), truth)
    report("experiment, its own keys 70% and 50% low",
           *fit(rig("experiment.yaml"), exp, FIVE, off([-70, -70, -70, -50, -50])), truth)
    report("experiment --model slow, 70% and 50% low",
           *fit(rig("experiment.yaml"), exp, FIVE, off([-70, -70, -70, -50, -50]),
                ["--model", "slow"]), truth)
    for name, mu, pcts in (("experiment-high-friction-inphase.yaml", 4.6e-3, [-50, 50, -50, 50, -50]),
                           ("experiment-low-friction-antiphase.yaml", MU, [-50, 50, 50, -50, -50])):
        data = record(name, os.path.join(WORK, name))
        base = (mu, BETA, BETA, ASTAR, ASTAR)
        report(name + " %s" % pcts, *fit(rig(name), data, FIVE, off(pcts, base)),
               dict(zip(FIVE, base)))
    data = record("experiment.yaml", os.path.join(WORK, "mu0"), ["platform.friction.mu=0"])
    starts = {FIVE[0]: 1e-3}
    starts.update({k: b * (1 + p / 100) for k, b, p in
                   zip(FIVE[1:], (BETA, BETA, ASTAR, ASTAR), (-50, 50, 50, -36))})
    report("experiment with mu = 0", *fit(rig("experiment.yaml"), data, FIVE, starts),
           dict(zip(FIVE[1:], (BETA, BETA, ASTAR, ASTAR))))
    shared = ["platform.friction.mu", "metronomes.*.pendulum.decay_rate",
              "metronomes.*.escapement.steady_amplitude"]
    report("experiment, shared keys -50 +50 -50",
           *fit(rig("experiment.yaml"), exp, shared,
                dict(zip(shared, (MU * 0.5, BETA * 1.5, ASTAR * 0.5)))),
           dict(zip(shared, (MU, BETA, ASTAR))))
    n3 = record("n3.yaml", os.path.join(WORK, "n3"))
    report("n3, shared keys +50 -50 +50",
           *fit(rig("n3.yaml"), n3, shared, dict(zip(shared, (MU * 1.5, BETA * 0.5, ASTAR * 1.5)))),
           dict(zip(shared, (MU, BETA, ASTAR))))


def measure_data():
    d = os.path.join(WORK, "measure")
    run(rig("experiment.yaml"), ["platform.friction={law: fixed}", "metronomes.0.start.angle=0.2",
                                  "metronomes.1.start.angle=0.1", "simulation.duration=10",
                                  "simulation.sample=0.01"], d + "/still")
    run(rig("board-on-springs.yaml"), ["simulation.sample=0.01"], d + "/springs")
    noisy(d + "/still/trajectory.csv", d + "/decay.csv", ["theta_1"], 1e-3, 3)
    noisy(d + "/springs/trajectory.csv", d + "/springs.csv", ["x"], 0.75e-3, 3)
    report("board on springs, x alone",
           *fit(rig("board-on-springs.yaml"), d + "/springs.csv", ["platforms.0.friction.mu"],
                {"platforms.0.friction.mu": 1e-3}), {"platforms.0.friction.mu": MU})
    report("free decay, --model slow",
           *fit(rig("experiment.yaml"), d + "/decay.csv", ["metronomes.0.pendulum.decay_rate"], {},
                ["--model", "slow", "--set", "platform.friction={law: fixed}", "--set",
                 "metronomes.0.start.angle=0.2", "--set", "metronomes.1.start.angle=0.1"]),
           {"metronomes.0.pendulum.decay_rate": BETA})


for name, f in (("two", two_keys), ("five", five_keys), ("table", table), ("measure", measure_data)):
    if wanted(name):
        f()
