#!/bin/bash
# Digests of every shipped single-platform rig's outputs (issue 24: a single rig is a network of
# one, and its files stay bit for bit those of the build before the change).
#
#   tools/reference/single_rig_digests.sh write METROSYNC OUT.txt   # record (the pre-change build)
#   tools/reference/single_rig_digests.sh check METROSYNC REF.txt   # compare; exit 1 on a change
#
# Each rig runs `metrosync run RIG --quiet --no-plot` at its own duration. A line per rig: its
# path, then the SHA-256 of trajectory.csv, envelope.csv and events.csv (when written) and of
# summary.json's results at full precision (final, counts, energy, regime, complete: everything
# but timings and provenance). Networks of more than one platform are left out (their summary has
# `network`); a network of one (board-on-springs.yaml) is a single rig and is in.
set -euo pipefail
mode=${1:?write or check}
bin=${2:?the metrosync binary}
ref=${3:?the digest file}
root=$(cd "$(dirname "$0")/../.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

digest_rig() {  # rig path relative to root -> one line
  local rig=$1 out=$work/${1//\//_} line
  "$bin" run "$root/$rig" --quiet --no-plot --out "$out" >/dev/null
  if grep -q '"network"' "$out/summary.json"; then return; fi
  line=$rig
  for f in trajectory.csv envelope.csv events.csv; do
    if [[ -f $out/$f ]]; then line+=" $f=$(sha256sum <"$out/$f" | cut -c1-16)"; fi
  done
  line+=" summary=$(python3 -c '
import json, sys
s = json.load(open(sys.argv[1]))
keep = {k: s[k] for k in ("final", "counts", "energy", "regime", "regime_window", "complete") if k in s}
print(json.dumps(keep, sort_keys=True))' "$out/summary.json" | sha256sum | cut -c1-16)"
  echo "$line"
  rm -rf "$out"
}

# every rig's line, in order; four runs at a time (a run's wall time is mostly its files' syncs)
all_digests() {
  local rig k=0
  for rig in $(rigs); do
    digest_rig "$rig" >"$work/line.$(printf %03d $k)" &
    k=$((k + 1))
    if ((k % 4 == 0)); then wait; fi
  done
  wait
  cat "$work"/line.* | grep -v '^$' || true
}

rigs() {
  cd "$root"
  ls yaml/rigs/*.yaml yaml/rigs/paper/*.yaml yaml/rigs/bench/*.yaml
}

case $mode in
  write)
    {
      echo "# written by: tools/reference/single_rig_digests.sh write METROSYNC $(basename "$ref")"
      echo "# (from the build before a change to the single-platform path; see the script)"
      all_digests
    } >"$ref.tmp"
    mv "$ref.tmp" "$ref"
    ;;
  check)
    status=0
    all_digests >"$work/got"
    while read -r rig rest; do
      want=$(grep "^$rig " "$ref" || true)
      if [[ -z $want ]]; then
        echo "no reference for $rig (regenerate: see the head of $ref)"
        status=1
      elif [[ $want != "$rig $rest" ]]; then
        echo "changed: $rig"
        echo "  reference:  $want"
        echo "  this build: $rig $rest"
        status=1
      fi
    done <"$work/got"
    # and no rig of the reference went missing
    if [[ $(grep -c '^yaml/' "$ref") != $(wc -l <"$work/got") ]]; then
      echo "the reference has $(grep -c '^yaml/' "$ref") rigs, this build ran $(wc -l <"$work/got")"
      status=1
    fi
    exit $status
    ;;
  *)
    echo "usage: $0 write|check METROSYNC FILE" >&2
    exit 2
    ;;
esac
