#!/usr/bin/env bash
# Regenerates docs/bench/peer (issue 11) in one run of metrosync_bench: the work-precision curves
# of metrosync's direct engine and the Boost.Odeint peer on the six bench scenes (wp-*.csv, .md,
# .png), the ratio tables at equal final-state and envelope error with the verdict (ratios.md,
# ratios.csv), the N-slope (nslope.csv) and the peer's validation. Takes many minutes of CPU.
#
#   tools/bench/peer.sh [OUT_DIR]        (default docs/bench/peer; needs ./build/metrosync_bench)
#
# For a quick look, fewer scenes and accuracies (the ratio table needs --repeat >= 5 to count):
#   SCENES="experiment-short n8" ACCURACIES=1e-4,1e-6,1e-8,1e-10 tools/bench/peer.sh /tmp/peer
# Other knobs: METHODS, REPEAT, BUDGET, MAX_LOAD, BENCH (the binary).
set -euo pipefail
cd "$(dirname "$0")/../.."

out=${1:-docs/bench/peer}
bench=${BENCH:-./build/metrosync_bench}
scenes=${SCENES:-experiment-short n8 n32 n128 suppression experiment}
methods=${METHODS:-odeint:dopri5,odeint:rkf78,direct:verner76,direct:dopri5,direct:verner65}
accuracies=${ACCURACIES:-1e-4,1e-5,1e-6,1e-7,1e-8,1e-9,1e-10,1e-11,1e-12}

if [ ! -x "$bench" ]; then
  echo "peer.sh: $bench not found: build it first (cmake --build build --target metrosync_bench)" >&2
  exit 2
fi
scene_args=()
for s in $scenes; do scene_args+=(--scene "yaml/rigs/bench/$s.yaml"); done

exec "$bench" precision "${scene_args[@]}" --methods "$methods" --accuracies "$accuracies" \
  --repeat "${REPEAT:-5}" --max-load "${MAX_LOAD:-0}" --budget "${BUDGET:-30}" \
  --reference direct:verner76:1e-13 --cross-check odeint:rkf78:1e-13 \
  --cross-check direct:dopri5:1e-12 --out "$out"
