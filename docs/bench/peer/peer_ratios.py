#!/usr/bin/env python3
"""Issue 11's table: for each scene (and its N), metrosync's direct engine against the faster
Boost.Odeint peer variant at equal envelope error, on CPU medians, from metrosync_bench precision
CSVs; and the cost per fast period against N (the N-slope).

  /usr/bin/python3 docs/bench/peer/peer_ratios.py docs/bench/peer/wp-*.csv

Each side's front is the cheapest run (any of its integrators) reaching each error: the Pareto
front of all its points, interpolated linearly in log-log at every decade from 1e-4 to 1e-10 that
both fronts cover (never extrapolated). ratio = peer time / metrosync time: > 1 means metrosync is
faster, the issue's goal is >= 2. The N-slope is the least-squares slope of log(CPU time per fast
period) against log N at a fixed error, over the scenes that reach it.
"""
import csv
import math
import sys

DECADES = range(4, 11)  # errors 1e-4 .. 1e-10
SLOPE_ERRORS = (1e-5, 1e-6, 1e-8)


def front(rows, engine, key="cpu_median_s"):
    pts = sorted((float(r["err_envelope"]), float(r[key]), r["integrator"], r["setting"])
                 for r in rows if r["engine"] == engine and r["status"] == "ok"
                 and r["err_envelope"] and float(r["err_envelope"]) > 0 and r[key])
    out = []  # increasing error, strictly decreasing time
    for p in pts:
        if not out or p[1] < out[-1][1]:
            out.append(p)
    return out


def time_at(fr, err):
    for (e0, t0, *_), (e1, t1, *_) in zip(fr, fr[1:]):
        if e0 <= err <= e1:
            if e1 == e0:
                return t0
            a = (math.log(err) - math.log(e0)) / (math.log(e1) - math.log(e0))
            return math.exp(math.log(t0) + a * (math.log(t1) - math.log(t0)))
    return None


def main(paths):
    scenes = []
    for path in (p for p in paths if not p.endswith("-equal-error.csv")):
        with open(path) as f:
            rows = list(csv.DictReader(f))
        if rows:
            scenes.append((rows[0]["scene"], int(rows[0]["n"]), float(rows[0]["periods"]), rows))
    scenes.sort(key=lambda s: (s[1], s[0]))
    print("| scene | N | " + " | ".join(f"1e-{k}" for k in DECADES) + " |")
    print("|---|---|" + "---|" * len(DECADES))
    for name, n, _, rows in scenes:
        fm, fp = front(rows, "direct"), front(rows, "odeint")
        cells = []
        for k in DECADES:
            tm, tp = time_at(fm, 10.0 ** -k), time_at(fp, 10.0 ** -k)
            cells.append(f"{tp / tm:.2f}" if tm and tp else "")
        print(f"| {name} | {n} | " + " | ".join(cells) + " |")
    print()
    for err in SLOPE_ERRORS:
        pts = []
        for name, n, periods, rows in scenes:
            if name in ("experiment", "suppression"):
                continue  # one scene per N: the N-scaling set (experiment-short, n8, n32, n128)
            t = time_at(front(rows, "direct"), err)
            tp = time_at(front(rows, "odeint"), err)
            if t:
                pts.append((n, t / periods, tp / periods if tp else None))
        if len(pts) < 2:
            continue
        xs = [math.log(p[0]) for p in pts]
        ys = [math.log(p[1]) for p in pts]
        mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
        slope = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)
        per = ", ".join(f"N={p[0]}: {p[1] * 1e6:.1f} us" + (f" (peer {p[2] * 1e6:.1f})" if p[2] else "")
                        for p in pts)
        print(f"error {err:.0e}: metrosync CPU per fast period {per}; log-log slope {slope:.2f}")


if __name__ == "__main__":
    main(sys.argv[1:])
