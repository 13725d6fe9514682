#!/usr/bin/env python3
"""Work-precision of the full model on one rig: every (integrator, accuracy) pair against a
reference run at the tightest tolerance (cross-checked by a second integrator).

Error = max over envelope rows of |A_i - A_i,ref| and of |psi_j - psi_j,ref| (scaled units),
and the final-state error. Wall time = median of --repeat runs (metrosync's own wall_seconds).

  python3 tools/bench/work_precision.py [--rig RIG] [--set KEY=VALUE ...] \
      [--integrators rk-merson,rk-feldberg] [--accuracies 1e-6,1e-8,1e-10] [--repeat 3] \
      [--out runs/work-precision]
Writes work_precision.csv in --out and prints a Markdown table.
"""
import argparse
import csv
import json
import math
import os
import statistics
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def run(binary, rig, sets, integrator, accuracy, out):
    cmd = [binary, "run"] + ([rig] if rig else []) + ["--quiet", "--out", out]
    for s in sets + [f"simulation.integrator={integrator}", f"simulation.accuracy={accuracy}"]:
        cmd += ["--set", s]
    subprocess.run(cmd, check=True)
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    with open(os.path.join(out, "envelope.csv")) as f:
        rows = [list(map(float, r)) for r in list(csv.reader(f))[1:]]
    return summary, rows


def env_error(rows, ref):
    n = min(len(rows), len(ref))
    ncol = len(ref[0])
    namp = ncol // 2  # tau, A_1..A_N, psi_2..psi_N: 2N columns
    da = dpsi = 0.0
    for r, q in zip(rows[:n], ref[:n]):
        for k in range(1, 1 + namp):
            da = max(da, abs(r[k] - q[k]))
        for k in range(1 + namp, ncol):
            d = (r[k] - q[k] + math.pi) % (2 * math.pi) - math.pi
            dpsi = max(dpsi, abs(d))
    return da, dpsi


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--rig", default="")
    p.add_argument("--set", action="append", default=[])
    p.add_argument("--integrators", default="rk-merson,rk-feldberg,rk3")
    p.add_argument("--accuracies", default="1e-6,1e-8,1e-10")
    p.add_argument("--reference", default="rk-feldberg:1e-12,rk-merson:1e-12")
    p.add_argument("--repeat", type=int, default=3)
    p.add_argument("--binary", default=os.path.join(ROOT, "build", "metrosync"))
    p.add_argument("--out", default=os.path.join(ROOT, "runs", "work-precision"))
    a = p.parse_args()
    os.makedirs(a.out, exist_ok=True)

    refs = []
    for spec in a.reference.split(","):
        integ, acc = spec.split(":")
        refs.append((integ, acc) + run(a.binary, a.rig, a.set, integ, acc,
                                       os.path.join(a.out, f"ref-{integ}-{acc}")))
    ref_rows = refs[0][3]
    cross = env_error(refs[1][3], ref_rows) if len(refs) > 1 else (float("nan"),) * 2
    print(f"reference {refs[0][0]} @ {refs[0][1]}; cross-check {refs[1][0]} @ {refs[1][1]}: "
          f"max|dA| = {cross[0]:.2e}, max|dpsi| = {cross[1]:.2e}")

    results = []
    for integ in a.integrators.split(","):
        for acc in a.accuracies.split(","):
            walls = []
            for k in range(a.repeat):
                out = os.path.join(a.out, f"{integ}-{acc}")
                summary, rows = run(a.binary, a.rig, a.set, integ, acc, out)
                walls.append(summary["wall_seconds"])
            da, dpsi = env_error(rows, ref_rows)
            c = summary["counts"]
            results.append(dict(integrator=integ, accuracy=acc, wall_median_s=statistics.median(walls),
                                runs=a.repeat, max_abs_dA=da, max_abs_dpsi=dpsi, steps=c["steps"],
                                rhs_evals=c["rhs_evals"], events=c["events"],
                                escapements=sum(c["escapements"]), stick_slip=c["stick_slip"],
                                ledger_rel_residual=summary["energy"]["relative_residual"],
                                regime=summary["regime"]))
    with open(os.path.join(a.out, "work_precision.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(results[0].keys()))
        w.writeheader()
        w.writerows(results)
    print("| integrator | accuracy | wall (median s) | max abs dA | max abs dpsi | steps | events | ticks | stick-slip | ledger residual | regime |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for r in results:
        print(f"| {r['integrator']} | {r['accuracy']} | {r['wall_median_s']:.2f} | {r['max_abs_dA']:.1e} | "
              f"{r['max_abs_dpsi']:.1e} | {r['steps']} | {r['events']} | {r['escapements']} | "
              f"{r['stick_slip']} | {r['ledger_rel_residual']:.1e} | {r['regime']} |")


if __name__ == "__main__":
    sys.exit(main())
