#!/usr/bin/env bash
# Size, load time and orbit frame times of a scene's viewer page in headless Chromium with
# software WebGL (SwiftShader, a CPU renderer: a real GPU is much faster), with meshes thinned
# for display (the default 50,000-triangle budget) and drawn whole (--max-triangles 0).
# Usage: scripts/bench-viewer-page.sh CONTACTLAB SCENE.yaml [WORKDIR] [RUNS]
# Prints, per page: its size, the time from navigation to the first frame drawn (data-ready-ms)
# and the mean and 95th-percentile time between frames while the camera circles the scene once
# in 240 frames (#bench=orbit, src/view/web/viewer.js), each over RUNS loads (default 3).
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
    # Real time (no virtual-time budget): the DOM is dumped after --timeout ms.
    chromium_run --timeout=25000 --dump-dom "file://$page#bench=orbit" "run-$budget-$run.log" > "run-$budget-$run.dom"
    tag=$(grep -o '<html[^>]*>' "run-$budget-$run.dom" | head -1)
    attr() { echo "$tag" | sed -n "s/.* $1=\"\([0-9.]*\)\".*/\1/p"; }
    echo "  run $run: ready $(attr data-ready-ms) ms, orbit frame mean $(attr data-bench-mean-ms) ms, p95 $(attr data-bench-p95-ms) ms"
  done
done
