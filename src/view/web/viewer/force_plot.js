// The force plot under the 3D view: |F| against t of every track, each in its own colour and
// named in the plot's legend (the current one thicker, its name marked), with a cursor at the
// current frame; a replay's models, or the live view's last 10 s.
import { TRACK_COLOURS } from './colours.js';
import { fmt } from './util.js';

// One track X (x.t, x.fmag) as a polyline of COLOUR on context G through X(t), Y(f), at most
// ~2 samples per pixel of a plot WIDTH pixels wide.
function curve(g, x, X, Y, colour, width, lineWidth) {
  g.strokeStyle = colour;
  g.lineWidth = lineWidth;
  g.beginPath();
  const step = Math.max(1, Math.floor(x.t.length / (2 * width)));
  for (let i = 0; i < x.t.length; i += step) {
    if (i === 0) g.moveTo(X(x.t[i]), Y(x.fmag[i])); else g.lineTo(X(x.t[i]), Y(x.fmag[i]));
  }
  g.stroke();
}

// The frame, axis labels and limits of a plot of AREA on context G (CH: the canvas height, CSS px).
function axes(g, area, ch, t0, t1, fmax) {
  g.strokeStyle = '#70757c';
  g.lineWidth = 1;
  g.strokeRect(area.left, area.top, area.width, area.height);
  g.fillStyle = '#c8ccd2';
  g.font = '11px sans-serif';
  g.textAlign = 'right';
  g.fillText(fmt(fmax) + ' N', area.left - 4, area.top + 9);
  g.fillText('0', area.left - 4, area.top + area.height);
  g.save();
  g.translate(12, area.top + area.height / 2);
  g.rotate(-Math.PI / 2);
  g.textAlign = 'center';
  g.fillText('|F| (N)', 0, 0);
  g.restore();
  g.textAlign = 'center';
  g.textAlign = 'left';
  g.fillText(t0.toFixed(2), area.left, ch - 6);
  g.textAlign = 'right';
  g.fillText(t1.toFixed(2), area.left + area.width, ch - 6);
  g.textAlign = 'center';
  g.fillText('t (s)', area.left + area.width / 2, ch - 6);
}

// Track K's colour.
export function trackColour(k) { return TRACK_COLOURS[k % TRACK_COLOURS.length]; }

// The tracks' names in their colours, top right inside AREA, on a dark backing so no curve
// hides them; the current one marked and bold.
function legend(g, area, tracks, current) {
  const named = tracks.filter(function (x) { return x.name; });
  if (named.length === 0) return;
  g.font = '11px sans-serif';
  const rows = tracks.map(function (x, k) { return {k: k, text: (k === current ? '\u25b6 ' : '') + (x.name || '')}; })
                     .filter(function (r) { return tracks[r.k].name; });
  let w = 0;
  rows.forEach(function (r) { w = Math.max(w, g.measureText(r.text).width); });
  const lineH = 13, pad = 4;
  const left = area.left + area.width - w - 2 * pad - 14, top = area.top + 2;
  g.fillStyle = 'rgba(20, 22, 26, 0.85)';
  g.fillRect(left, top, w + 2 * pad + 14, rows.length * lineH + 2 * pad);
  g.textAlign = 'left';
  rows.forEach(function (r, i) {
    const y = top + pad + i * lineH + 10;
    g.fillStyle = trackColour(r.k);
    g.fillRect(left + pad, y - 7, 10, 3);
    g.font = (r.k === current ? 'bold ' : '') + '11px sans-serif';
    g.fillText(r.text, left + pad + 14, y);
  });
  g.font = '11px sans-serif';
}

export class ForcePlot {
  // CANVAS: the <canvas> to draw on.
  constructor(canvas) {
    this.canvas = canvas;
    this.area = {left: 56, top: 8, width: 1, height: 1};  // the plot's frame, CSS px
    this.shown = null;  // what draw() drew last
  }

  // Draws TRACKS ({t, fmag, fmax} each), track CURRENT bright, the cursor at its FRAMEINDEX.
  draw(tracks, current, frameIndex) {
    this.shown = {tracks: tracks, current: current, frameIndex: frameIndex};
    const plot = this.canvas, area = this.area;
    const dpr = window.devicePixelRatio || 1;
    const cw = plot.clientWidth, ch = plot.clientHeight;
    if (plot.width !== Math.round(cw * dpr)) { plot.width = Math.round(cw * dpr); plot.height = Math.round(ch * dpr); }
    const g = plot.getContext('2d');
    g.setTransform(dpr, 0, 0, dpr, 0, 0);
    g.clearRect(0, 0, cw, ch);
    area.width = Math.max(10, cw - area.left - 10);
    area.height = Math.max(10, ch - area.top - 24);
    const tr = tracks[current];
    const t0 = tr.t[0];
    let t1 = tr.t[tr.t.length - 1];
    if (!(t1 > t0)) t1 = t0 + 1;
    let fmax = 0;
    tracks.forEach(function (x) { fmax = Math.max(fmax, x.fmax); });
    if (!(fmax > 0)) fmax = 1;
    const X = function (t) { return area.left + (t - t0) / (t1 - t0) * area.width; };
    const Y = function (f) { return area.top + area.height * (1 - f / fmax); };
    axes(g, area, ch, t0, t1, fmax);
    // Curves, each track in its colour; the current one last (on top) and thicker.
    tracks.forEach(function (x, k) {
      if (k !== current) curve(g, x, X, Y, trackColour(k), area.width, 1.25);
    });
    curve(g, tr, X, Y, trackColour(current), area.width, 2.5);
    legend(g, area, tracks, current);
    // The names the legend shows, for tests that read the page's DOM.
    plot.setAttribute('data-legend', tracks.map(function (x) { return x.name || ''; }).join(','));
    // Cursor.
    g.strokeStyle = '#ffffff';
    g.beginPath();
    g.moveTo(X(tr.t[frameIndex]) + 0.5, area.top);
    g.lineTo(X(tr.t[frameIndex]) + 0.5, area.top + area.height);
    g.stroke();
  }

  // Draws again what was drawn last (after the canvas was resized), if anything.
  redraw() {
    const s = this.shown;
    if (s && s.tracks.length > 0) this.draw(s.tracks, s.current, s.frameIndex);
  }

  // Where CLIENTX (a mouse event's) falls along the time axis: 0 at its start, 1 at its end.
  fractionAt(clientX) {
    const r = this.canvas.getBoundingClientRect();
    return Math.max(0, Math.min(1, (clientX - r.left - this.area.left) / this.area.width));
  }
}
