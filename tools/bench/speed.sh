#!/usr/bin/env bash
# Speed against a careful C++ program (issues 23 and 36), in one run: every figure of issue 36's
# table, written under docs/bench/speed/ and printed, and README.md's speed paragraph (the text
# between its speed:begin and speed:end markers) regenerated, naming the peer measured against.
#   1. the careful peer (../shared/peer, beside the repository on the project's machines): found or
#      built (`metrosync_bench peer`; PEER=PATH or METROSYNC_PEER=PATH to give it), named in
#      peer.md (PEER_NAME to name another); when it is missing (CI has no shared/) the script says
#      so and goes on without the ratio tables
#   2. `metrosync_bench precision` on the bench scenes: the direct engine (every integrator), the
#      peer (dopri5, rkf78) and `metrosync run` itself (run:INTEGRATOR, on RUN_PRECISION_SCENES)
#      over the accuracies, against a reference at 1e-13 that the peer cross-checks: the engine's
#      and `run`'s ratios to the peer at equal final-state error, `run`'s wall_seconds against
#      its engine_seconds and against the engine with recording off at each point
#   3. `metrosync_bench runcost`: `run` against its engine on every bench scene and the default
#      rig (`metrosync run --no-plot`), with the same engine alone, recording off (run.md)
#   4. `metrosync_bench process`: the whole process on the peer's scene, phase by phase
#   5. `metrosync_bench eventcost`: cost per step and per event against one RHS evaluation at
#      N = 2, 8, 32, 128
#   6. `metrosync_bench fitcost`: one fit on the fit bench, against one run of the same rig
#   7. `metrosync_bench continue`: `continue --all` at N = 32 on both n32 rigs
#   8. `metrosync_bench maps` (not with --no-maps): the two regime maps
#   9. `metrosync_bench summary`: every figure beside its target (the folder's README.md) and
#      README.md's paragraph
#
#   tools/bench/speed.sh [--no-maps] [--no-readme] [OUT_DIR]   (default docs/bench/speed)
#
# Needs build/metrosync, build/metrosync_bench and build/metrosync_fit_bench (cmake --build build
# --target metrosync metrosync_bench metrosync_fit_bench). Knobs (environment): QUICK=1 (a short
# run end to end: 3 scenes, 4 accuracies, 3 repeats, 2 fit records, continuation stopped after
# 60 s, no maps; not a result), SCENES, RUN_PRECISION_SCENES, RUN_SCENES, METHODS, ACCURACIES,
# REPEAT (timed runs per point, default 7), RUN_REPEAT (default 11), PROCESS_REPEAT (default 21),
# EVENT_SCENES, EVENT_ACCURACIES, FIT_RECORDS (default 50), FIT_RUN_REPEAT, CONT_REPEAT,
# CONT_TIMEOUT (seconds, 0: none), MAP_REPEAT, MAX_LOAD (wait before each timed run until the
# 1-minute load is below it; default 0: never), MAX_WAIT (at most this many seconds per run,
# default 600), BUDGET, BUILD (the build directory), PEER, PEER_NAME.
set -euo pipefail
cd "$(dirname "$0")/../.."

maps=1
readme=1
out=docs/bench/speed
for a in "$@"; do
  case $a in
    --no-maps) maps=0 ;;
    --no-readme) readme=0 ;;
    -h | --help) sed -n '2,37p' "$0"; exit 0 ;;
    -*) echo "speed.sh: unknown option $a (--no-maps, --no-readme, OUT_DIR)" >&2; exit 2 ;;
    *) out=$a ;;
  esac
done

