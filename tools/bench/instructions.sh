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

rows=$(mktemp)
trap 'rm -f "$rows"' EXIT
keep() { echo "$1" | tee -a "$rows"; }  # a line of the table, kept for the ratios below

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
  keep "## $scene"
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
    keep "| metrosync verner76 | $acc | $err | $n | $evals |"
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
      keep "| peer $method | $tol | ${row% *} | $(((a - b) / 2)) | ${row#* } |"
    done
  done
done

# The ratios at equal error: at each of the engine's points, the peer's instructions at the same
# final-state error (log-log interpolation between two points of one peer method; the fewer of
# the two methods) over the engine's; none where the error is outside both peers' points.
echo
echo "## At equal final-state error"
echo
echo "peer's Ir at the engine's error / the engine's Ir, at each of the engine's settings:"
echo
python3 - "$rows" <<'PY'
import math, re, sys
scenes = {}
for line in open(sys.argv[1]):
    if line.startswith("## "):
        scene = line[3:].strip()
        scenes[scene] = []
    m = re.match(r"\| (metrosync \w+|peer \w+) \| (\S+) \| (\S+) \| (\d+) \|", line)
    if m:
        scenes[scene].append((m.group(1), m.group(2), float(m.group(3)), int(m.group(4))))
def peer_ir(rows, err):
    best = None
    for side in sorted({r[0] for r in rows if r[0].startswith("peer")}):
        pts = sorted(((e, ir) for s, _, e, ir in rows if s == side), reverse=True)
        for (e1, i1), (e2, i2) in zip(pts, pts[1:]):
            if e1 >= err >= e2 and e1 > e2:
                t = math.log(err / e1) / math.log(e2 / e1)
                v = math.exp(math.log(i1) + t * math.log(i2 / i1))
                best = v if best is None else min(best, v)
    return best
for scene, rows in scenes.items():
    cells = []
    for s, setting, err, ir in rows:
        if s.startswith("metrosync"):
            p = peer_ir(rows, err)
            cells.append("%s (err %.2g): %s" % (setting, err, "%.2fx" % (p / ir) if p else "-"))
    print("- %s: %s" % (scene, "; ".join(cells)))
PY
