#!/usr/bin/env bash
# The viewer pages in a real browser: makes a scene page and a replay page with the built
# program on a small procedural scene, loads each in headless Chromium (software WebGL), and
# checks with check_page.py that the page drew its first frame (data-ready on <html>), logged no
# JavaScript error (data-errors on <html>, Chromium's console log), and that the screenshot is
# not blank and shows both bodies in their colours.
# Usage: browser_test.sh CONTACTLAB WORKDIR CHROMIUM PYTHON3. Exit 77 (ctest: skipped) only when
# Chromium or Python with numpy and matplotlib is absent or Chromium cannot start at all.
set -uo pipefail
cli=$1; work=$2; chromium=${3:-}; python=${4:-python3}
here=$(cd "$(dirname "$0")" && pwd)

skip() { echo "SKIPPED: $*"; exit 77; }
[ -n "$chromium" ] && [ -x "$chromium" ] || skip "no chromium found (install Debian's chromium: scripts/install-deps.sh)"
"$python" -c 'import numpy, matplotlib.image' 2>/dev/null || skip "$python lacks numpy or matplotlib"

rm -rf "$work" && mkdir -p "$work" || exit 1
cd "$work" || exit 1
export HOME="$work/home"   # Chromium's profile and crash folders stay in the work folder
mkdir -p "$HOME"

CHROMIUM=$chromium WORK=$work
source "$here/headless_chromium.sh"
browse() { chromium_run --virtual-time-budget=8000 "$@"; }  # browse OUT_OPTION URL LOG
chromium_alive  # Chromium must start: a trivial page

# A small procedural scene: a soft ball (pointshell, reduced StVK) resting on a plate (field),
# and a run of it, whose replay deforms the ball's mesh in the page.
cat > scene.yaml <<'YAML'
name: view-test
bodies:
  - name: ball
    mesh: "sphere:0.02,3"
    pose: [0, 0, 0.0205, 1, 0, 0, 0]
    role: pointshell
    pointshell: {points: 1024, levels: 3, seed: 3}
    field: {resolution: 24}
    deformable: {model: stvk, modes: 6, cells: 8, E: 2.0e5, nu: 0.4, rho: 1000,
                 damping: {alpha: 10.0, beta: 0.001}, anchor: none}
  - name: plate
    mesh: "box:0.05,0.05,0.01,2"
    pose: [0, 0, -0.01, 1, 0, 0, 0]
    role: field
    field: {resolution: 32}
model: {k_C: 1000}
YAML
cat > exp.yaml <<'YAML'
name: view-test-run
scene: scene.yaml
models: [pointshell, pointshell-linear]
moving_body: ball
trajectory: {type: twist, direction: [0, 0, -1], depth: 0.002, angle: 0.4, duration: 0.2}
reference: ''
YAML
"$cli" view scene.yaml --out scene.html --cache cache || { echo "FAILED: contactlab view scene.yaml"; exit 1; }
"$cli" run exp.yaml --out results/view-test-run --cache cache > run.log 2>&1 || { cat run.log; echo "FAILED: contactlab run"; exit 1; }
"$cli" view results/view-test-run --out replay.html --cache cache || { echo "FAILED: contactlab view results"; exit 1; }

status=0
for page in scene replay; do
  start=$(date +%s)
  browse --dump-dom "file://$work/$page.html#t=0.1" "$page.dom.log" > "$page.dom"
  browse "--screenshot=$work/$page.png" "file://$work/$page.html#t=0.1" "$page.shot.log" > /dev/null
  echo "$page: browser $(( $(date +%s) - start )) s"
  extra=()
  [ "$page" = replay ] && extra=(--replay --expect-text "mesh deformed per frame")
  "$python" "$here/check_page.py" --page "$page" --dom "$page.dom" --png "$page.png" \
      --logs "$page.dom.log" "$page.shot.log" "${extra[@]}" || status=1
done

# The checks must see a broken page: the scene page with a script error added must fail them.
sed 's|</body>|<script>undefinedViewerFunction();</script></body>|' scene.html > broken.html
browse --dump-dom "file://$work/broken.html" broken.dom.log > broken.dom
if "$python" "$here/check_page.py" --page broken --dom broken.dom --png scene.png --logs broken.dom.log > broken.out; then
  cat broken.out; echo "FAILED: a page with a script error passed the checks"; status=1
elif ! grep -q "undefinedViewerFunction" broken.out; then
  cat broken.out; echo "FAILED: the script error of the broken page was not reported"; status=1
else
  echo "broken page: its script error was reported, as it should be"
fi
exit $status
