#!/usr/bin/env bash
# The viewer pages in a real browser: makes a scene page and a replay page with the built
# program on a small procedural scene, loads each in headless Chromium (software WebGL), and
# checks with check_page.py that the page drew its first frame (data-ready on <html>), logged no
# JavaScript error (data-errors on <html>, Chromium's console log), and that the screenshot is
# not blank and shows both bodies in their colours. A sweep's results give one page of every job:
# opened at #job=1 it shows that job, and choosing another job in its selector shows that one.
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
# A sweep of two jobs, viewed without --job: one page, a job selector.
cat > jobs.yaml <<'YAML'
name: view-test-jobs
scene: scene.yaml
models: [pointshell]
moving_body: ball
trajectory: {type: twist, direction: [0, 0, -1], depth: 0.002, angle: 0.4, duration: 0.1}
reference: ''
sweep: {k_C: [500, 1500], "scene.bodies[name=plate].field.resolution": [32]}
YAML
"$cli" run jobs.yaml --out results/view-test-jobs --cache cache > jobs-run.log 2>&1 || { cat jobs-run.log; echo "FAILED: contactlab run (sweep)"; exit 1; }
"$cli" view results/view-test-jobs --out jobs.html --cache cache || { echo "FAILED: contactlab view results of two jobs"; exit 1; }

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

# The page of two jobs at #job=1: job 1 drawn (its title, data-job), both jobs in the selector.
browse --dump-dom "file://$work/jobs.html#job=1&t=0.05" jobs.dom.log > jobs.dom
browse "--screenshot=$work/jobs.png" "file://$work/jobs.html#job=1&t=0.05" jobs.shot.log > /dev/null
"$python" "$here/check_page.py" --page jobs --dom jobs.dom --png jobs.png --logs jobs.dom.log jobs.shot.log --replay \
    --expect-text "<h1 id=\"title\">view-test-jobs — k_C=1500 scene.bodies[name=plate].field.resolution=32</h1>" --expect-attr data-job=1 --expect-attr data-jobs=2 || status=1
# An option names a key path by its last key.
grep -q '<option value="0">job 0: k_C=500 resolution=32</option><option value="1">job 1: k_C=1500 resolution=32</option>' jobs.dom ||
  { echo "FAILED: the job selector does not list both jobs"; status=1; }
# The chosen job's whole label is written out under the selector.
grep -q '<span id="job-label" class="small">k_C=1500 scene.bodies\[name=plate\].field.resolution=32</span>' jobs.dom ||
  { echo "FAILED: the chosen job's label is not shown under the selector"; status=1; }
# Every force trace of the replay is named in the plot's legend, in the model selector's order.
grep -q 'id="plot"[^>]*data-legend="pointshell,pointshell-linear"' replay.dom ||
  { echo "FAILED: the force plot's legend does not name both models' traces"; status=1; }
# Choosing job 1 in the selector of a page opened on job 0 (a script added to the page does what a
# user would) shows job 1. The script is a module so that it runs after the viewer's module has
# filled the selector (module scripts run in order, once the page is parsed).
sed 's|</body>|<script type="module">if (document.documentElement.getAttribute("data-job") === "0" \&\& !sessionStorage.getItem("switched")) { sessionStorage.setItem("switched", "1"); var s = document.getElementById("job"); s.value = "1"; s.dispatchEvent(new Event("change")); }</script></body>|' \
  jobs.html > switch.html
browse --dump-dom "file://$work/switch.html" switch.dom.log > switch.dom
"$python" "$here/check_page.py" --page switch --dom switch.dom --png jobs.png --logs switch.dom.log --replay \
    --expect-text "<h1 id=\"title\">view-test-jobs — k_C=1500 scene.bodies[name=plate].field.resolution=32</h1>" --expect-attr data-job=1 || status=1

