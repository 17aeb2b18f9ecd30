// The live view's contacts of a scene of many bodies (docs/viewer.md): every touching pair's
// contacts of one cycle (its model's contact list, world frame), as "pair-contacts" events of the
// session's stream, drawn as red points through everything and counted per pair in the legend.
import { CONTACT_COLOUR } from './colours.js';
import { contactPointCloud } from './contact_marks.js';
import { decode, el } from './util.js';

// Room for MAX contacts in SCENE (a frame with more makes a larger one).
function contactPoints(scene, max) {
  const points = contactPointCloud(max);
  scene.add(points);
  return points;
}

// The legend's rows of frame F: contacts per touching pair (PAIRS: the page data's "pairs").
function showPairsLegend(row, f, pairIndex, pairs) {
  const counts = new Map();
  for (let i = 0; i < pairIndex.length; ++i) counts.set(pairIndex[i], (counts.get(pairIndex[i]) || 0) + 1);
  row.innerHTML = '';
  const head = el('div', {'class': 'row small'});
  head.appendChild(el('span', {'class': 'swatch', style: 'background:' + CONTACT_COLOUR}));
  head.appendChild(el('span', {}, 'contacts, cycle ' + f.cycle + ': ' + f.contacts + ' of ' + f.pairs_touching +
                                  ' pair' + (f.pairs_touching === 1 ? '' : 's') +
                                  (f.not_kept > 0 ? ' (' + f.not_kept + ' more not listed)' : '')));
  row.appendChild(head);
  Array.from(counts.keys()).sort(function (a, b) { return a - b; }).forEach(function (p) {
    const names = pairs[p] ? pairs[p].bodies.join(' / ') : 'pair ' + p;
    row.appendChild(el('div', {'class': 'small'}, names + ': ' + counts.get(p)));
  });
}

// Draws the pair contacts of STREAM (an EventSource) in SCENE as they come. Each event sets
// data-pair-contacts (frames received) and data-pair-contacts-count (contacts in the newest) on
// <html>.
export function followPairContacts(stream, scene, pairs) {
  let points = contactPoints(scene, 1024), row = null, received = 0;
  stream.addEventListener('pair-contacts', function (e) {
    const f = JSON.parse(e.data);
    const xyz = decode(f.points, Float32Array), pairIndex = decode(f.pair, Int32Array);
    if (xyz.length > points.geometry.attributes.position.array.length) {
      scene.remove(points);
      points = contactPoints(scene, xyz.length / 3);
    }
    const position = points.geometry.attributes.position;
    position.array.set(xyz);
    position.needsUpdate = true;
    points.geometry.setDrawRange(0, xyz.length / 3);
    if (!row) {
      row = el('div', {'class': 'small'});
      document.getElementById('legend').appendChild(row);
    }
    showPairsLegend(row, f, pairIndex, pairs);
    document.documentElement.setAttribute('data-pair-contacts', String(++received));
    document.documentElement.setAttribute('data-pair-contacts-count', String(xyz.length / 3));
  });
}
