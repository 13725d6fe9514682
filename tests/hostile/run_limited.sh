#!/bin/sh
# Runs a command under the limits issue 17 sets for hostile input: 200 MB of address space and
# 5 s of wall time (killed after; exit 137). RUN_LIMITED_SECONDS overrides the wall time for a
# test whose run is meant to last (tests/hostile/test_big_sweep.cpp).
ulimit -v 204800 || exit 99
exec timeout -s KILL "${RUN_LIMITED_SECONDS:-5}" "$@"
