#!/usr/bin/env bash
# Builds the libFuzzer targets (tests/fuzz, clang with ASan + UBSan) into build-fuzz/ and runs
# each for SECONDS (default 60), starting from its seed corpus; new inputs found are kept in
# build-fuzz/fuzz-corpus/TARGET (the repository's corpus is never written), crash reproducers
# in build-fuzz/fuzz-artifacts/. Prints the iterations per target; exits non-zero on a finding.
#   scripts/fuzz.sh [SECONDS] [TARGET...]      e.g. scripts/fuzz.sh 120 fuzz_ply_reader
#   scripts/fuzz.sh --build-only [TARGET...]
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${BUILD_DIR:-build-fuzz}
build_only=0
if [ "${1:-}" = --build-only ]; then build_only=1; shift; fi
seconds=${1:-60}
[ $# -gt 0 ] && shift

if [ ! -f "$build_dir/CMakeCache.txt" ]; then
  generator=()
  if command -v ninja >/dev/null 2>&1; then generator=(-G Ninja); fi
  # Only what the targets link is built: no tests, benchmarks or CGAL.
  CC=clang CXX=clang++ cmake -S . -B "$build_dir" "${generator[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -gline-tables-only" -DCONTACTLAB_FUZZ=ON \
    -DCONTACTLAB_BUILD_TESTS=OFF -DCONTACTLAB_BUILD_BENCHMARKS=OFF -DCONTACTLAB_WITH_CGAL=OFF >/dev/null
fi
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  cmake --build "$build_dir" --parallel "${JOBS:-$(nproc)}" --target fuzz_targets
  targets=($(cd tests/fuzz/corpus && ls))
else
  cmake --build "$build_dir" --parallel "${JOBS:-$(nproc)}" --target "${targets[@]}"
fi
[ $build_only -eq 1 ] && exit 0
mkdir -p "$build_dir/fuzz-artifacts"
status=0
printf '%-22s %12s %8s  %s\n' target iterations corpus result
for t in "${targets[@]}"; do
  work="$build_dir/fuzz-corpus/$t"
  log="$build_dir/fuzz-artifacts/$t.log"
  mkdir -p "$work"
  result=ok
  if ! "$build_dir/bin/$t" -max_total_time="$seconds" -max_len=65536 -rss_limit_mb=2048 -timeout=30 \
       -print_final_stats=1 -artifact_prefix="$build_dir/fuzz-artifacts/$t-" \
       "$work" "tests/fuzz/corpus/$t" >"$log" 2>&1; then
    result="FINDING (see $log)"
    status=1
  fi
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  printf '%-22s %12s %8s  %s\n' "$t" "${runs:-?}" "$(ls "$work" | wc -l)" "$result"
done
exit $status
