# Headless Chromium with software WebGL (SwiftShader), no GPU, no network, a fixed window:
# sourced by the browser tests (tests/view/browser_*.sh) and scripts/bench-viewer-page.sh.
# Set CHROMIUM (the program) and WORK (a folder for its profile) before calling; PROFILE, when
# set, is the profile folder instead (two browsers at once need two).
#
# chromium_run ARGS... LOG: runs Chromium on ARGS (options, then the address), its log to LOG,
# for at most CHROMIUM_SECONDS (default 40).
chromium_run() {
  local log=${*: -1}
  timeout "${CHROMIUM_SECONDS:-40}" "$CHROMIUM" --headless=new --no-sandbox --disable-gpu-sandbox --enable-unsafe-swiftshader \
    --use-angle=swiftshader --use-gl=angle --enable-webgl --ignore-gpu-blocklist \
    --no-first-run --no-default-browser-check --disable-extensions --disable-background-networking \
    --user-data-dir="${PROFILE:-$WORK/profile}" --enable-logging=stderr --v=0 --hide-scrollbars \
    --window-size=1000,700 "${@:1:$#-1}" 2>"$log"
}

# chromium_alive: exits 77 (ctest: skipped) when Chromium is absent or cannot start at all.
chromium_alive() {
  [ -n "$CHROMIUM" ] && [ -x "$CHROMIUM" ] || { echo "SKIPPED: no chromium found (install Debian's chromium: scripts/install-deps.sh)"; exit 77; }
  echo '<html><body><script>document.title="alive"</script></body></html>' > "$WORK/alive.html"
  chromium_run --dump-dom "file://$WORK/alive.html" "$WORK/alive.log" > "$WORK/alive.dom"
  grep -q "<title>alive</title>" "$WORK/alive.dom" || { cat "$WORK/alive.log"; echo "SKIPPED: headless Chromium does not start here"; exit 77; }
}
