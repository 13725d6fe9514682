#!/usr/bin/env bash
# What a cold build costs, file by file: configures a scratch build directory (no ccache), builds
# the given targets (default: metrosync, what `bash tools/setup.sh run` builds) with every compile
# timed, then prints the wall time, the CPU seconds of compiling per folder and the costliest files.
#   bash tools/bench/compile_cost.sh [--dir DIR] [--jobs J] [TARGET...] [-- CMAKE_ARGS...]
# e.g. `bash tools/bench/compile_cost.sh -- -DMETROSYNC_PCH=OFF` for the cost without precompiled
# headers. Take it on a quiet machine: each file's time is its wall time.
set -euo pipefail
cd "$(dirname "$0")/../.."
dir=$(mktemp -d /tmp/metrosync-compile-cost.XXXXXX)
jobs=$(nproc 2>/dev/null || echo 2)
targets=()
cmake_args=()
while [ $# -gt 0 ]; do
  case "$1" in
    --dir) dir="$2"; shift 2 ;;
    --jobs) jobs="$2"; shift 2 ;;
    --) shift; cmake_args=("$@"); break ;;
    *) targets+=("$1"); shift ;;
  esac
done
[ ${#targets[@]} -eq 0 ] && targets=(metrosync)
mkdir -p "$dir"
log="$dir/compile-times.txt"
: > "$log"
launcher="$dir/timed-compile.sh"
cat > "$launcher" <<LAUNCH
#!/usr/bin/env bash
s=\$(date +%s%N); "\$@"; rc=\$?; e=\$(date +%s%N)
src=""; prev=""; for a in "\$@"; do [ "\$prev" = "-c" ] && src="\$a"; prev="\$a"; done
echo "\$(( (e - s) / 1000000 )) \$src" >> "$log"
exit \$rc
LAUNCH
chmod +x "$launcher"
cmake -S . -B "$dir/build" -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER_LAUNCHER="$launcher" \
  "${cmake_args[@]}" >/dev/null
start=$(date +%s%N)
cmake --build "$dir/build" -j"$jobs" --target "${targets[@]}" >"$dir/build.log" 2>&1
end=$(date +%s%N)
echo "targets: ${targets[*]}; jobs: $jobs; cmake args: ${cmake_args[*]:-(none)}"
echo "wall: $(( (end - start) / 1000000 )) ms; build directory: $dir/build"
python3 - "$log" "$PWD" <<'PY'
import collections, sys
per_folder, files, total = collections.defaultdict(float), collections.Counter(), 0.0
rows = []
for line in open(sys.argv[1]):
    ms, src = line.split(None, 1)
    src = src.strip().replace(sys.argv[2] + "/", "")
    s = int(ms) / 1000
    folder = src.rsplit("/", 1)[0] if "/" in src else "."
    if "cmake_pch" in src:
        folder += " (precompiled header)"
    per_folder[folder] += s
    files[folder] += 1
    total += s
    rows.append((s, src))
print(f"compiling: {total:.1f} CPU s in {len(rows)} files")
for folder, s in sorted(per_folder.items(), key=lambda x: -x[1]):
    print(f"  {s:7.1f} s  {files[folder]:3d} files  {folder}")
print("costliest files:")
for s, src in sorted(rows, reverse=True)[:15]:
    print(f"  {s:6.1f} s  {src}")
PY
