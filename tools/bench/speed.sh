#!/usr/bin/env bash
# Speed at equal error against a careful C++ program (issue 23), in one run: regenerates
# docs/bench/speed/ and README.md's speed paragraph (the text between its speed:begin and
# speed:end markers).
#   1. the careful peer (../shared/peer, beside the repository on the project's machines): found or
#      built (`metrosync_bench peer`; PEER=PATH or METROSYNC_PEER=PATH to give it); when it is
#      missing (CI has no shared/) the script says so and goes on without the ratio tables
#   2. `metrosync_bench precision` on the bench scenes: metrosync's direct engine (every
#      integrator) and the peer (dopri5, rkf78) over the accuracies, against a reference at 1e-13
#      that the peer cross-checks: ratios at equal final-state error with the verdict per scene
#      and overall (ratios.md, verdicts.md), the N-slope of metrosync's cost per fast period
#   3. `metrosync_bench runcost`: `metrosync run` against its engine (run.md)
#   4. `metrosync_bench maps`: the 64 x 64 full-model map and the 100 x 100 slow map (maps.md)
#   5. `metrosync_bench summary`: the folder's README.md and README.md's paragraph
#
#   tools/bench/speed.sh [--no-maps] [--no-readme] [OUT_DIR]   (default docs/bench/speed)
#
# Needs build/metrosync and build/metrosync_bench (cmake --build build --target metrosync
# metrosync_bench). Knobs (environment): SCENES, RUN_SCENES, METHODS, ACCURACIES, REPEAT (timed
# runs per point, default 7), RUN_REPEAT (default 11), MAP_REPEAT (default 1), MAX_LOAD (wait
# before each timed run until the 1-minute load is below it; default 0: never), MAX_WAIT (at most
# this many seconds per run, default 600), BUDGET, BUILD (the build directory), PEER. A quick
# look elsewhere:
#   SCENES="peer-n2 experiment-short" ACCURACIES=1e-6,1e-8,1e-10 REPEAT=5 \
#     tools/bench/speed.sh --no-maps --no-readme /tmp/speed
set -euo pipefail
cd "$(dirname "$0")/../.."

maps=1
readme=1
out=docs/bench/speed
for a in "$@"; do
  case $a in
    --no-maps) maps=0 ;;
    --no-readme) readme=0 ;;
    -h | --help) sed -n '2,25p' "$0"; exit 0 ;;
    -*) echo "speed.sh: unknown option $a (--no-maps, --no-readme, OUT_DIR)" >&2; exit 2 ;;
    *) out=$a ;;
  esac
done

build=${BUILD:-build}
bench=$build/metrosync_bench
metrosync=$build/metrosync
scenes=${SCENES:-peer-n2 peer-n8 experiment-short experiment suppression n8 n32 n128}
# `run`: the bench scenes, and the default rig itself (a name is a bench scene, a path a rig file)
run_scenes=${RUN_SCENES:-peer-n2 peer-n8 experiment-short experiment suppression n8 yaml/rigs/experiment.yaml}
accuracies=${ACCURACIES:-1e-4,1e-5,1e-6,1e-7,1e-8,1e-9,1e-10,1e-11,1e-12}
repeat=${REPEAT:-7}
max_load=${MAX_LOAD:-0}
max_wait=${MAX_WAIT:-600}  # seconds a timed run waits for the load at most
for b in "$bench" "$metrosync"; do
  if [ ! -x "$b" ]; then
    echo "speed.sh: $b not found: build it first (cmake --build $build --target metrosync metrosync_bench)" >&2
    exit 2
  fi
done
mkdir -p "$out"
started=$(date -u '+%Y-%m-%d %H:%M UTC')
commit=$(git rev-parse --short HEAD 2>/dev/null || echo unknown)
git diff --quiet HEAD 2>/dev/null || commit="$commit (with uncommitted changes)"
load_start=$(cut -d' ' -f1-3 /proc/loadavg)
commands=()
quote() {  # the arguments as a shell reads them back (single quotes where needed)
  local a out=
  for a in "$@"; do
    if [[ $a =~ ^[A-Za-z0-9_./:=,+@%-]+$ ]]; then out+=" $a"; else out+=" '${a//\'/\'\\\'\'}'"; fi
  done
  echo "${out# }"
}
step() {  # prints and records a command, then runs it
  local q
  q=$(quote "$@")
  commands+=("$q")
  echo "+ $q" >&2
  "$@"
}

