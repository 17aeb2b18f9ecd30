// The live view's contact marks (docs/viewer.md): per-point contact state of the drawn points,
// from a sweep over a few consecutive cycles, as "marks" events of the session's stream: red in
// contact (d < 0), blue evaluated (d >= 0), grey not evaluated.
import { THREE } from './three_global.js';
import { CONTACT_COLOUR, EVALUATED_COLOUR, UNEVALUATED_COLOUR } from './colours.js';
import { decode, el } from './util.js';

// Room for N points in contact, drawn larger and through everything, as on a scene page: they
// usually lie inside the other body. None drawn yet.
export function contactPointCloud(n) {
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(3 * n), 3));
  geometry.setDrawRange(0, 0);
  // Transparent, so that it is drawn with (after, by renderOrder) the translucent bodies.
  const cloud = new THREE.Points(geometry, new THREE.PointsMaterial(
      {size: 5, sizeAttenuation: false, color: CONTACT_COLOUR, depthTest: false, transparent: true, depthWrite: false}));
  cloud.renderOrder = 5;
  cloud.frustumCulled = false;
  return cloud;
}

// The points in contact again, added to POINTS (same frame; hidden with them).
function touchingPoints(points) {
  const touching = contactPointCloud(points.geometry.attributes.position.count);
  points.add(touching);
  return touching;
}

// Colours POINTS by the 2-bit states of marks M (MarksJson) and copies those in contact into
// TOUCHING; returns the count of each state (not evaluated, evaluated, in contact).
function colourByState(m, points, touching, markColours) {
  const packed = decode(m.states, Uint8Array);
  const drawnPositions = points.geometry.attributes.position.array;
  const col = points.geometry.attributes.color, a = col.array;
  const n = Math.min(m.points, a.length / 3), counts = [0, 0, 0];
  const tp = touching.geometry.attributes.position;
  for (let i = 0; i < n; ++i) {
    const state = (packed[i >> 2] >> (2 * (i & 3))) & 3, mc = markColours[state] || markColours[0];
    if (state === 2) {
      tp.array[3 * counts[2]] = drawnPositions[3 * i];
      tp.array[3 * counts[2] + 1] = drawnPositions[3 * i + 1];
      tp.array[3 * counts[2] + 2] = drawnPositions[3 * i + 2];
    }
    ++counts[state];
    a[3 * i] = mc.r; a[3 * i + 1] = mc.g; a[3 * i + 2] = mc.b;
  }
  col.needsUpdate = true;
  tp.needsUpdate = true;
  touching.geometry.setDrawRange(0, counts[2]);
  return counts;
}

// The legend's rows of the marks M, COUNTS per state, in MARKSROW.
function showMarksLegend(marksRow, m, counts) {
  marksRow.innerHTML = '';
  [[CONTACT_COLOUR, 'in contact (d < 0): ' + counts[2]], [EVALUATED_COLOUR, 'evaluated, d >= 0: ' + counts[1]],
   [UNEVALUATED_COLOUR, 'not evaluated: ' + counts[0]]].forEach(function (x) {
    const r = el('div', {'class': 'row small'});
    r.appendChild(el('span', {'class': 'swatch', style: 'background:' + x[0]}));
    r.appendChild(el('span', {}, x[1]));
    marksRow.appendChild(r);
  });
  marksRow.appendChild(el('div', {'class': 'small'}, 'drawn points by contact state, cycles ' + m.first_cycle +
                                                   '-' + m.last_cycle));
}

// Colours POINTS by the marks events of STREAM (an EventSource) as they come. Each event also
// sets data-marks (events received) and data-marks-contact (points in contact) on <html>, and
// data-panel: where the panel is (x,y,w,h, CSS px), since its legend swatches are not points.
export function followContactMarks(stream, points) {
  const markColours = [UNEVALUATED_COLOUR, EVALUATED_COLOUR, CONTACT_COLOUR].map(function (h) { return new THREE.Color(h); });
  let marksRow = null, marksReceived = 0;
  const touching = touchingPoints(points);
  stream.addEventListener('marks', function (e) {
    const m = JSON.parse(e.data);
    const counts = colourByState(m, points, touching, markColours);
    if (!marksRow) {  // the points now show contact state, not level
      Array.prototype.forEach.call(document.querySelectorAll('.level-row'), function (r) { r.hidden = true; });
      marksRow = el('div', {'class': 'small'});
      document.getElementById('legend').appendChild(marksRow);
    }
    showMarksLegend(marksRow, m, counts);
    document.documentElement.setAttribute('data-marks', String(++marksReceived));
    document.documentElement.setAttribute('data-marks-contact', String(counts[2]));
    const pr = document.getElementById('panel').getBoundingClientRect();
    document.documentElement.setAttribute('data-panel', [pr.left, pr.top, pr.width, pr.height].map(Math.round).join(','));
  });
}
