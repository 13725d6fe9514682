#!/usr/bin/env bash
# Writes metrosync.1 from the binary's own --help texts with help2man (Debian package help2man):
# the top-level help, then one section per sub-command with that command's --help.
#   manpage.sh METROSYNC_BINARY OUT_FILE
set -euo pipefail
bin="$1"
out="$2"
include=$(mktemp)
trap 'rm -f "$include"' EXIT

commands=$("$bin" --help | awk '/^Subcommands:/{on=1; next} on && /^  [a-z]/{print $1} on && /^$/{on=0}')
{
  echo "[COMMANDS]"
  for c in $commands; do
    echo ".SS metrosync $c"
    echo ".nf"
    # roff: a leading dot or quote would be a request, backslashes escapes
    "$bin" "$c" --help | sed -e 's/\\/\\e/g' -e "s/^\([.']\)/\\\\\&\1/"
    echo ".fi"
  done
  echo "[FILES]"
  echo "The example rigs are installed in /usr/share/metrosync/rigs (or PREFIX/share/metrosync/rigs);"
  echo "the reference documentation in /usr/share/doc/metrosync."
} > "$include"
help2man --no-info --section 1 --name "coupled metronomes on a platform with dry friction" \
  --include "$include" --version-string "$("$bin" --version | head -1)" \
  --help-option --help "$bin" > "$out"
