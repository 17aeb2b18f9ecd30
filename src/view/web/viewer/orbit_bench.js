// #bench=orbit[&frames=N]: after the first frame the camera circles the scene once in N frames
// (default 240); the mean and 95th-percentile time between frames (requestAnimationFrame
// timestamps), in ms, go to data-bench-mean-ms and data-bench-p95-ms on <html> and to
// window.contactlabBench (scripts/bench-viewer-page.sh reads them).

// The benchmark's step for the animation loop, given each frame's timestamp after the first,
// or null when OPTIONS do not ask for it. It turns CAMERA about CONTROLS.target.
export function orbitBench(options, camera, controls) {
  if (options.bench !== 'orbit') return null;
  const n = Math.max(2, Number(options.frames) || 240), times = [];
  let last = null, done = false;
  return function (now) {
    if (done) return;
    if (last !== null) times.push(now - last);
    last = now;
    const offset = camera.position.clone().sub(controls.target);
    offset.applyAxisAngle(camera.up, 2 * Math.PI / n);
    camera.position.copy(controls.target).add(offset);
    camera.lookAt(controls.target);
    if (times.length === n) {
      const sorted = times.slice().sort(function (a, b) { return a - b; });
      const mean = sorted.reduce(function (a, b) { return a + b; }, 0) / sorted.length;
      const p95 = sorted[Math.min(sorted.length - 1, Math.floor(0.95 * sorted.length))];
      window.contactlabBench = {frames: sorted.length, mean_ms: mean, p95_ms: p95};
      document.documentElement.setAttribute('data-bench-mean-ms', mean.toFixed(2));
      document.documentElement.setAttribute('data-bench-p95-ms', p95.toFixed(2));
      done = true;
    }
  };
}
