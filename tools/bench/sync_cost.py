#!/usr/bin/env python3
"""The cost of making a run's files durable, three ways (docs/bench/process.md).

Writes 4 files the size of the speed scene's outputs (150, 60, 20, 3 kB) to temporary names in
DIR, makes them durable, renames them and fsyncs DIR; the median over REPS of the time from the
first sync to the directory's fsync, for each way:
  fsync each          fsync of each file in turn (metrosync before the batch)
  write-back + fsync  sync_file_range(WRITE) on every file, then fsync of each in turn
  concurrent          sync_file_range(WRITE) on every file, then their fsyncs at once, one
                      thread each (CommitBatch, sim/record/atomic_file.h)
  syncfs              one syncfs (the whole filesystem)
Usage: tools/bench/sync_cost.py [DIR (default: a new folder under /tmp)] [REPS (default 15)]
"""
import ctypes
import os
import statistics
import sys
import tempfile
import threading
import time

libc = ctypes.CDLL(None, use_errno=True)
SYNC_FILE_RANGE_WRITE = 2
SIZES = [150_000, 60_000, 20_000, 3_000]


def fsync_each(fds):
    for fd in fds:
        os.fsync(fd)


def batch(fds):
    for fd in fds:
        libc.sync_file_range(fd, ctypes.c_longlong(0), ctypes.c_longlong(0),
                             ctypes.c_uint(SYNC_FILE_RANGE_WRITE))
    for fd in fds:
        os.fsync(fd)


def concurrent(fds):
    for fd in fds:
        libc.sync_file_range(fd, ctypes.c_longlong(0), ctypes.c_longlong(0),
                             ctypes.c_uint(SYNC_FILE_RANGE_WRITE))
    threads = [threading.Thread(target=os.fsync, args=(fd,)) for fd in fds[1:]]
    for t in threads:
        t.start()
    os.fsync(fds[0])
    for t in threads:
        t.join()


def syncfs(fds):
    libc.syncfs(fds[0])


def once(directory, how):
    fds, names = [], []
    for k, size in enumerate(SIZES):
        name = os.path.join(directory, ".f%d.part" % k)
        fd = os.open(name, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644)
        os.write(fd, b"x" * size)
        fds.append(fd)
        names.append(name)
    t0 = time.perf_counter()
    how(fds)
    for fd, name in zip(fds, names):
        os.close(fd)
        os.rename(name, name.replace(".part", "").replace("/.f", "/f"))
    d = os.open(directory, os.O_RDONLY | os.O_DIRECTORY)
    os.fsync(d)
    os.close(d)
    return time.perf_counter() - t0


def main():
    directory = sys.argv[1] if len(sys.argv) > 1 else tempfile.mkdtemp(prefix="metrosync_sync_")
    reps = int(sys.argv[2]) if len(sys.argv) > 2 else 15
    os.makedirs(directory, exist_ok=True)
    ways = [("fsync each", fsync_each), ("write-back+fsync", batch),
            ("concurrent (chosen)", concurrent), ("syncfs", syncfs)]
    for label, how in ways:
        t = [once(directory, how) for _ in range(reps)]
        print("%-20s median %.2f ms  min %.2f ms" % (label, statistics.median(t) * 1e3,
                                                     min(t) * 1e3))


if __name__ == "__main__":
    main()
