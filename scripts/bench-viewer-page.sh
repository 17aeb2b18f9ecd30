#!/usr/bin/env bash
# Size, load time and orbit frame times of a scene's viewer page in headless Chromium with
# software WebGL (SwiftShader, a CPU renderer: a real GPU is much faster), with meshes thinned
# for display (the default 50,000-triangle budget) and drawn whole (--max-triangles 0).
# Usage: scripts/bench-viewer-page.sh CONTACTLAB SCENE.yaml [WORKDIR] [RUNS]
# Prints, per page: its size, the time from navigation to the first frame drawn (data-ready-ms)
# and the mean and 95th-percentile time between frames while the camera circles the scene once
# in 240 frames (#bench=orbit, src/view/web/viewer/orbit_bench.js), each of RUNS loads (default 3) in a
# fresh browser, read in real time through the DevTools protocol (viewer-page-timing.mjs).
set -uo pipefail
cli=$1; scene=$2; work=${3:-/tmp/contactlab-bench-viewer}; runs=${4:-3}
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$work" && cd "$work" || exit 1
export HOME="$work/home"
mkdir -p "$HOME"
CHROMIUM=${CHROMIUM:-$(command -v chromium || command -v chromium-browser)} WORK=$work
source "$here/../tests/view/headless_chromium.sh"
chromium_alive

for budget in 50000 0; do
  page="$work/page-$budget.html"
  "$cli" view "$scene" --out "$page" --max-triangles "$budget" 2> view.log || { cat view.log; exit 1; }
  echo "--max-triangles $budget: $(stat -c %s "$page") bytes ($(tail -1 view.log))"
  for run in $(seq "$runs"); do
    port=$((20000 + RANDOM % 20000))
    rm -rf "$work/profile"
    CHROMIUM_SECONDS=150 chromium_run --remote-debugging-port=$port about:blank "run-$budget-$run.log" &
    browser=$!
    echo "  run $run: $(node --experimental-websocket "$here/viewer-page-timing.mjs" $port "file://$page#bench=orbit" 140 2>&1)"
    kill "$browser" 2>/dev/null; wait "$browser" 2>/dev/null
  done
done
