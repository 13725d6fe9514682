#!/bin/sh
# Runs a command under the limits issue 17 sets for hostile input: 200 MB of address space and
# 5 s of wall time (killed after; exit 137).
ulimit -v 204800 || exit 99
exec timeout -s KILL 5 "$@"
