#!/usr/bin/env python3
"""Speed of the full model's engines (the issue "Speed against error").

  python3 tools/bench/direct_speed.py default [--repeat 7] [--binary build/metrosync]
      The default rig (`metrosync run`, yaml/rigs/experiment.yaml): for each engine and
      integrator, the median over --repeat runs of summary.json's wall_seconds (the engine's run,
      output files included) and of the whole process, and the envelope error: max over envelope
      rows of |A_i - A_i,ref| and |psi - psi_ref| against the direct engine at accuracy 1e-13
      (verner76), itself checked against 1e-14.

  python3 tools/bench/direct_speed.py scaling [--repeat 5] [--periods 20]
      N metronomes (N = 1 .. 100, detuned, scattered phases, epsilon = min(0.05, 0.4 / N), the
      platform's mu ~ 0.1 sqrt(N)), --periods fast periods each, default engine and integrator:
      wall time per fast period, per step and per step and metronome, steps and events per period.

The load on the machine matters (two cores shared): the script prints the load average next to
the numbers; compare runs made under the same load.
"""
import argparse
import csv
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def run(binary, args, out):
    t0 = time.perf_counter()
    subprocess.run([binary, "run"] + args + ["--quiet", "--out", out], check=True)
    wall = time.perf_counter() - t0
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    return summary, wall


def envelope(out):
    with open(os.path.join(out, "envelope.csv")) as f:
        return [list(map(float, r)) for r in list(csv.reader(f))[1:]]


def env_error(rows, ref):
    ncol = len(ref[0])
    n_amp = ncol // 2  # tau, A_1..A_N, psi_2..psi_N
    da = dp = 0.0
    for r, q in zip(rows, ref):
        for k in range(1, 1 + n_amp):
            da = max(da, abs(r[k] - q[k]))
        for k in range(1 + n_amp, ncol):
            dp = max(dp, abs((r[k] - q[k] + math.pi) % (2 * math.pi) - math.pi))
    return max(da, dp) if len(rows) == len(ref) else float("inf")


def load():
    return os.getloadavg()[0]


def default_rig(a, tmp):
    ref_dir = os.path.join(tmp, "ref")
    run(a.binary, ["--engine", "direct", "--set", "simulation.integrator=verner76",
                   "--set", "simulation.accuracy=1e-13"], ref_dir)
    ref = envelope(ref_dir)
    check_dir = os.path.join(tmp, "check")
    run(a.binary, ["--engine", "direct", "--set", "simulation.integrator=verner76",
                   "--set", "simulation.accuracy=1e-14"], check_dir)
    print(f"reference: direct verner76 @1e-13; against @1e-14: "
          f"{env_error(envelope(check_dir), ref):.1e}")
    cases = [("direct", None), ("direct", "verner76"), ("direct", "verner65"),
             ("direct", "dopri5"), ("simbody", None)]
    print(f"load average {load():.1f}")
    print("| engine | integrator | accuracy | wall_seconds (median) | process (median) | "
          "envelope error | steps | rhs evals | events |")
    print("|---|---|---|---|---|---|---|---|---|")
    for engine, integ in cases:
        args = ["--engine", engine]
        if integ:
            args += ["--set", f"simulation.integrator={integ}"]
        out = os.path.join(tmp, f"{engine}-{integ}")
        walls, procs = [], []
        repeat = a.repeat if engine == "direct" else max(1, min(a.repeat, 3))
        for _ in range(repeat):
            s, w = run(a.binary, args, out)
            walls.append(s["wall_seconds"])
            procs.append(w)
        c = s["counts"]
        print(f"| {engine} | {s['integrator']} | {s['accuracy']:g} | "
              f"{1e3 * statistics.median(walls):.1f} ms | {1e3 * statistics.median(procs):.1f} ms | "
              f"{env_error(envelope(out), ref):.1e} | {c['steps']} | {c['rhs_evals']} | "
              f"{c['events']} |")
    print(f"load average {load():.1f}")


def scaling_rig(n, periods):
    eps = min(0.05, 0.4 / n)
    lines = ["units: scaled", f"name: n{n}", f"epsilon: {eps}", "platform:",
             f"  friction: {{law: coulomb, mu: {0.1 * math.sqrt(n):.4f}}}", "metronomes:"]
    for i in range(n):
        alpha = 0.0 if i == 0 else -1 + 2 * i / max(n - 1, 1)
        x = 43758.5453 * math.sin(i + 1)
        phi = 2 * math.pi * (x - math.floor(x))
        lines.append(f"  - {{nu: 0.7, J: 2.8, theta_c: 0.9, alpha: {alpha:.6f}, "
                     f"start: {{A: 1.9, phi: {phi:.6f}}}}}")
    lines += ["simulation:", f"  tau: {periods * 2 * math.pi * eps:.9f}", ""]
    return "\n".join(lines)


def scaling(a, tmp):
    print(f"load average {load():.1f}")
    print("| N | integrator | ms per period | us per step | us per step and metronome | "
          "steps per period | events per period |")
    print("|---|---|---|---|---|---|---|")
    for n in (1, 2, 5, 10, 20, 50, 100):
        rig = os.path.join(tmp, f"n{n}.yaml")
        with open(rig, "w") as f:
            f.write(scaling_rig(n, a.periods))
        walls = []
        for _ in range(a.repeat):
            s, _ = run(a.binary, [rig, "--engine", "direct"], os.path.join(tmp, f"out{n}"))
            walls.append(s["wall_seconds"])
        w = statistics.median(walls)
        c = s["counts"]
        print(f"| {n} | {s['integrator']} | {1e3 * w / a.periods:.3f} | "
              f"{1e6 * w / c['steps']:.2f} | {1e6 * w / c['steps'] / n:.2f} | "
              f"{c['steps'] / a.periods:.0f} | {c['events'] / a.periods:.0f} |")
    print(f"load average {load():.1f}")


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("what", choices=["default", "scaling"])
    p.add_argument("--repeat", type=int, default=7)
    p.add_argument("--periods", type=int, default=20)
    p.add_argument("--binary", default=os.path.join(ROOT, "build", "metrosync"))
    a = p.parse_args()
    with tempfile.TemporaryDirectory(prefix="metrosync-speed-") as tmp:
        (default_rig if a.what == "default" else scaling)(a, tmp)


if __name__ == "__main__":
    sys.exit(main())
