#!/usr/bin/env bash
# The whole-process cost of `metrosync run` (docs/bench/process.md): the median wall-clock time of
# RUNS whole processes (start-up, rig parse, integration, files, exit) against the median of the
# same runs' own integration time (wall_seconds in summary.json), their ratio, and the budget of
# issue 11 (1.5 x wall_seconds + 3 ms); also the processes' CPU time (user + system, from
# getrusage), which other load on the machine does not inflate.
#   tools/bench/process_overhead.sh [METROSYNC] [RIG] [RUNS] [-- extra run options]
# defaults: build/metrosync, yaml/rigs/bench/experiment-short.yaml (the speed scene), 21 runs.
set -euo pipefail
bin=${1:-build/metrosync}
rig=${2:-yaml/rigs/bench/experiment-short.yaml}
runs=${3:-21}
shift $(( $# < 3 ? $# : 3 ))
[[ ${1:-} == -- ]] && shift
exec python3 - "$bin" "$rig" "$runs" "$@" <<'PY'
import json, os, resource, shutil, statistics, subprocess, sys, tempfile, time
bin, rig, runs, extra = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4:]
tmp = tempfile.mkdtemp(prefix="metrosync_process_")
proc, cpu, wall = [], [], []
try:
    for k in range(runs + 1):  # the first run warms the page cache and is not counted
        out = os.path.join(tmp, "r%d" % k)
        cmd = [bin, "run", rig, "--quiet", "--no-plot", "--out", out] + extra
        r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
        t0 = time.perf_counter()
        subprocess.run(cmd, check=True, stdin=subprocess.DEVNULL)
        t = time.perf_counter() - t0
        r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
        c = (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)
        with open(os.path.join(out, "summary.json")) as f:
            w = json.load(f)["wall_seconds"]
        shutil.rmtree(out)
        if k:
            proc.append(t)
            cpu.append(c)
            wall.append(w)
finally:
    shutil.rmtree(tmp, ignore_errors=True)
p, w = statistics.median(proc), statistics.median(wall)
budget = 1.5 * w + 3e-3
print("rig              %s %s" % (rig, " ".join(extra)))
print("load average     %.2f (1 min, at the end; the machine's other work inflates wall times)" %
      os.getloadavg()[0])
print("runs             %d (median; first run not counted)" % runs)
print("whole process    %.2f ms" % (p * 1e3))
print("process CPU      %.2f ms (user + system; what a loaded machine does not inflate)" %
      (statistics.median(cpu) * 1e3))
print("wall_seconds     %.2f ms (the run's own integration time)" % (w * 1e3))
print("ratio            %.2f" % (p / w))
print("overhead         %.2f ms (process - wall_seconds)" % ((p - w) * 1e3))
print("budget           %.2f ms (1.5 x wall_seconds + 3 ms): %s" %
      (budget * 1e3, "met" if p <= budget else "NOT met"))
PY
