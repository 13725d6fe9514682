#!/usr/bin/env python3
"""Time ratios at equal envelope error between two methods of a metrosync_bench precision CSV,
per integrator (metrosync_bench itself compares only the best integrator of each engine), for
both wall and CPU medians: on a loaded machine the wall median of a millisecond run carries the
other sessions' preemptions, the CPU median much less.

  python3 docs/bench/odeint/equal_error.py docs/bench/odeint/wp-experiment-short.csv

Each method's Pareto front (cheapest run for each error) is interpolated linearly in log-log, at
every decade of error both fronts cover (never extrapolated); ratio = time(a) / time(b), < 1: a
is faster.
"""
import csv
import math
import sys

PAIRS = [("direct:verner76", "odeint:dopri5"), ("direct:dopri5", "odeint:dopri5"),
         ("direct:verner76", "odeint:rkf78"), ("odeint:dopri5", "odeint:rkf78")]


def front(rows, label, time_key):
    pts = sorted((float(r["err_envelope"]), float(r[time_key])) for r in rows
                 if f'{r["engine"]}:{r["integrator"]}' == label and r["status"] == "ok"
                 and r["err_envelope"] and float(r["err_envelope"]) > 0)
    out = []  # increasing error, strictly decreasing time
    for e, t in pts:
        if not out or t < out[-1][1]:
            out.append((e, t))
    return out


def time_at(fr, err):
    for (e0, t0), (e1, t1) in zip(fr, fr[1:]):
        if e0 <= err <= e1:
            if e1 == e0:
                return t0
            a = (math.log(err) - math.log(e0)) / (math.log(e1) - math.log(e0))
            return math.exp(math.log(t0) + a * (math.log(t1) - math.log(t0)))
    return fr[0][1] if len(fr) == 1 and fr[0][0] == err else None


def main(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    print("| a / b | error | wall a (s) | wall b (s) | wall ratio | cpu a (s) | cpu b (s) "
          "| cpu ratio |\n|---|---|---|---|---|---|---|---|")
    for a, b in PAIRS:
        fw = {m: front(rows, m, "wall_median_s") for m in (a, b)}
        fc = {m: front(rows, m, "cpu_median_s") for m in (a, b)}
        for k in range(3, 14):
            err = 10.0 ** -k
            w = [time_at(fw[m], err) if fw[m] else None for m in (a, b)]
            c = [time_at(fc[m], err) if fc[m] else None for m in (a, b)]
            if None in w or None in c:
                continue
            print(f"| {a} / {b} | {err:.0e} | {w[0]:.3g} | {w[1]:.3g} | {w[0] / w[1]:.2f} "
                  f"| {c[0]:.3g} | {c[1]:.3g} | {c[0] / c[1]:.2f} |")


if __name__ == "__main__":
    main(sys.argv[1])
