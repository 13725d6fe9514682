#!/usr/bin/env bash
# The time of `metrosync continue` (the slow flow, docs/bench/slow-continuation.md): every default
# call on the shipped rigs and the paper's rigs (no --all, cycles followed), and the --all calls
# of issue 25 and of issue 36 (n32). For each case, the median over RUNS whole processes of the
# wall-clock time and of the CPU time (user + system, from getrusage: other load on the machine
# does not inflate it), the points of the branches and of the cycles. Issue 25's targets: a
# default call <= 10 s, --all <= 20 s (issue 36: n32's too, on 2 cores). --all runs on every core
# (continue --jobs), so its CPU time is the sum over the threads.
#   tools/bench/slow_continuation.sh [METROSYNC] [RUNS]
# defaults: build/metrosync, 1 run.
set -euo pipefail
bin=${1:-build/metrosync}
runs=${2:-1}
exec python3 - "$bin" "$runs" <<'PY'
import csv, os, resource, shutil, statistics, subprocess, sys, tempfile, time
bin, runs = sys.argv[1], int(sys.argv[2])
R = "yaml/rigs/"
MU = ["--param", "platform.friction.mu"]
ALPHA = ["--param", "metronomes.1.alpha"]
cases = [
    ("experiment", R + "experiment.yaml", MU + ["--to", "0.01"]),
    ("experiment-high-friction-antiphase", R + "experiment-high-friction-antiphase.yaml",
     MU + ["--to", "0.01"]),
    ("experiment-high-friction-inphase", R + "experiment-high-friction-inphase.yaml",
     MU + ["--to", "0.01"]),
    ("experiment-low-friction-antiphase", R + "experiment-low-friction-antiphase.yaml",
     MU + ["--to", "0.01"]),
    ("experiment-low-friction-inphase", R + "experiment-low-friction-inphase.yaml",
     MU + ["--to", "0.01"]),
    ("experiment-map in mu", R + "experiment-map.yaml", MU + ["--to", "1.5"]),
    ("experiment-map in alpha", R + "experiment-map.yaml", ALPHA + ["--to", "3"]),
    ("experiment-scaled", R + "experiment-scaled.yaml", MU + ["--to", "1"]),
    ("detuned-population", R + "detuned-population.yaml", MU + ["--to", "0.5"]),
    ("n3", R + "n3.yaml", MU + ["--to", "0.01"]),
    ("n5", R + "n5.yaml", MU + ["--to", "0.01"]),
    ("n32", R + "n32.yaml", MU + ["--to", "0.01"]),
    ("f4.1 (mu = 0)", R + "paper/f4.1.yaml", MU + ["--to", "0.8"]),
    ("f4.2 (a neutral family)", R + "paper/f4.2.yaml", MU + ["--to", "0.8"]),
    ("f4.3-mu0.2", R + "paper/f4.3-mu0.2.yaml", MU + ["--to", "0.6"]),
    ("f4.3-mu0.3", R + "paper/f4.3-mu0.3.yaml", MU + ["--to", "0.6"]),
    ("f4.3-mu0.4", R + "paper/f4.3-mu0.4.yaml", MU + ["--to", "0.1"]),
    ("f4.4-alpha0.2", R + "paper/f4.4-alpha0.2.yaml", ALPHA + ["--to", "3"]),
    ("f4.4-alpha2", R + "paper/f4.4-alpha2.yaml", ALPHA + ["--to", "4"]),
    ("f4.4-alpha4", R + "paper/f4.4-alpha4.yaml", ALPHA + ["--from", "3", "--to", "4"]),
    ("f4.4 locked state, alpha 0.2 .. 3", R + "paper/f4.4-alpha4.yaml",
     ALPHA + ["--from", "0.2", "--to", "3"]),
    ("--all: f4.3-mu0.2", R + "paper/f4.3-mu0.2.yaml", MU + ["--to", "0.6", "--all"]),
    ("--all: f4.1", R + "paper/f4.1.yaml", MU + ["--to", "1", "--all"]),
    ("--all: experiment-map in alpha", R + "experiment-map.yaml", ALPHA + ["--to", "3", "--all"]),
    # issue 36: <= 20 s wall on 2 cores (--all follows its states on every core: CPU > wall)
    ("--all: n32 (bench scene)", R + "bench/n32.yaml", MU + ["--to", "0.01", "--all"]),
    ("--all: n32", R + "n32.yaml", MU + ["--to", "0.01", "--all"]),
]


def rows(path):
    if not os.path.exists(path):
        return 0
    with open(path) as f:
        return sum(1 for _ in csv.DictReader(f))


tmp = tempfile.mkdtemp(prefix="metrosync_slowcont_")
print("| case | arguments | exit | points | cycle points | wall (median of %d) | CPU |" % runs)
print("| --- | --- | --- | --- | --- | --- | --- |")
try:
    for name, rig, args in cases:
        wall, cpu = [], []
        for k in range(runs):
            out = os.path.join(tmp, "r%d" % k)
            shutil.rmtree(out, ignore_errors=True)
            cmd = [bin, "continue", rig] + args + ["-q", "--out", out]
            r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
            t0 = time.perf_counter()
            code = subprocess.run(cmd, stdin=subprocess.DEVNULL).returncode
            wall.append(time.perf_counter() - t0)
            r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
            cpu.append((r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime))
        print("| %s | `%s` | %d | %d | %d | %.2f s | %.2f s |" % (
            name, " ".join(args), code, rows(os.path.join(out, "branches.csv")),
            rows(os.path.join(out, "cycles.csv")), statistics.median(wall),
            statistics.median(cpu)), flush=True)
finally:
    shutil.rmtree(tmp)
PY
