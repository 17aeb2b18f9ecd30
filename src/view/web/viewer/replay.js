// The replay of an experiment's run: per-cycle poses, forces and (deformable bodies) reduced
// coordinates of each model, shown frame by frame with a time slider, play / pause, speed, a
// model selector and the force plot.
import { THREE } from './three_global.js';
import { deform } from './bodies.js';
import { showTrackSurface, surfaceMesh } from './contact_surfaces.js';
import { addToggle } from './panel.js';
import { aimArrow } from './force_arrow.js';
import { decode, el, fmt, setPose } from './util.js';

// |F| of frame I of the forces F (3 per frame).
function magnitude(f, i) { return Math.hypot(f[3 * i], f[3 * i + 1], f[3 * i + 2]); }

// The track of model M (an entry of the page data's replay.models), its arrays decoded.
function decodeTrack(m) {
  const t = decode(m.t, Float32Array), force = decode(m.force, Float32Array);
  const fmag = new Float32Array(t.length);
  let fmax = 0;
  for (let i = 0; i < t.length; ++i) { fmag[i] = magnitude(force, i); fmax = Math.max(fmax, fmag[i]); }
  return {name: m.name, cycles: m.cycles, t: t, pose: decode(m.pose, Float32Array), force: force,
          torque: decode(m.torque, Float32Array), level: decode(m.level, Int32Array),
          contacts: decode(m.contacts, Int32Array), fmag: fmag, fmax: fmax,
          r: m.r || 0, q: m.r ? decode(m.q, Float32Array) : null,
          r_B: m.r_B || 0, q_B: m.r_B ? decode(m.q_B, Float32Array) : null,
          bodiesQ: (m.bodies_q || []).map(function (c) { return {body: c.body, r: c.r, q: decode(c.q, Float32Array)}; }),
          surface: m.surface ? {frames: decode(m.surface.frames, Int32Array), start: decode(m.surface.start, Uint32Array),
                                corners: decode(m.surface.corners, Float32Array),
                                pressure: decode(m.surface.pressure, Float32Array), pmax: m.surface.pmax} : null};
}

class Replayer {
  // REPLAY: the page data's "replay"; VIEW: {scene, bodies, arrow, bounds, plot}.
  constructor(replay, view) {
    this.replay = replay;
    this.view = view;
    this.tracks = replay.models.map(decodeTrack);
    this.current = 0;     // track index
    this.frameIndex = 0;  // frame of the current track
    this.playing = false;
    this.playTime = 0;
    this.lastWall = null;
    this.surface = null;  // the current track's contact surface, when a track has one
    if (this.tracks.some(function (tr) { return tr.surface; })) {
      this.surface = surfaceMesh(view.scene);
      addToggle('contact surface', [this.surface], true);
    }
  }

  // The model selector, slider, play button and plot clicks.
  wireControls() {
    const self = this, tracks = this.tracks;
    const select = document.getElementById('model');
    tracks.forEach(function (tr, i) { select.appendChild(el('option', {value: String(i)}, tr.name)); });
    if (tracks.length < 2) document.getElementById('model-choice').hidden = true;
    select.addEventListener('change', function () {
      const t = tracks[self.current].t[self.frameIndex];
      self.current = Number(select.value);
      self.showTime(t);
    });
    const slider = document.getElementById('slider');
    slider.addEventListener('input', function () {
      self.playing = false;
      self.updatePlayButton();
      self.showFrame(Number(slider.value));
    });
    document.getElementById('play').addEventListener('click', function () {
      const tr = tracks[self.current];
      if (!self.playing && self.frameIndex >= tr.t.length - 1) self.showFrame(0);
      self.playing = !self.playing;
      self.playTime = tr.t[self.frameIndex];
      self.lastWall = null;
      self.updatePlayButton();
    });
    const plot = this.view.plot;
    plot.canvas.addEventListener('click', function (e) {
      const tr = tracks[self.current];
      self.showTime(tr.t[0] + plot.fractionAt(e.clientX) * (tr.t[tr.t.length - 1] - tr.t[0]));
    });
  }

