// The live view of a haptic session: snapshots from the server's event stream
// (live_view_server.h) move the haptic body; the device (manipulandum) pose is a grey
// wireframe ghost; a model's proxy of the haptic body a cyan one; the plot shows the last 10 s.
import { THREE } from './three_global.js';
import { followContactMarks } from './contact_marks.js';
import { followPairContacts } from './pair_contacts.js';
import { aimArrow } from './force_arrow.js';
import { fmt, setPose } from './util.js';

// A wireframe of HAPTIC's mesh in COLOUR at OPACITY, drawn at RENDERORDER.
function wireframe(haptic, colour, opacity, renderOrder) {
  const mesh = new THREE.Mesh(haptic.mesh.geometry, new THREE.MeshBasicMaterial(
      {color: colour, wireframe: true, transparent: true, opacity: opacity, depthWrite: false}));
  mesh.renderOrder = renderOrder;
  return mesh;
}

// The replay bar as the live view uses it: the readout and the plot only.
function showLiveBar(live) {
  document.getElementById('replay').hidden = false;
  ['play', 'slider', 'model-choice'].forEach(function (id) { document.getElementById(id).hidden = true; });
  document.getElementById('speed').parentNode.hidden = true;
  document.getElementById('subtitle').textContent = 'live: model ' + live.model + ', device ' + live.device;
}

// The readout of snapshot S, FM its |F|.
function readout(s, fm) {
  return 't = ' + s.t.toFixed(3) + ' s   |F| = ' + fmt(fm) + ' N   |T| = ' +
         fmt(Math.hypot(s.torque[0], s.torque[1], s.torque[2])) + ' N m' +
         (s.level >= 0 ? '   level ' + s.level : '') + '   contacts ' + s.contacts + '   cycle ' +
         s.work_us.toFixed(0) + ' us';
}

// Follows the session of LIVE (the page data's "live") in VIEW ({scene, bodies, arrow,
// bounds, plot, points, pairs: a scene of many bodies' pairs}); sets data-snapshots on <html> to the snapshots received.
export function startLive(live, view) {
  showLiveBar(live);
  const haptic = view.bodies[live.haptic], arrow = view.arrow;
  const ghost = wireframe(haptic, 0xbbbbbb, 0.3, 4);
  setPose(ghost, haptic.spec.pose);
  view.scene.add(ghost);
  // A model's proxy of the haptic body (pointshell-ccd: where it is held outside the other
  // body), shown while the snapshots carry one.
  const proxy = wireframe(haptic, 0x17becf, 0.5, 5);
  proxy.visible = false;
  view.scene.add(proxy);
  const history = [];  // [t, |F|] of the last 10 s
  let liveMax = 0, received = 0;
  const stream = new EventSource(live.stream);
  stream.onmessage = function (e) {
    const s = JSON.parse(e.data);
    ++received;
    setPose(haptic.group, s.body);
    setPose(ghost, s.device);
    proxy.visible = !!s.proxy;
    if (s.proxy) setPose(proxy, s.proxy);
    const f = new THREE.Vector3(s.force[0], s.force[1], s.force[2]);
    const fm = f.length();
    liveMax = Math.max(liveMax, fm);
    arrow.visible = fm > 0;
    if (arrow.visible) aimArrow(arrow, s.body, f, fm, 0.6 * view.bounds.radius * fm / liveMax);
    document.getElementById('readout').textContent = readout(s, fm);
    document.documentElement.setAttribute('data-snapshots', String(received));
    history.push([s.t, fm]);
    while (history.length > 1 && history[0][0] < s.t - 10) history.shift();
    const t = new Float32Array(history.length), fmag = new Float32Array(history.length);
    let fmax = 0;
    for (let i = 0; i < history.length; ++i) { t[i] = history[i][0]; fmag[i] = history[i][1]; fmax = Math.max(fmax, fmag[i]); }
    view.plot.draw([{name: live.model, t: t, fmag: fmag, fmax: fmax}], 0, history.length - 1);
  };
  if (view.pairs) followPairContacts(stream, view.scene, view.pairs);
  else if (view.points) followContactMarks(stream, view.points);
  stream.onerror = function () {
    // The session ended (or the server went away): keep the last pose.
    stream.close();
    document.getElementById('readout').textContent += '   (stream ended)';
  };
}
