#!/usr/bin/env bash
# The speed of `metrosync continue --model full` (docs/bench/full-continuation.md): for each case,
# the median over RUNS whole processes of the wall-clock time and of the CPU time (user + system,
# from getrusage: other load on the machine does not inflate it), the periodic orbits computed
# (rows of branches.csv) and the time per orbit; issue 26's target is a 100-orbit family at N = 2
# in under a minute on 2 cores.
#   tools/bench/full_continuation.sh [METROSYNC] [RUNS]
# defaults: build/metrosync, 3 runs.
set -euo pipefail
bin=${1:-build/metrosync}
runs=${2:-3}
exec python3 - "$bin" "$runs" <<'PY'
import csv, os, resource, shutil, statistics, subprocess, sys, tempfile, time
bin, runs = sys.argv[1], int(sys.argv[2])
cases = [
    ("f4.3 in mu, in phase (eps 0.073)",
     ["yaml/rigs/paper/f4.3-mu0.2.yaml", "--param", "platform.friction.mu", "--to", "0.35"]),
    ("f4.4 in alpha, near antiphase (eps 0.073)",
     ["yaml/rigs/paper/f4.4-alpha0.2.yaml", "--param", "metronomes.1.alpha", "--to", "2.5"]),
    ("experiment in eps, exact antiphase + its asymmetric branch",
     ["yaml/rigs/experiment-scaled.yaml", "--param", "epsilon", "--to", "0.004",
      "--set", "metronomes.0.start={A: 2.9, phi: 0.0}",
      "--set", "metronomes.1.start={A: 2.9, phi: 3.141592653589793}"]),
]
tmp = tempfile.mkdtemp(prefix="metrosync_fullcont_")
print("| case | orbits | wall (median of %d) | CPU | CPU per orbit |" % runs)
print("| --- | --- | --- | --- | --- |")
try:
    for name, args in cases:
        wall, cpu, points = [], [], 0
        for k in range(runs):
            out = os.path.join(tmp, "r%d" % k)
            cmd = [bin, "continue"] + args + ["--model", "full", "-q", "--out", out]
            r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
            t0 = time.perf_counter()
            subprocess.run(cmd, check=True, stdin=subprocess.DEVNULL)
            wall.append(time.perf_counter() - t0)
            r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
            cpu.append((r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime))
            with open(os.path.join(out, "branches.csv")) as f:
                points = sum(1 for _ in csv.DictReader(f))
        w, c = statistics.median(wall), statistics.median(cpu)
        print("| %s | %d | %.2f s | %.2f s | %.1f ms |" % (name, points, w, c, 1000 * c / points))
finally:
    shutil.rmtree(tmp)
PY