  // The first frame shown, from the address's OPTIONS: #model=NAME, #t=SECONDS, #play.
  start(options) {
    const self = this;
    if (options.model !== undefined) {
      this.tracks.forEach(function (tr, i) { if (tr.name === options.model) self.current = i; });
      document.getElementById('model').value = String(this.current);
    }
    if (options.t !== undefined) this.showTime(Number(options.t)); else this.showFrame(0);
    if (options.play !== undefined) {
      this.playing = true;
      this.playTime = this.tracks[this.current].t[this.frameIndex];
      this.updatePlayButton();
    }
  }

  updatePlayButton() { document.getElementById('play').textContent = this.playing ? 'Pause' : 'Play'; }

  // Shows the frame of the current track at or just before time T.
  showTime(t) {
    const tt = this.tracks[this.current].t;
    let lo = 0, hi = tt.length - 1;
    while (lo < hi) { const mid = (lo + hi + 1) >> 1; if (tt[mid] <= t) lo = mid; else hi = mid - 1; }
    this.showFrame(lo);
  }

  // Shows frame I of the current track: poses, deformation, force arrow, surface, readout, plot.
  showFrame(i) {
    const tr = this.tracks[this.current], bodies = this.view.bodies, arrow = this.view.arrow;
    const frameIndex = this.frameIndex = Math.max(0, Math.min(tr.t.length - 1, i));
    const slider = document.getElementById('slider');
    slider.max = String(tr.t.length - 1);
    slider.value = String(frameIndex);
    const p = tr.pose.subarray(7 * frameIndex, 7 * frameIndex + 7);
    setPose(bodies[this.replay.moving].group, p);
    if (bodies[0].basis && tr.q && tr.r === bodies[0].modes) deform(bodies[0], tr.q, tr.r * frameIndex);
    if (bodies[1].basis && tr.q_B && tr.r_B === bodies[1].modes) deform(bodies[1], tr.q_B, tr.r_B * frameIndex);
    // A scene of many bodies: each deformable body whose coordinates were recorded.
    tr.bodiesQ.forEach(function (c) {
      const b = bodies[c.body];
      if (b && b.basis && c.r === b.modes) deform(b, c.q, c.r * frameIndex);
    });
    // The force on the moving body at its origin, scaled so the largest force of the run is
    // 60% of the scene's radius.
    const f = new THREE.Vector3(tr.force[3 * frameIndex], tr.force[3 * frameIndex + 1], tr.force[3 * frameIndex + 2]);
    const fm = f.length();
    arrow.visible = fm > 1e-9 * Math.max(tr.fmax, 1e-12) && fm > 0;
    if (arrow.visible) aimArrow(arrow, p, f, fm, 0.6 * this.view.bounds.radius * fm / Math.max(tr.fmax, 1e-12));
    if (this.surface) showTrackSurface(this.surface, tr, frameIndex);
    const torque = Math.hypot(tr.torque[3 * frameIndex], tr.torque[3 * frameIndex + 1], tr.torque[3 * frameIndex + 2]);
    document.getElementById('readout').textContent =
        't = ' + tr.t[frameIndex].toFixed(3) + ' s   |F| = ' + fmt(fm) + ' N   |T| = ' + fmt(torque) + ' N m' +
        (tr.level[frameIndex] >= 0 ? '   level ' + tr.level[frameIndex] : '') + '   contacts ' + tr.contacts[frameIndex];
    this.view.plot.draw(this.tracks, this.current, frameIndex);
  }

  // An animation frame at NOW (ms): while playing, the frame at the time played to.
  tick(now) {
    if (!this.playing || this.tracks.length === 0) return;
    const tr = this.tracks[this.current];
    if (this.lastWall !== null) this.playTime += (now - this.lastWall) / 1000 * Number(document.getElementById('speed').value);
    this.lastWall = now;
    if (this.playTime >= tr.t[tr.t.length - 1]) {
      this.playTime = tr.t[tr.t.length - 1];
      this.playing = false;
      this.updatePlayButton();
    }
    this.showTime(this.playTime);
  }
}

// Shows the replay bar and the first frame of REPLAY (the page data's "replay") in VIEW
// ({scene, bodies, arrow, bounds, plot}), as OPTIONS ask; returns what the animation loop
// ticks.
export function startReplay(replay, view, options) {
  document.getElementById('replay').hidden = false;
  const replayer = new Replayer(replay, view);
  replayer.wireControls();
  if (replayer.tracks.length > 0) replayer.start(options);
  return replayer;
}
