#!/bin/sh
# Runs a command with at most N processes and threads for its user (RLIMIT_NPROC), the limit
# under which a thread cannot start (issue 29): run_threads_limited.sh N COMMAND...
# Root ignores RLIMIT_NPROC, so as root the command runs as `nobody` (whose only process it is:
# N - 1 threads can start besides its main one). As another user, the user's other processes
# count too: fewer threads, often none, can start.
n=$1
shift
if [ "$(id -u)" = 0 ]; then
  exec prlimit --nproc="$n:$n" -- setpriv --reuid=nobody --regid=nogroup --clear-groups -- "$@"
fi
exec prlimit --nproc="$n:$n" -- "$@"