# The pressure field's contact surface: a rigid ball pressed 4 mm into the plate, drawn with and
# without it. Every corner and pixel count of the surface's data is checked by view_data_test; here,
# that the page draws it: the legend names it and the screenshots differ where it is.
sed -e 's|pose: \[0, 0, 0.0205,|pose: [0, 0, 0.016,|' -e '/deformable:/,/anchor: none}/d' scene.yaml > pressed.yaml
"$cli" view pressed.yaml --out pressed.html --cache cache || { echo "FAILED: contactlab view pressed.yaml"; exit 1; }
"$cli" view pressed.yaml --model pressure-field --out surface.html --cache cache ||
  { echo "FAILED: contactlab view pressed.yaml --model pressure-field"; exit 1; }
for page in pressed surface; do
  browse --dump-dom "file://$work/$page.html" "$page.dom.log" > "$page.dom"
  browse "--screenshot=$work/$page.png" "file://$work/$page.html" "$page.shot.log" > /dev/null
done
"$python" "$here/check_page.py" --page pressed --dom pressed.dom --png pressed.png --logs pressed.dom.log pressed.shot.log || status=1
"$python" "$here/check_page.py" --page surface --dom surface.dom --png surface.png --logs surface.dom.log surface.shot.log \
    --expect-text "contact surface of pressure-field" --differs-from pressed.png --min-differing 500 || status=1

# A scene of many bodies: every body drawn, the tool in orange and the others in blues; the
# legend names the tool and lists the pairs in their models' order.
cat > many.yaml <<'YAML'
name: view-many
tool: ball
bodies:
  - {name: ball, mesh: "sphere:0.02,3", pose: [0, 0, 0.0205, 1, 0, 0, 0], role: pointshell,
     pointshell: {points: 512, levels: 3, seed: 3}, field: {resolution: 24}}
  - {name: plate, mesh: "box:0.05,0.05,0.01,2", pose: [0, 0, -0.01, 1, 0, 0, 0], role: field, field: {resolution: 24}}
  - {name: wall, mesh: "box:0.01,0.05,0.03,2", pose: [0.035, 0, 0.03, 1, 0, 0, 0], role: field, field: {resolution: 24}}
  - {name: post, mesh: "box:0.01,0.01,0.03,2", pose: [-0.03, 0.03, 0.03, 1, 0, 0, 0], field: {resolution: 24}}
model: {k_C: 1000}
YAML
"$cli" view many.yaml --out many.html --cache cache || { echo "FAILED: contactlab view many.yaml"; exit 1; }
browse --dump-dom "file://$work/many.html" many.dom.log > many.dom
browse "--screenshot=$work/many.png" "file://$work/many.html" many.shot.log > /dev/null
"$python" "$here/check_page.py" --page many --dom many.dom --png many.png --logs many.dom.log many.shot.log \
    --expect-text "3 pairs: ball / plate (pointshell), ball / wall (pointshell), ball / post (pointshell)" || status=1
grep -q "ball (tool, pointshell" many.dom || { echo "FAILED: the legend does not name the tool"; status=1; }
# Its run (study: many-bodies) replayed: the tool moves, the others stay.
cat > many-run.yaml <<'YAML'
name: view-many-run
study: many-bodies
scene: many.yaml
models: [pointshell]
trajectory: {type: slide, direction: [0, 0, -1], depth: 0.001, tangent: [-1, 0, 0], length: 0.01, duration: 0.2}
YAML
"$cli" run many-run.yaml --out results/view-many-run --cache cache > many-run.log 2>&1 || { cat many-run.log; echo "FAILED: contactlab run (many bodies)"; exit 1; }
"$cli" view results/view-many-run --out many-replay.html --cache cache || { echo "FAILED: contactlab view of a many-bodies run"; exit 1; }
browse --dump-dom "file://$work/many-replay.html#t=0.1" many-replay.dom.log > many-replay.dom
browse "--screenshot=$work/many-replay.png" "file://$work/many-replay.html#t=0.1" many-replay.shot.log > /dev/null
"$python" "$here/check_page.py" --page many-replay --dom many-replay.dom --png many-replay.png \
    --logs many-replay.dom.log many-replay.shot.log --replay --expect-text "3 pairs: ball / plate (pointshell)" || status=1

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
