#!/bin/bash
# The installed package (tools/install/package.cmake, docs/library.md) as a user meets it: the
# core installed into a fresh prefix (`cmake --install --component dev`), examples/ configured
# against it with find_package(metrosync) and built, and its run_rig on a shipped rig giving what
# `metrosync run` gives on the same rig: the regime, the steps, every metronome's ticks; and its
# sweep_mu giving every point the regime `metrosync sweep --engine direct` gives it.
#   check_package.sh BUILD_DIR
set -euo pipefail
src=$(cd "$(dirname "$(readlink -f "$0")")/../.." && pwd)
build=$(cd "${1:?the build tree}" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cmake --install "$build" --prefix "$work/prefix" --component dev >/dev/null
test -f "$work/prefix/lib/cmake/metrosync/metrosyncConfig.cmake" ||
  test -n "$(find "$work/prefix" -name metrosyncConfig.cmake)"
cmake -S "$src/examples" -B "$work/examples" -DCMAKE_PREFIX_PATH="$work/prefix" >/dev/null
cmake --build "$work/examples" -j2 >/dev/null
rig=$src/yaml/rigs/experiment.yaml
"$work/examples/run_rig" "$rig" simulation.duration=20 >"$work/example.txt"
"$build/metrosync" run "$rig" --set simulation.duration=20 --quiet --no-plot --out "$work/run" \
  >/dev/null
python3 - "$work/example.txt" "$work/run/summary.json" <<'PY'
import json, sys
lines = dict()
ticks = []
for line in open(sys.argv[1]):
    key, *rest = line.split()
    if key == "ticks":
        ticks.append(int(rest[1]))
    else:
        lines[key] = rest
summary = json.load(open(sys.argv[2]))
checks = [
    ("regime", lines["regime"][0], summary["regime"]),
    ("steps", int(lines["steps"][0]), summary["counts"]["steps"]),
    ("ticks", ticks, summary["counts"]["escapements"]),
]
bad = [f"{name}: example {a!r}, metrosync run {b!r}" for name, a, b in checks if a != b]
if len(lines["final"]) < 5:
    bad.append(f"final: {lines['final']}")
if bad:
    sys.exit("the installed package's run differs from metrosync run:\n  " + "\n  ".join(bad))
print("the example on the installed package:", lines["regime"][0], lines["steps"][0], "steps",
      ticks, "ticks: as metrosync run")
PY
# a range over which the regime changes (in-phase, suppression, death, ...)
rig=$src/yaml/rigs/experiment-low-friction-inphase.yaml
vary=platform.friction.mu=0.001:0.1:7:log
"$work/examples/sweep_mu" "$rig" "$vary" >"$work/sweep.txt"
"$build/metrosync" sweep "$rig" --vary "$vary" --engine direct --quiet --no-plot \
  --out "$work/sweep" >/dev/null
python3 - "$work/sweep.txt" "$work/sweep/regimes.csv" <<'PY'
import csv, sys
example = {int(i): (mu, regime) for i, mu, regime in (l.split() for l in open(sys.argv[1]))}
sweep = {int(r["index"]): (r["platform.friction.mu"], r["regime"])
         for r in csv.DictReader(open(sys.argv[2]))}
if example != sweep or len(example) != 7 or len({v[1] for v in example.values()}) < 3:
    sys.exit(f"the installed package's sweep differs from metrosync sweep:\n  {example}\n  {sweep}")
print("the sweep example on the installed package:", [v[1] for _, v in sorted(example.items())],
      ": as metrosync sweep")
PY
