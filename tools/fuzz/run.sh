#!/usr/bin/env bash
# The fuzz stage (issue 39): each libFuzzer target of build-fuzz (tools/setup.sh fuzz builds
# them) for a bounded time, from its seed corpus: the shipped rigs, the hostile corpus and
# tools/fuzz/corpus/<target>/ (regression inputs and seeds). Fails on a crash, a finding (an
# abort: tools/fuzz/fuzz_entries.h), a leak, an input that takes more than 1 s or more than
# 2048 MB. A failing input is left in build-fuzz/findings/: copy it into tools/fuzz/corpus/<target>/
# with the fix, where tests/fuzz replays it in every build.
#   bash tools/fuzz/run.sh [SECONDS_PER_TARGET]   (default: $METROSYNC_FUZZ_SECONDS, else 30)
set -euo pipefail
cd "$(dirname "$0")/../.."

seconds="${1:-${METROSYNC_FUZZ_SECONDS:-30}}"
build="${METROSYNC_FUZZ_BUILD:-build-fuzz}"

seeds() {
  case "$1" in
    rig | network) echo yaml/rigs tests/hostile/corpus ;;
    keys | data | options) echo "" ;;
  esac
}

status=0
for target in rig network keys data options; do
  work="$build/corpus/$target"  # what libFuzzer adds, kept between runs
  mkdir -p "$work" "$build/findings"
  echo "fuzz: $target for ${seconds} s"
  # shellcheck disable=SC2046
  if ! ASAN_OPTIONS=detect_leaks=1:detect_odr_violation=2 \
       UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
       "$build/fuzz_$target" -max_total_time="$seconds" -timeout=1 -rss_limit_mb=2048 \
         -print_final_stats=1 -artifact_prefix="$build/findings/$target-" \
         "$work" "tools/fuzz/corpus/$target" $(seeds "$target") \
         >"$build/fuzz-$target.log" 2>&1; then
    echo "fuzz: $target FAILED (log: $build/fuzz-$target.log, input: $build/findings/)" >&2
    tail -n 40 "$build/fuzz-$target.log" >&2
    status=1
  else
    grep -E '^stat::number_of_executed_units|^stat::peak_rss_mb' "$build/fuzz-$target.log" |
      tr '\n' ' ' | sed "s/^/fuzz: $target: /;s/ $/\n/"
  fi
done
exit $status
