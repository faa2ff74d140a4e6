#!/usr/bin/env bash
# Fuzzes fricon's readers with libFuzzer for a bounded time: fuzz/run.sh [SECONDS] [TARGET...]
# (default 60 s for each of problem_file_fuzz, siconos_dat_fuzz and dual_fuzz, one after
# another). Configures and builds the clang fuzz build in build-fuzz (FUZZ_BUILD overrides),
# seeds each target's corpus (below), and runs each target until SECONDS have passed or something
# is found. The corpora grow across runs in build-fuzz/corpus/<reader>; a finding is written to
# build-fuzz/artifacts/ and the script exits non-zero at once. See docs/fuzzing.md.
#
# Seeds: problem_file_fuzz takes examples/*.toml and tests/bad_input/*.toml (plus the same files
# with a --set override appended, see problem_file_fuzz.cpp); the others fuzz/seeds/<reader>/.
# FUZZ_FRESH_CORPUS=1 (make test-fuzz) starts each target from its seeds alone, in
# build-fuzz/fresh-corpus, emptied first: a short run then costs the same every time.
# UNITY=OFF compiles the library's files one by one rather than in CMake's unity batches.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
seconds=${1:-60}
shift || true
all_targets=(problem_file_fuzz siconos_dat_fuzz dual_fuzz)
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=("${all_targets[@]}")
build=${FUZZ_BUILD:-$root/build-fuzz}

for t in "${targets[@]}"; do
  case " ${all_targets[*]} " in
    *" $t "*) ;;
    *) echo "fuzz: unknown target $t (the targets: ${all_targets[*]})" >&2; exit 1 ;;
  esac
done
if ! command -v clang++ >/dev/null || ! command -v clang >/dev/null; then
  echo "fuzz: clang/clang++ not found (bash scripts/install-deps.sh installs clang and libFuzzer)" >&2
  exit 1
fi

cmake -S "$root/fuzz" -B "$build" -G Ninja -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_UNITY_BUILD="${UNITY:-ON}" >/dev/null
cmake --build "$build" --target "${targets[@]}"

artifacts=$build/artifacts
mkdir -p "$artifacts"
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}

corpora=$build/corpus
if [ -n "${FUZZ_FRESH_CORPUS:-}" ]; then
  corpora=$build/fresh-corpus
  rm -rf "$corpora"
fi
for target in "${targets[@]}"; do
  reader=${target%_fuzz}
  corpus=$corpora/$reader
  seeds=$build/seeds/$reader
  rm -rf "$seeds"
  mkdir -p "$corpus" "$seeds"
  if [ "$reader" = problem_file ]; then
    cp "$root"/examples/*.toml "$root"/tests/bad_input/*.toml "$seeds"/
    # Seeds for the --set path: a file, a NUL, then one override.
    i=0
    for o in 'mesh.cells=[24,8,8]' 'material.young=2e11' 'contact.friction.law=constant' \
      'traction[1].value=[0,0,-1e7]' 'dirichlet.1.boundary=x1' 'mesh.cells.0=24' \
      'output.dir="results/run 1"' 'contact.slip_bound=1e7' 'material.model=anisotropic'; do
      printf '%s\0%s' "$(cat "$root/examples/paper-brick.toml")" "$o" >"$seeds/set-$i"
      i=$((i + 1))
    done
  else
    cp "$root"/fuzz/seeds/"$reader"/* "$seeds"/
  fi
  echo "fuzz: $target for ${seconds} s (corpus $corpus)"
  "$build/$target" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
    -max_len=16384 -dict="$root/fuzz/$reader.dict" -artifact_prefix="$artifacts/" \
    -print_final_stats=1 "$corpus" "$seeds"
done
