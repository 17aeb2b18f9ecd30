#!/usr/bin/env bash
# The live view in a real browser: runs `contactlab session --device sim:circle --view` on a
# small procedural scene (and on a scene of many bodies), loads its page from 127.0.0.1 in headless Chromium, and checks that the
# page drew its first frame, received snapshots and contact marks from the event stream
# (data-snapshots, data-marks, data-marks-contact on <html>), drew some points in contact, and
# logged no JavaScript error.
# Nothing waits by the clock: the session starts when the browsers have opened its stream.
# Usage: browser_live_test.sh CONTACTLAB WORKDIR CHROMIUM [PYTHON3]. Exit 77 (ctest: skipped)
# only when Chromium is absent or cannot start at all.
set -uo pipefail
cli=$1; work=$2; chromium=${3:-}; python=${4:-python3}
here=$(cd "$(dirname "$0")" && pwd)

rm -rf "$work" && mkdir -p "$work" || exit 1
cd "$work" || exit 1
export HOME="$work/home"
mkdir -p "$HOME"

CHROMIUM=$chromium WORK=$work
source "$here/headless_chromium.sh"
browse() { chromium_run --virtual-time-budget=3000 --dump-dom "$@"; }  # browse URL LOG: the DOM after the budget
chromium_alive

cat > scene.yaml <<'YAML'
name: view-live-test
bodies:
  - name: ball
    mesh: "sphere:0.02,3"
    pose: [0, 0, 0.0205, 1, 0, 0, 0]
    role: pointshell
    pointshell: {points: 1024, levels: 3, seed: 3}
    field: {resolution: 24}
  - name: plate
    mesh: "box:0.05,0.05,0.01,2"
    pose: [0, 0, -0.01, 1, 0, 0, 0]
    role: field
    field: {resolution: 32}
model: {k_C: 1000}
YAML
"$cli" contact scene.yaml --cache cache > /dev/null 2>&1 || { echo "FAILED: contactlab contact"; exit 1; }

# The session, in the background, waiting for its viewers (--view-wait): it starts once each
# browser below has opened the page's stream, however long Chromium takes to start (a loaded
# 2-core machine was seen taking 13 s), and streams for its duration from there. Its address is
# read from its output through a FIFO as it is printed. timeout(1) is only a hang guard, for a
# browser that never opens the stream: it stops the session cleanly before ctest's limit.
viewers=1
if "$python" -c 'import numpy, matplotlib.image' 2>/dev/null; then
  viewers=2  # the DOM's browser and the screenshot's
else
  echo "note: $python lacks numpy or matplotlib: no screenshot check"
fi
# live NAME SESSION-ARGS...: runs the session with the view and its browsers; NAME.dom the
# page's DOM, NAME.png its screenshot (shot=1 when taken), NAME.out the session's output,
# session_status its exit status.
live() {
  local name=$1; shift
  rm -f "$name.fifo" "$name.out" && mkfifo "$name.fifo" || exit 1
  timeout 100 "$cli" session "$@" --no-realtime --quiet --view --view-wait "$viewers" > "$name.fifo" 2>&1 &
  local session=$!
  exec 3< "$name.fifo"
  local url="" line
  while IFS= read -r line <&3; do
    printf '%s\n' "$line" >> "$name.out"
    case $line in "view: http://127.0.0.1:"*/) url=${line#view: }; break ;; esac
  done
  cat <&3 >> "$name.out" &  # the rest of its output
  local drain=$!
  exec 3<&-
  if [ -z "$url" ]; then wait "$session"; wait "$drain"; cat "$name.out"; echo "FAILED: the session printed no view address"; exit 1; fi
  # The DOM and, from a second browser at the same time, a screenshot. Pending stream data
  # holds virtual time, so both finish when the session ends its stream.
  shot="" ; local shooter=""
  if [ "$viewers" -eq 2 ]; then
    PROFILE="$work/profile-shot" chromium_run --virtual-time-budget=3000 "--screenshot=$work/$name.png" "$url" \
      "$name.shot.log" > /dev/null &
    shooter=$!
  fi
  browse "$url" "$name.log" > "$name.dom"
  [ -z "$shooter" ] || { wait "$shooter" && shot=1; }
  wait "$session"; session_status=$?
  wait "$drain"
  [ -n "$shot" ] || [ -z "$shooter" ] || { echo "FAILED: no screenshot of the $name page"; status=1; }
  [ "$session_status" -ne 124 ] || { cat "$name.out"; echo "FAILED: the session still waited for its $viewers viewer(s) or ran after 100 s"; status=1; }
  [ "$session_status" -eq 0 ] || [ "$session_status" -eq 124 ] || { cat "$name.out"; echo "FAILED: the session exited with $session_status"; status=1; }
}

