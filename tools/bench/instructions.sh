#!/usr/bin/env bash
# Instructions executed at equal final-state error: the direct engine against the careful peer
# (../shared/peer), counted by valgrind (callgrind's Ir), which a busy machine does not change.
# Both sides built for the same baseline x86-64 (the peer without -march=native, as
# build/metrosync). Per run: the count of 3 runs less that of 1, halved (start-up cancels).
# Error: max over xdot, theta_i, thetadot_i of the final state against the engine at 1e-13.
#   tools/bench/instructions.sh [BUILD_DIR] > docs/bench/speed/instructions.md
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
build=${1:-$root/build}
probe=$build/metrosync_engine_probe
peer_dir=${PEER_BUILD:-/tmp/metrosync-peer}
peer=$peer_dir/peer-base
peer_src=$root/../shared/peer/peer.cpp
[[ -x $probe ]] || { echo "build metrosync_engine_probe first" >&2; exit 2; }
command -v valgrind >/dev/null || { echo "valgrind missing (apt-get install valgrind)" >&2; exit 2; }
if [[ ! -x $peer || $peer_src -nt $peer ]]; then
  mkdir -p "$peer_dir"
  g++ -std=c++17 -O3 -DNDEBUG -o "$peer" "$peer_src"
fi

ir() { valgrind --tool=callgrind --callgrind-out-file=/dev/null "$@" 2>&1 >/dev/null |
  awk '/refs/ {gsub(",", "", $NF); print $NF}'; }

echo "# Instructions at equal final-state error: direct engine and careful peer"
echo
echo "Made by \`tools/bench/instructions.sh\` on $(date -u +%F), commit $(git -C "$root" rev-parse --short HEAD)."
echo "Ir: instructions per run (valgrind); err: max final-state difference against direct verner76 at 1e-13."
for scene in peer-n2 peer-n8; do
  rig=$root/yaml/rigs/bench/$scene.yaml
  mapfile -t args < <("$probe" "$rig" --peer-args)
  ref=$("$probe" "$rig" 1 simulation.accuracy=1e-13)
  echo
  echo "## $scene"
  echo
  echo "| side | setting | err | Ir | RHS evaluations |"
  echo "|---|---|---|---|---|"
  for acc in 1e-5 1e-6 1e-7 1e-8 1e-9; do
    out=$("$probe" "$rig" 1 simulation.accuracy=$acc)
    a=$(ir "$probe" "$rig" 3 simulation.accuracy=$acc)
    b=$(ir "$probe" "$rig" 1 simulation.accuracy=$acc)
    n=$(((a - b) / 2))
    err=$(python3 -c "
import sys
r=[float(v) for v in sys.argv[1].split('final')[1].split()]
o=[float(v) for v in sys.argv[2].split('final')[1].split()]
print('%.2g' % max(abs(a-b) for a,b in zip(r[2:-1],o[2:-1])))" "$ref" "$out")
    evals=$(echo "$out" | awk '{print $4}')
    echo "| metrosync verner76 | $acc | $err | $n | $evals |"
  done
  for m in "dopri5 1e-6 1e-7 1e-8 1e-9 1e-10" "rkf78 1e-7 1e-8 1e-9 1e-10 1e-11"; do
    set -- $m
    method=$1; shift
    for tol in "$@"; do
      a=$(ir "$peer" "${args[@]}" --method "$method" --rtol "$tol" --repeat 3)
      b=$(ir "$peer" "${args[@]}" --method "$method" --rtol "$tol" --repeat 1)
      json=$("$peer" "${args[@]}" --method "$method" --rtol "$tol" --repeat 1)
      row=$(python3 -c "
import json, sys
r=[float(v) for v in sys.argv[1].split('final')[1].split()]
d=json.loads(sys.argv[2]); s=d['state']; n=(len(s)-2)//2
# peer: th_1..N, th'_1..N, x, x'; ours (after t, x): xdot, theta_1, thetadot_1, ...
ours=r[2:-1]
peer=[s[-1]]+[v for i in range(n) for v in (s[i], s[n+i])]
print('%.2g %d' % (max(abs(a-b) for a,b in zip(ours,peer)), d['rhs_calls']))" "$ref" "$json")
      echo "| peer $method | $tol | ${row% *} | $(((a - b) / 2)) | ${row#* } |"
    done
  done
done
