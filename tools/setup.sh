#!/usr/bin/env bash
# One-command set-up on a fresh Debian 12: installs what is missing (apt-get), builds Release,
# then either runs the default rig (`run`, the main job, with its plots) or every test (`test`).
# `run` installs and builds only what `metrosync run` needs (the packages of run_packages, the
# target metrosync with the Simbody plugin it loads for --engine simbody); `test` adds
# test_packages and builds everything (tests, benches, the Python module, the man page).
#   bash tools/setup.sh run   [extra metrosync run arguments]
#   bash tools/setup.sh test
#   bash tools/setup.sh sanitize   (the `fast` tests under AddressSanitizer +
#                                   UndefinedBehaviorSanitizer, in build-fuzz)
#   bash tools/setup.sh fuzz [S]   (libFuzzer's targets in build-fuzz, S seconds each;
#                                   tools/fuzz/run.sh)
# `test` ends with both: one instrumented build (clang, build-fuzz) serves the two, so that CI
# (.ci/run) compiles the libraries twice, not three times.
set -euo pipefail
cd "$(dirname "$0")/.."

mode="${1:-run}"
shift || true

# what `metrosync run` needs to build and to draw its plot
run_packages=(cmake g++ make libsimbody-dev libeigen3-dev libyaml-cpp-dev nlohmann-json3-dev
              libfmt-dev  # base/number_text.cpp: the rows' text (header-only use)
              libcli11-dev zlib1g-dev gnuplot-nox)  # zlib: sweep's envelopes.csv.gz
# what the tests, benches, the Python module, fit, animate and metrosync-mpi add
test_packages=(libgtest-dev libbenchmark-dev
          libceres-dev  # metrosync fit (sim/analysis/fit)
          libboost-dev  # bench-only (tools/bench's Boost.Odeint peer, header-only)
          help2man dpkg-dev man-db  # the man page, the .deb's dependencies, and their tests
          bash-completion  # tests/install: bash finds the installed completion
          pybind11-dev python3-dev python3-numpy python3-pytest  # the Python module, its tests
          python3-yaml  # tests/python: the shipped rigs as dicts
          python3-setuptools python3-wheel python3-pip python3-venv  # pip install . (tests/pip)
          jupyter-nbconvert python3-ipykernel python3-matplotlib python3-pandas  # the notebooks
          libcairo2-dev pkg-config ffmpeg  # `metrosync animate`: Cairo draws, ffmpeg encodes
          libopenmpi-dev openmpi-bin  # metrosync-mpi: a sweep over MPI ranks (docs/cluster.md)
          clang libclang-rt-14-dev)  # the fuzz stage: libFuzzer, ASan, UBSan (tools/fuzz)
packages=("${run_packages[@]}")
if [ "$mode" != run ]; then packages+=("${test_packages[@]}"); fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  sudo_cmd=""
  [ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
  $sudo_cmd apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq "${missing[@]}" >/dev/null
fi

jobs=$(nproc 2>/dev/null || echo 2)
# ccache, when the machine has it, makes a rebuild of an unchanged file free
launcher=""
command -v ccache >/dev/null 2>&1 && launcher="-DCMAKE_CXX_COMPILER_LAUNCHER=ccache"

# The checked build: its own directory (clang, every object instrumented for libFuzzer's coverage
# and compiled with AddressSanitizer + UndefinedBehaviorSanitizer; -O1: a third of -O3's compile
# time, and what the sanitizers' documentation recommends for readable reports), building only
# what its two stages need:
#   sanitize: the `fast` tests under the sanitizers, every ODR violation and leak reported, the
#             first UB finding fatal;
#   fuzz:     each libFuzzer target for S seconds (default $METROSYNC_FUZZ_SECONDS, else 30),
#             failing on a crash, leak, slow input or memory limit (tools/fuzz/run.sh).
fast_tests=(test_contact test_models test_sim test_yaml test_layout test_bench_fast test_fuzz)
checked_build() {
  CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE=-O1 \
        -DMETROSYNC_FUZZ=ON $launcher >/dev/null
  cmake --build build-fuzz -j"$jobs" --target "$@"
}
sanitize_stage() {
  checked_build "${fast_tests[@]}"
  ASAN_OPTIONS=detect_odr_violation=2:detect_leaks=1 UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
    ctest --test-dir build-fuzz -L fast --output-on-failure -j"$jobs" --timeout 900
}
fuzz_stage() {
  checked_build fuzz_targets
  bash tools/fuzz/run.sh "$@"
}
case "$mode" in
  sanitize) sanitize_stage; exit $? ;;
  fuzz) fuzz_stage "$@"; exit $? ;;
esac

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release $launcher >/dev/null

case "$mode" in
  run)
    cmake --build build -j"$jobs" --target metrosync  # with the plugins it loads
    ./build/metrosync run "$@"
    ;;
  test)
    cmake --build build -j"$jobs"
    ctest --test-dir build --output-on-failure -j"$jobs" --timeout 900
    sanitize_stage
    fuzz_stage
    ;;
  *)
    echo "usage: bash tools/setup.sh run|test|sanitize|fuzz" >&2
    exit 2
    ;;
esac