quick=${QUICK:-0}
q() { [ "$quick" = 1 ] && echo "$1" || echo "$2"; }  # the quick setting, or the full one
build=${BUILD:-build}
bench=$build/metrosync_bench
metrosync=$build/metrosync
fit_bench=$build/metrosync_fit_bench
scenes=${SCENES:-$(q "peer-n2 peer-n8 suppression" "peer-n2 peer-n8 experiment-short experiment suppression n8 n32 n128")}
run_precision_scenes=${RUN_PRECISION_SCENES:-peer-n2,peer-n8,suppression}
# `run`: every bench scene and the default rig (a name is a bench scene, a path a rig file,
# `default` the built-in rig)
run_scenes=${RUN_SCENES:-peer-n2 peer-n8 experiment-short experiment suppression n8 n32 n128 default}
accuracies=${ACCURACIES:-$(q 1e-6,1e-8,1e-10,1e-12 1e-4,1e-5,1e-6,1e-7,1e-8,1e-9,1e-10,1e-11,1e-12)}
repeat=${REPEAT:-$(q 3 7)}
max_load=${MAX_LOAD:-0}
max_wait=${MAX_WAIT:-600}  # seconds a timed run waits for the load at most
[ "$quick" = 1 ] && maps=0
for b in "$bench" "$metrosync" "$fit_bench"; do
  if [ ! -x "$b" ]; then
    echo "speed.sh: $b not found: build it first (cmake --build $build --target metrosync" \
      "metrosync_bench metrosync_fit_bench)" >&2
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
common=(--max-load "$max_load" --max-wait "$max_wait")

# 1. the peer, and its name
peer_args=()
[ -n "${PEER:-}" ] && peer_args=(--peer "$PEER")
rm -f "$out"/wp-*.csv "$out"/wp-*.md "$out"/wp-*.png "$out"/ratios.* "$out"/nslope.csv \
  "$out"/verdicts.md "$out"/run.* "$out"/runpoints.csv "$out"/maps.* "$out"/process.* \
  "$out"/eventcost.* "$out"/fit.* "$out"/continuation.* "$out"/peer.md
if peer=$("$bench" peer "${peer_args[@]}" 2>"$out/.peer.err"); then
  echo "speed.sh: the careful peer: $peer" >&2
  peer_methods=peer:dopri5,peer:rkf78
  peer_checks=(--cross-check peer:rkf78:1e-13)
  peer_note="the careful peer: \`$peer\`"
  src=$(cd "$(git rev-parse --git-common-dir 2>/dev/null || echo .git)/.." && pwd)/../shared/peer/peer.cpp
  hash=$([ -f "$src" ] && sha256sum "$src" | cut -c1-12 || echo unknown)
  # named by its source's hash, not by a path outside the repository (docs:pointers)
  peer_default="\`shared/peer\` (beside the repository on the project's machines, not in a clone; peer.cpp sha256 $hash...)"
  echo "${PEER_NAME:-$peer_default}" >"$out/peer.md"
else
  why=$(cat "$out/.peer.err")
  echo "speed.sh: THE CAREFUL PEER IS MISSING: $why" >&2
  echo "speed.sh: no ratio tables in this run; the rest is measured" >&2
  peer_methods=
  peer_checks=()
  peer_note="the careful peer: **missing** ($why); no ratio tables"
fi
rm -f "$out/.peer.err"

# 2. work-precision against the peer: the engine and `run`
methods=${METHODS:-$(q "direct:verner76,direct:dopri5" "direct:*")${peer_methods:+,$peer_methods},run:$(q verner76 "*")}
scene_args=()
for s in $scenes; do scene_args+=(--scene "yaml/rigs/bench/$s.yaml"); done
step "$bench" precision "${scene_args[@]}" --methods "$methods" --accuracies "$accuracies" \
  --repeat "$repeat" "${common[@]}" --budget "${BUDGET:-30}" "${peer_args[@]}" \
  --metrosync "$metrosync" --run-scenes "$run_precision_scenes" \
  --reference direct:verner76:1e-13 "${peer_checks[@]}" --cross-check direct:verner76:1e-12 \
  --out "$out" >/dev/null

