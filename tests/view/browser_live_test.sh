#!/usr/bin/env bash
# The live view in a real browser: runs `contactlab session --device sim:circle --view` on a
# small procedural scene, loads its page from 127.0.0.1 in headless Chromium, and checks that the
# page drew its first frame, received snapshots from the event stream (data-snapshots on <html>)
# and logged no JavaScript error.
# Usage: browser_live_test.sh CONTACTLAB WORKDIR CHROMIUM. Exit 77 (ctest: skipped) only when
# Chromium is absent or cannot start at all.
set -uo pipefail
cli=$1; work=$2; chromium=${3:-}

skip() { echo "SKIPPED: $*"; exit 77; }
[ -n "$chromium" ] && [ -x "$chromium" ] || skip "no chromium found (install Debian's chromium: scripts/install-deps.sh)"

rm -rf "$work" && mkdir -p "$work" || exit 1
cd "$work" || exit 1
export HOME="$work/home"
mkdir -p "$HOME"

browse() {  # browse URL LOG: the DOM after the virtual-time budget
  timeout 40 "$chromium" --headless=new --no-sandbox --disable-gpu-sandbox --enable-unsafe-swiftshader \
    --use-angle=swiftshader --use-gl=angle --enable-webgl --ignore-gpu-blocklist \
    --no-first-run --no-default-browser-check --disable-extensions --disable-background-networking \
    --user-data-dir="$work/profile" --enable-logging=stderr --v=0 \
    --window-size=1000,700 --virtual-time-budget=3000 --dump-dom "$1" 2>"$2"
}

echo '<html><body><script>document.title="alive"</script></body></html>' > alive.html
browse "file://$work/alive.html" alive.log > alive.dom
grep -q "<title>alive</title>" alive.dom || { cat alive.log; skip "headless Chromium does not start here"; }

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

# The session, in the background; its address is printed on stdout.
"$cli" session scene.yaml --cache cache --device sim:circle:0.004:1 --touch 0.001 --duration 8 --no-realtime \
  --quiet --view > session.out 2>&1 &
session=$!
url=""
for _ in $(seq 100); do
  url=$(sed -n 's/^view: \(http:\/\/127\.0\.0\.1:[0-9]*\/\)$/\1/p' session.out)
  [ -n "$url" ] && break
  sleep 0.1
done
if [ -z "$url" ]; then cat session.out; kill "$session" 2>/dev/null; echo "FAILED: the session printed no view address"; exit 1; fi

browse "$url" live.log > live.dom
wait "$session"; session_status=$?
tag=$(grep -o '<html[^>]*>' live.dom | head -1)
echo "live page: $tag"
status=0
[ "$session_status" -eq 0 ] || { cat session.out; echo "FAILED: the session exited with $session_status"; status=1; }
echo "$tag" | grep -q 'data-ready="1"' || { echo "FAILED: the live page never drew its first frame"; status=1; }
echo "$tag" | grep -q 'data-errors="0"' || { grep -o '<pre id="errors"[^<]*' live.dom; echo "FAILED: JavaScript errors"; status=1; }
snapshots=$(echo "$tag" | sed -n 's/.*data-snapshots="\([0-9]*\)".*/\1/p')
if [ -z "$snapshots" ] || [ "$snapshots" -lt 10 ]; then
  echo "FAILED: the page received ${snapshots:-no} snapshots from the stream"; status=1
fi
if grep -q "CONSOLE.*Uncaught" live.log; then grep "CONSOLE.*Uncaught" live.log; echo "FAILED: uncaught errors"; status=1; fi
exit $status
