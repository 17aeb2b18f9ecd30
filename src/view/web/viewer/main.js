// ContactLab viewer (src/view/web/viewer/main.js, the entry module): draws the data that
// `contactlab view` or a session's live view puts in the page (src/view/view_data.h) with
// three.js r111: the two bodies at their poses, the pointshell of the pointshell body coloured
// by level, a slice of the field body's signed distance field, contact surfaces, and for an
// experiment's run the per-cycle poses and forces with a time slider and a force plot, or for
// a live session the stream of its snapshots. When the first frame is drawn,
// <html data-ready="1"> is set.
//
// The modules (this folder) are ES modules, served as files by the live view and bundled into
// one inline module by `contactlab view` (src/view/module_bundle.h): they import with
// `import { a, b } from './name.js';` and export with `export function|const|class NAME`.
import { addBodies } from './bodies.js';
import { addSceneSurfaces } from './contact_surfaces.js';
import { addFieldSlice } from './field_slice.js';
import { addForceArrow } from './force_arrow.js';
import { ForcePlot } from './force_plot.js';
import { startLive } from './live.js';
import { orbitBench } from './orbit_bench.js';
import { loadPageData, readOptions } from './page_data.js';
import { addPanelToggles, fillPanel } from './panel.js';
import { addPointshell } from './pointshell.js';
import { startReplay } from './replay.js';
import { addOrbitControls, createView, frameBodies, layoutView } from './scene_setup.js';

const options = readOptions();
const data = loadPageData(options);

// The 3D view and what it draws, in the order the scene holds them.
const view = createView(document.getElementById('view'));
const bodies = addBodies(view.scene, data.bodies);
const shell = addPointshell(data, bodies);
const slice = data.slice ? addFieldSlice(data.slice, bodies) : null;
const surfaces = addSceneSurfaces(data.surfaces || [], view.scene);
const arrow = addForceArrow(view.scene);
const bounds = frameBodies(view, bodies);
const controls = addOrbitControls(view, bounds.center);

// The panel, then a replay's or a live session's bar and plot.
fillPanel(data, bodies, {contactPoints: shell.contactPoints, surfaces: surfaces});
addPanelToggles(bodies, {points: shell.points, contactPoints: shell.contactPoints, slice: slice, surfaces: surfaces});
const plot = new ForcePlot(document.getElementById('plot'));
const parts = {scene: view.scene, bodies: bodies, arrow: arrow, bounds: bounds, plot: plot, points: shell.points,
               pairs: data.pairs};
const replayer = data.replay ? startReplay(data.replay, parts, options) : null;
if (data.live) startLive(data.live, parts);

// The 3D view fills the window above the replay / live bar.
function layout() {
  layoutView(view, document.getElementById('replay'));
  plot.redraw();
}
layout();
window.addEventListener('resize', layout);

// The animation loop: the replay played on, the orbit benchmark's step, the orbit controls.
const bench = orbitBench(options, view.camera, controls);
let frames = 0;
function animate(now) {
  requestAnimationFrame(animate);
  if (bench && frames > 0) bench(now);
  if (replayer) replayer.tick(now);
  controls.update();
  view.renderer.render(view.scene, view.camera);
  if (++frames === 1) {
    document.documentElement.setAttribute('data-ready', '1');
    // Time from the start of navigation to the first frame drawn, ms.
    document.documentElement.setAttribute('data-ready-ms', performance.now().toFixed(0));
    window.contactlabReady = true;
  }
}
requestAnimationFrame(animate);