# 3. run against its engine
run_args=()
for s in $run_scenes; do
  case $s in */* | default) run_args+=(--scene "$s") ;; *) run_args+=(--scene "yaml/rigs/bench/$s.yaml") ;; esac
done
# (the rig as it is; sampled every 100 periods; the recording thread never, always, and nothing
# off the run's thread, against the engine's own choice: docs/outputs.md)
step "$bench" runcost --metrosync "$metrosync" "${run_args[@]}" --variant "" \
  --variant simulation.sample=100 --variant env:METROSYNC_RECORDING_THREAD=never \
  --variant env:METROSYNC_RECORDING_THREAD=always --variant env:METROSYNC_RECORDING_THREAD=inline \
  --repeat "${RUN_REPEAT:-$(q 3 11)}" "${common[@]}" --out "$out" >/dev/null || true

# 4. the whole process on the peer's scene
step "$bench" process --metrosync "$metrosync" --scene yaml/rigs/bench/peer-n2.yaml \
  --repeat "${PROCESS_REPEAT:-$(q 5 21)}" "${common[@]}" --out "$out" >/dev/null || true

# 5. cost per step and per event
event_args=()
for s in ${EVENT_SCENES:-experiment-short n8 n32 n128}; do event_args+=(--scene "yaml/rigs/bench/$s.yaml"); done
step "$bench" eventcost "${event_args[@]}" --accuracies "${EVENT_ACCURACIES:-$(q 1e-6 1e-6,1e-9)}" \
  --repeat "$repeat" "${common[@]}" --out "$out" >/dev/null || true

# 6. one fit
step "$bench" fitcost --fit-bench "$fit_bench" --metrosync "$metrosync" \
  --records "${FIT_RECORDS:-$(q 2 50)}" --run-repeat "${FIT_RUN_REPEAT:-$(q 2 5)}" "${common[@]}" \
  --out "$out" >/dev/null || true

# 7. continue --all at N = 32
step "$bench" continue --metrosync "$metrosync" --rig yaml/rigs/bench/n32.yaml \
  --rig yaml/rigs/n32.yaml --repeat "${CONT_REPEAT:-1}" --timeout "${CONT_TIMEOUT:-$(q 60 0)}" \
  "${common[@]}" --out "$out" >/dev/null || true

# 8. the maps
if [ "$maps" = 1 ]; then
  step "$bench" maps --metrosync "$metrosync" --repeat "${MAP_REPEAT:-1}" "${common[@]}" \
    --out "$out" >/dev/null || true
fi

# 9. provenance, the summary, README.md
load_end=$(cut -d' ' -f1-3 /proc/loadavg)
cpu=$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//')
{
  echo "Measured $started to $(date -u '+%H:%M UTC') by \`$([ "$quick" = 1 ] && echo 'QUICK=1 ')tools/bench/speed.sh${*:+ $*}\`," \
    "commit $commit, on $(nproc) cores ($cpu) shared with the project's other sessions: load" \
    "average (1, 5, 15 min) $load_start at the start, $load_end at the end (every table gives" \
    "the 1-minute load of its own timed runs). Medians of $repeat timed runs per point of the" \
    "work-precision; $peer_note.$([ "$quick" = 1 ] && echo ' QUICK=1: shortened settings, not a result.')"
  knobs=$(for k in QUICK SCENES RUN_PRECISION_SCENES RUN_SCENES METHODS ACCURACIES REPEAT RUN_REPEAT \
      PROCESS_REPEAT EVENT_SCENES EVENT_ACCURACIES FIT_RECORDS FIT_RUN_REPEAT CONT_REPEAT CONT_TIMEOUT \
      MAP_REPEAT MAX_LOAD MAX_WAIT BUDGET; do if [ -n "${!k:-}" ]; then printf "%s=%q " "$k" "${!k}"; fi; done)
  if [ -n "$knobs" ]; then echo "Knobs set: \`${knobs% }\` (the commands below carry them)."; fi
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
sed -n '/^## Every figure against its target/,/^## How it was made/p' "$out/README.md" | sed '1d;$d'
[ -f "$out/process.md" ] && sed -n '/^| part/,/^| whole process/p' "$out/process.md"
echo "speed.sh: wrote $out/README.md$([ "$readme" = 1 ] && echo ' and README.md'\''s speed paragraph')"