# check_drawn NAME: the page of NAME.dom drew its first frame, logged no JavaScript error and
# received snapshots from the stream; sets tag to its <html> tag.
check_drawn() {
  tag=$(grep -o '<html[^>]*>' "$1.dom" | head -1)
  echo "$1 page: $tag"
  echo "$tag" | grep -q 'data-ready="1"' || { echo "FAILED: the $1 page never drew its first frame"; status=1; }
  echo "$tag" | grep -q 'data-errors="0"' || { grep -o '<pre id="errors"[^<]*' "$1.dom"; echo "FAILED: JavaScript errors"; status=1; }
  local snapshots
  snapshots=$(echo "$tag" | sed -n 's/.*data-snapshots="\([0-9]*\)".*/\1/p')
  if [ -z "$snapshots" ] || [ "$snapshots" -lt 10 ]; then
    echo "FAILED: the $1 page received ${snapshots:-no} snapshots from the stream"; status=1
  fi
}

status=0
live live scene.yaml --cache cache --device sim:circle:0.004:1 --touch 0.003 --duration 8
check_drawn live
# Contact marks of the drawn points: received, and some points drawn red (in contact).
marks=$(echo "$tag" | sed -n 's/.*data-marks="\([0-9]*\)".*/\1/p')
red=$(echo "$tag" | sed -n 's/.*data-marks-contact="\([0-9]*\)".*/\1/p')
echo "marks received: ${marks:-none}, points drawn in contact in the last: ${red:-none}"
if [ -z "$marks" ] || [ "$marks" -lt 2 ]; then echo "FAILED: the page received ${marks:-no} contact marks"; status=1; fi
if [ -z "$red" ] || [ "$red" -lt 1 ]; then echo "FAILED: no point drawn in contact"; status=1; fi
if [ -n "$shot" ]; then
  "$python" "$here/check_page.py" --page live --dom live.dom --png live.png --logs live.log live.shot.log --min-red 20 || status=1
fi
if grep -q "CONSOLE.*Uncaught" live.log; then grep "CONSOLE.*Uncaught" live.log; echo "FAILED: uncaught errors"; status=1; fi

# A scene of many bodies: the ball among a plate, a wall and a post; the page draws every body
# (the tool orange, the others blue), follows the tool and lists its pairs.
cat > many.yaml <<'YAML'
name: view-live-many
tool: ball
bodies:
  - {name: ball, mesh: "sphere:0.02,3", pose: [0, 0, 0.0195, 1, 0, 0, 0], role: pointshell,
     pointshell: {points: 512, levels: 3, seed: 3}, field: {resolution: 24}}
  - {name: plate, mesh: "box:0.05,0.05,0.01,2", pose: [0, 0, -0.01, 1, 0, 0, 0], role: field, field: {resolution: 24}}
  - {name: wall, mesh: "box:0.01,0.05,0.03,2", pose: [0.04, 0, 0.03, 1, 0, 0, 0], role: field, field: {resolution: 24}}
  - {name: post, mesh: "box:0.01,0.01,0.03,2", pose: [-0.035, 0.035, 0.03, 1, 0, 0, 0], role: field, field: {resolution: 24}}
model: {k_C: 1000}
YAML
live many many.yaml --cache cache --device sim:circle:0.004:1 --duration 4
check_drawn many
grep -q "4 bodies, tool ball, 3 pairs" many.out || { cat many.out; echo "FAILED: the session did not say its bodies and pairs"; status=1; }
grep -q "3 pairs: ball / plate (pointshell)" many.dom || { echo "FAILED: the live page does not list the pairs"; status=1; }
# Every pair's contacts: frames received, and the ball's contacts with the plate drawn.
tag=$(grep -o '<html[^>]*>' many.dom | head -1)
frames=$(echo "$tag" | sed -n 's/.*data-pair-contacts="\([0-9]*\)".*/\1/p')
drawn=$(echo "$tag" | sed -n 's/.*data-pair-contacts-count="\([0-9]*\)".*/\1/p')
echo "pair contact frames received: ${frames:-none}, contacts drawn in the last: ${drawn:-none}"
if [ -z "$frames" ] || [ "$frames" -lt 2 ]; then echo "FAILED: the page received ${frames:-no} pair contact frames"; status=1; fi
if [ -z "$drawn" ] || [ "$drawn" -lt 1 ]; then echo "FAILED: no pair contact drawn"; status=1; fi
grep -q "ball / plate: [0-9]" many.dom || { echo "FAILED: the legend does not count the ball's contacts with the plate"; status=1; }
if [ -n "$shot" ]; then
  "$python" "$here/check_page.py" --page many --dom many.dom --png many.png --logs many.log many.shot.log || status=1
fi
exit $status
