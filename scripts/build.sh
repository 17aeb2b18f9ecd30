#!/usr/bin/env bash
# Configures and builds ContactLab into build/ (Release unless BUILD_TYPE says otherwise).
# Extra arguments go to cmake's configure step, e.g. -DCONTACTLAB_NATIVE=ON.
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${BUILD_DIR:-build}
generator=()
if command -v ninja >/dev/null 2>&1; then generator=(-G Ninja); fi
if [ ! -f "$build_dir/CMakeCache.txt" ]; then
  cmake -S . -B "$build_dir" "${generator[@]}" -DCMAKE_BUILD_TYPE="${BUILD_TYPE:-Release}" "$@"
elif [ $# -gt 0 ]; then
  cmake -S . -B "$build_dir" "$@"
fi
cmake --build "$build_dir" --parallel "${JOBS:-$(nproc)}"