# 1. the peer
peer_args=()
[ -n "${PEER:-}" ] && peer_args=(--peer "$PEER")
if peer=$("$bench" peer "${peer_args[@]}" 2>"$out/.peer.err"); then
  echo "speed.sh: the careful peer: $peer" >&2
  peer_methods=peer:dopri5,peer:rkf78
  peer_checks=(--cross-check peer:rkf78:1e-13)
  peer_note="the careful peer: \`$peer\`"
else
  why=$(cat "$out/.peer.err")
  echo "speed.sh: THE CAREFUL PEER IS MISSING: $why" >&2
  echo "speed.sh: no ratio tables in this run; the N-slope, run and the maps are measured" >&2
  peer_methods=
  peer_checks=()
  peer_note="the careful peer: **missing** ($why); no ratio tables"
fi
rm -f "$out/.peer.err"
rm -f "$out"/wp-*.csv "$out"/wp-*.md "$out"/wp-*.png "$out"/ratios.* "$out"/nslope.csv \
  "$out"/verdicts.md "$out"/run.* "$out"/maps.*

# 2. work-precision against the peer
methods=${METHODS:-direct:*${peer_methods:+,$peer_methods}}
scene_args=()
for s in $scenes; do scene_args+=(--scene "yaml/rigs/bench/$s.yaml"); done
step "$bench" precision "${scene_args[@]}" --methods "$methods" --accuracies "$accuracies" \
  --repeat "$repeat" --max-load "$max_load" --max-wait "$max_wait" --budget "${BUDGET:-30}" \
  "${peer_args[@]}" --reference direct:verner76:1e-13 "${peer_checks[@]}" \
  --cross-check direct:verner76:1e-12 --out "$out" >/dev/null

# 3. run against its engine
run_args=()
for s in $run_scenes; do
  case $s in */*) run_args+=(--scene "$s") ;; *) run_args+=(--scene "yaml/rigs/bench/$s.yaml") ;; esac
done
step "$bench" runcost --metrosync "$metrosync" "${run_args[@]}" --repeat "${RUN_REPEAT:-11}" \
  --max-load "$max_load" --max-wait "$max_wait" --out "$out" >/dev/null || true

# 4. the maps
if [ "$maps" = 1 ]; then
  step "$bench" maps --metrosync "$metrosync" --repeat "${MAP_REPEAT:-1}" --max-load "$max_load" \
    --max-wait "$max_wait" --out "$out" >/dev/null || true
fi

# 5. provenance, the summary, README.md
load_end=$(cut -d' ' -f1-3 /proc/loadavg)
cpu=$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//')
{
  echo "Measured $started to $(date -u '+%H:%M UTC') by \`tools/bench/speed.sh${*:+ $*}\`, commit" \
    "$commit, on $(nproc) cores ($cpu) shared with the project's other sessions: load average" \
    "(1, 5, 15 min) $load_start at the start, $load_end at the end (every table gives the" \
    "1-minute load of its own timed runs). Medians of $repeat timed runs per point of the" \
    "work-precision; $peer_note."
  echo
  echo "The commands, in order:"
  echo
  for c in "${commands[@]}"; do echo "    $c"; done
  summary_args=(--dir "$out" --date "${started%% *}" --commit "$commit")
  [ "$readme" = 1 ] && summary_args+=(--readme README.md)
  echo "    $(quote "$bench" summary "${summary_args[@]}")"
} >"$out/provenance.md"
"$bench" summary "${summary_args[@]}"
echo
[ -f "$out/verdicts.md" ] && sed -n '1,/^| scene/p' "$out/verdicts.md" | head -n -1
[ -f "$out/run.md" ] && grep -m1 '^\*\*' "$out/run.md"
[ -f "$out/maps.md" ] && grep '^| \(full\|slow\)' "$out/maps.md"
echo "speed.sh: wrote $out/README.md$([ "$readme" = 1 ] && echo ' and README.md'\''s speed paragraph')"
