#!/bin/sh
# Runs the shipped network rigs on both engines (and a network sweep and a single rig's sweep) into
# a folder, with the timings removed from summary.json, so that two builds' folders can be
# compared byte for byte: `network_files_check.sh METROSYNC OUT_DIR`, then `diff -r OLD NEW`.
set -eu
bin=$1
out=$2
src=$(cd "$(dirname "$0")/../.." && pwd)
mkdir -p "$out"
strip() {  # summary.json less what differs from run to run: timings, command line, build
  python3 -c 'import json,sys
j=json.load(open(sys.argv[1]))
for k in ("wall_seconds","engine_seconds","write_seconds","command_line","build","resolved_rig"):
    j.pop(k,None)
json.dump(j,open(sys.argv[1],"w"),indent=2,sort_keys=True)' "$1"
}
for rig in two-swings n3 two-boards-rollers chimera-swings; do
  for engine in direct simbody; do
    d=$out/$rig-$engine
    "$bin" run "$src/yaml/rigs/$rig.yaml" --engine $engine --set simulation.duration=3 \
      -q --no-plot --out "$d"
    strip "$d/summary.json"
  done
done
"$bin" sweep "$src/yaml/rigs/two-boards-rollers.yaml" --vary 'couplings.0.k=1,50' \
  --set simulation.duration=2 --jobs 1 -q --out "$out/sweep-network"
"$bin" sweep "$src/yaml/rigs/experiment.yaml" --vary 'platform.friction.mu=0.001,0.01' \
  --set simulation.duration=20 --jobs 1 -q --out "$out/sweep-single"
"$bin" sweep "$src/yaml/rigs/experiment.yaml" --model full --engine direct \
  --vary 'platform.friction.mu=0.001,0.01' --set simulation.duration=5 --jobs 1 -q \
  --out "$out/sweep-single-full"
for s in "$out"/sweep-*; do rm -f "$s"/*.png "$s"/timings.csv "$s"/progress* "$s"/sweep.json; done
