"""The table of tests/docs/run_docs.py: how a command of README.md or docs/ is run when not as
shown, or why it cannot run in a test. A command runs as shown when no entry matches it; each run
must take at most a minute on 2 cores, the whole `docs` label at most 10 minutes.

Each entry: `match`, a regular expression searched in the command's first line (whitespace
collapsed); optionally `file`, the page it applies to; then one of
  skip:     why the command cannot run in a test (it is listed, never silently dropped);
  replace:  [(pattern, replacement), ...] applied to the command, with `why`: the shortened form
            the test runs (a smaller grid, --quick, a shorter tau);
and optionally `before` (shell run first, in the same folder), `expect` (the exit code; default 0,
or 2 for a transcript that shows an error) and `defer` (run after the page's other commands:
its data are made further down the page). The first matching entry wins.
`ctest -R docs:table` fails on an entry that matches no command any more.
"""

# a grid of 100 x 100 points takes minutes with the full model and ~20 s of CPU with the slow flow
SMALL_GRID = [(r":(100|200)(:open)?\b", r":6\2")]

TABLE = [
    # --- synopses: placeholders, not commands ---------------------------------------------------
    {"match": r"(^|\s)\[|\.\.\.|(?<![\w$'\"/.=-])(RIG|KEY|DIR|INDEX|FILE|NETWORK|SCENE|DATA|CMD|"
              r"VALUE|LINE|P|S|N|J|D|K|OUT)(?![\w])|\w\|\w",
     "skip": "a synopsis with placeholders (RIG, KEY, [options], ...), not a command"},

    # --- set-up and the test command itself -----------------------------------------------------
    {"match": r"^bash tools/setup\.sh test",
     "skip": "runs every test, this one included (it is CI's .ci/run)"},
    {"match": r"^bash tools/setup\.sh run", "replace": [(r"^bash tools/setup\.sh run", "build/metrosync run")],
     "why": "its apt-get and build are the ones that made this build tree; its last step runs"},
    {"match": r"^python3 -m pip (install|wheel)",
     "skip": "installs into the running Python / builds a wheel from the source tree: tests/pip "
             "does both in a virtual environment"},
    {"match": r"^bash ../shared|^tools/bench/(speed|instructions)\.sh|SCENES=",
     "skip": "the speed instrument: hours on a quiet machine, and the careful peer is not part of "
             "this repository (tests/bench covers the tool)"},

    {"match": r"--shard \"\$SLURM_ARRAY_TASK_ID", "file": "docs/cluster.md",
     "skip": "a Slurm job array's task: Slurm sets its variables (tests/sweep runs --shard and "
             "merge, tests/mpi the MPI sweep)"},
    {"match": r"--out /tmp/v'$", "file": "docs/install.md",
     "skip": "the second line of a command run inside a debootstrap chroot (a clean Debian "
             "installed from the network: not part of CI)"},
    {"match": r"^metrosync fit rig\.yaml data\.csv", "file": "docs/fit.md",
     "skip": "its record (a Simbody run of a variant of experiment.yaml with noise) is described "
             "in prose, not made by commands on the page; tests/fit fits this case"},

    # --- data made elsewhere on the page, or stood in for ---------------------------------------
    {"match": r"^metrosync fit yaml/rigs/(board-on-springs\.yaml springs|experiment\.yaml decay)"
              r"\.csv", "file": "docs/fit.md", "defer": True,
     "why": "springs.csv and decay.csv are made by the measured example further down"},
    {"match": r"^metrosync fit yaml/rigs/experiment\.yaml data\.csv --free", "file": "docs/keys.md",
     "before": "printf 't,theta_1\\n0,0.1\\n0.01,0.09\\n0.02,0.07\\n' > data.csv",
     "why": "the reader's data.csv: three rows stand in (the key is refused before they are fitted)"},
    {"match": r"^build/metrosync merge part1 part2 part3 part4", "file": "docs/maps/README.md",
     "before": "for k in 1 2 3 4; do build/metrosync sweep yaml/rigs/experiment-map.yaml "
               "--vary platform.friction.mu=0:1:8 --set simulation.tau=50 --shard $k/4 "
               "--out part$k -q --no-plot || exit 1; done",
     "why": "the four shards of the synopsis above, made first on an 8-point grid"},

    # --- long runs, shortened ---------------------------------------------------------------------
    {"match": r"--model full --vary metronomes.0.start.phi=0:2pi:(100|32):open",
     "file": "docs/maps/README.md", "replace": [(r":(100|32)(:open)?\b", r":8\2")],
     "why": "an 8 x 8 grid (the full model's 100 x 100 map takes hours, 32 x 32 minutes)"},
    {"match": r"--vary metronomes.1.alpha=0:5:100 --vary platform.friction.mu=0:3:100",
     "file": "docs/maps/README.md", "replace": [(r":100\b", r":20")],
     "why": "a 20 x 20 grid (100 x 100: about two minutes of CPU)"},
    {"match": r"simulation.accuracy=1e-12 --vary", "file": "docs/bench/slow-flow-speed.md",
     "replace": [(r":100(:open)?\b", r":12\1")],
     "why": "a 12 x 12 grid of the reference map (100 x 100 at 1e-12 on one thread: minutes)"},
    # the benchmarks: one quick point each, timed once, without waiting for a quiet machine
    {"match": r"^\./build/metrosync_bench precision --scene yaml/rigs/bench/experiment\.yaml",
     "file": "docs/bench/README.md",
     "replace": [(r"bench/experiment\.yaml", "bench/experiment-short.yaml"),
                 (r"--cross-check simbody:rk-merson:1e-12 ", ""),
                 (r"--out docs/bench", "--methods direct:verner76,direct:dopri5 --accuracies "
                                       "1e-4,1e-6 --repeat 1 --max-load 0 --out docs/bench")],
     "why": "the short scene, two direct methods at two accuracies, timed once (the full "
            "measurement: hours on a quiet machine)"},
    {"match": r"^\./build/metrosync_bench precision --scene yaml/rigs/bench/experiment-short\.yaml "
              r"--siconos-steps", "file": "docs/bench/README.md",
     "skip": "Siconos's Moreau-Jean steps: the bench has Siconos only when built with Debian's "
             "libsiconos-kernel-dev, which tools/setup.sh does not install"},
    {"match": r"^\./build/metrosync_bench precision --scene yaml/rigs/bench/\$s\.yaml",
     "file": "docs/bench/README.md",
     "replace": [(r"\$s\.yaml", "experiment-short.yaml"), (r"--methods \S+", "--methods "
                  "direct:verner76,simbody:rk-merson"), (r"--simbody-accuracies \S+",
                  "--simbody-accuracies 1e-4"), (r"--cross-check simbody:rk-merson:1e-12 ", ""),
                 (r"--out docs/bench", "--accuracies 1e-4,1e-6 --repeat 1 --max-load 0 --out "
                                       "docs/bench")],
     "why": "the loop's body for one scene (experiment-short), one method of each engine at "
            "low accuracies, timed once"},
    {"match": r"^\./build/metrosync_bench nscale", "file": "docs/bench/README.md",
     "replace": [(r"--methods \S+", "--methods direct:verner65:1e-8,direct:dopri5:1e-8 --n 2,8 "
                  "--periods 5 --repeat 1 --max-load 0")],
     "why": "N = 2 and 8, 5 fast periods, the direct engine's two methods, timed once"},
    {"match": r"^metrosync_fit_bench --records 50 --seed 1", "file": "docs/fit.md",
     "replace": [(r"--records 50", "--records 2"), (r"--duration 30", "--duration 8")],
     "why": "2 records of 8 s (50 of 30 s: half an hour of CPU)"},
    {"match": r"^\./build/metrosync validate --engine direct --out docs/validation",
     "replace": [(r"--out docs/validation", "--quick --out docs/validation")],
     "why": "--quick, the reduced plan (the full plan takes minutes on a loaded machine)"},
]
