#!/usr/bin/env bash
# Fuzzes the problem-file reader with libFuzzer for a bounded time: fuzz/run.sh [SECONDS]
# (default 60). Configures and builds the clang fuzz build in build-fuzz (FUZZ_BUILD overrides),
# seeds the corpus from examples/*.toml and tests/bad_input/*.toml (plus the same files with a
# --set override appended, see problem_file_fuzz.cpp), and runs until SECONDS have passed or
# something is found. The corpus grows across runs in build-fuzz/corpus; a finding is written to
# build-fuzz/artifacts/ and the script exits non-zero. See docs/fuzzing.md.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
seconds=${1:-60}
build=${FUZZ_BUILD:-$root/build-fuzz}

if ! command -v clang++ >/dev/null; then
  echo "fuzz: clang++ not found (bash scripts/install-deps.sh installs clang and libFuzzer)" >&2
  exit 1
fi

cmake -S "$root/fuzz" -B "$build" -G Ninja -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "$build" --target problem_file_fuzz

corpus=$build/corpus/problem_file
seeds=$build/seeds/problem_file
artifacts=$build/artifacts
rm -rf "$seeds"
mkdir -p "$corpus" "$seeds" "$artifacts"
cp "$root"/examples/*.toml "$root"/tests/bad_input/*.toml "$seeds"/
# Seeds for the --set path: a file, a NUL, then one override.
i=0
for o in 'mesh.cells=[24,8,8]' 'material.young=2e11' 'contact.friction.law=constant' \
  'traction[1].value=[0,0,-1e7]' 'dirichlet.1.boundary=x1' 'mesh.cells.0=24' \
  'output.dir="results/run 1"' 'contact.slip_bound=1e7' 'material.model=anisotropic'; do
  printf '%s\0%s' "$(cat "$root/examples/paper-brick.toml")" "$o" >"$seeds/set-$i"
  i=$((i + 1))
done

export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
echo "fuzz: problem_file_fuzz for ${seconds} s (corpus $corpus)"
"$build/problem_file_fuzz" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
  -max_len=16384 -dict="$root/fuzz/problem_file.dict" -artifact_prefix="$artifacts/" \
  -print_final_stats=1 "$corpus" "$seeds"
