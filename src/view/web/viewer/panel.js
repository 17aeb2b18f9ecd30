// The panel: title, subtitle, the legend of what is drawn, and the checkboxes that show or
// hide each part.
import { CONTACT_COLOUR, LEVEL_COLOURS, PRESSURE_STOPS, bodyColour } from './colours.js';
import { decode, el, fmt, hex } from './util.js';

// A legend row: a swatch of COLOUR and TEXT, of class CLS ('row' and more).
function swatchRow(cls, colour, text) {
  const row = el('div', {'class': cls});
  row.appendChild(el('span', {'class': 'swatch', style: 'background:' + colour}));
  row.appendChild(el('span', {}, text));
  return row;
}

// A row per body: its colour, name, role (the tool of a scene of many bodies), how it deforms,
// its triangles.
function bodyLegend(legend, bodies) {
  const specs = bodies.map(function (b) { return b.spec; });
  bodies.forEach(function (b, i) {
    const how = !b.spec.deformable ? '' : b.basis ? ', deformable: mesh deformed per frame, points at rest'
                                                  : ', deformable, shown at rest';
    const triangles = b.spec.source_triangles > b.spec.triangles
        ? b.spec.source_triangles + ' \u2192 ' + b.spec.triangles + ' triangles for display' : b.spec.triangles + ' triangles';
    const role = b.spec.tool ? 'tool, ' + b.spec.role : b.spec.role;
    legend.appendChild(swatchRow('row', hex(bodyColour(specs, i)), b.spec.name + ' (' + role + how + ', ' + triangles + ')'));
  });
}

// The pointshell PS: its points drawn per level, and those in contact at the start when drawn.
function pointshellLegend(legend, ps, contactPoints) {
  const shown = ps.kept.reduce(function (a, b) { return a + b; }, 0);
  legend.appendChild(el('div', {'class': 'small'}, 'pointshell: ' + ps.points + ' points, ' + ps.levels +
                                                  ' levels; ' + shown + ' drawn'));
  ps.kept.forEach(function (kept, l) {
    legend.appendChild(swatchRow('row small level-row', LEVEL_COLOURS[l % LEVEL_COLOURS.length],
                                 'level ' + l + ': ' + kept + (kept < ps.total[l] ? ' of ' + ps.total[l] : '') + ' points'));
  });
  if (contactPoints) {
    legend.appendChild(swatchRow('row small', CONTACT_COLOUR,
                                 'in contact at the start (d < 0): ' + ps.in_contact + ' of ' + ps.points + ' points'));
  }
}

// The field slice S of BODIES[S.body]: where it is, and its colour bar.
function sliceLegend(legend, s, bodies) {
  legend.appendChild(el('div', {'class': 'small'}, 'field of ' + bodies[s.body].spec.name + ', slice ' +
                                                  'xyz'[s.axis] + ' = ' + fmt(s.at) + ' m (body frame)'));
  legend.appendChild(el('div', {'class': 'colorbar', style:
      'background: linear-gradient(to right, rgb(40,110,70), rgb(100,230,160) 49%, #000 49.5%, #000 50.5%, ' +
      'rgb(220,110,240) 51%, rgb(110,50,130))'}));
  legend.appendChild(el('div', {'class': 'small'}, 'd from ' + fmt(s.min) + ' m (inside, green) to ' + fmt(s.max) +
                                                  ' m (outside, purple); black: d = 0; isolines every ' +
                                                  fmt(4 * s.spacing) + ' m'));
}

// The pressure colour bar and TEXT.
function surfaceLegend(legend, text) {
  legend.appendChild(el('div', {'class': 'colorbar', style:
      'background: linear-gradient(to right, ' + PRESSURE_STOPS.map(function (c) { return 'rgb(' + c.join(',') + ')'; }).join(', ') + ')'}));
  legend.appendChild(el('div', {'class': 'small surface-legend'}, text));
}

// Title, subtitle and legend of DATA, drawn as BODIES, PARTS.contactPoints and PARTS.surfaces.
export function fillPanel(data, bodies, parts) {
  const replay = data.replay || null;
  document.getElementById('title').textContent = data.title || 'ContactLab';
  document.getElementById('subtitle').textContent =
      replay ? (replay.folder + ', job ' + replay.job + (replay.label ? ' (' + replay.label + ')' : '')) : (data.scene || '');
  const legend = document.getElementById('legend');
  bodyLegend(legend, bodies);
  if (data.pointshell) pointshellLegend(legend, data.pointshell, parts.contactPoints);
  if (data.slice) sliceLegend(legend, data.slice, bodies);
  if (data.pairs) {
    legend.appendChild(el('div', {'class': 'small'}, data.pairs.length + ' pairs: ' + data.pairs.map(function (p) {
      return p.bodies.join(' / ') + ' (' + p.model + ')';
    }).join(', ')));
  }
  parts.surfaces.forEach(function (sf) {
    surfaceLegend(legend, 'contact surface of ' + sf.spec.model + ': ' + sf.spec.triangles + ' triangles' +
                          (sf.spec.triangles >= sf.spec.max_triangles ? ' (the first ' + sf.spec.max_triangles + ')' : '') +
                          ', pressure 0 to ' + fmt(sf.spec.pmax) + ' Pa');
  });
  if (replay && replay.models.some(function (m) { return m.surface; })) {
    surfaceLegend(legend, 'contact surface (pressure-field models), at ' + replay.models.filter(function (m) { return m.surface; })
                          .map(function (m) { return m.name + ': ' + decode(m.surface.frames, Int32Array).length; }).join(', ') +
                          ' frames, each at the kept frame at or before the one shown; pressure 0 to the model\'s largest');
  }
}

// A checkbox LABEL that shows or hides OBJECTS, checked when ON.
export function addToggle(label, objects, on) {
  const box = el('input', {type: 'checkbox'});
  box.checked = on;
  objects.forEach(function (o) { o.visible = on; });
  box.addEventListener('change', function () { objects.forEach(function (o) { o.visible = box.checked; }); });
  const lab = el('label');
  lab.appendChild(box);
  lab.appendChild(document.createTextNode(' ' + label));
  document.getElementById('toggles').appendChild(lab);
}

// The 'solid' checkbox: BODIES opaque instead of translucent.
function addSolidToggle(bodies) {
  const solid = el('input', {type: 'checkbox'});
  solid.addEventListener('change', function () {
    bodies.forEach(function (b) {
      b.mesh.material.transparent = !solid.checked;
      b.mesh.material.depthWrite = solid.checked;
      b.mesh.material.opacity = solid.checked ? 1 : 0.55;
      b.mesh.material.needsUpdate = true;
    });
  });
  const solidLabel = el('label');
  solidLabel.appendChild(solid);
  solidLabel.appendChild(document.createTextNode(' solid'));
  document.getElementById('toggles').appendChild(solidLabel);
}

// A checkbox per part drawn (BODIES and PARTS: points, contactPoints, slice, surfaces), and 'solid'.
export function addPanelToggles(bodies, parts) {
  bodies.forEach(function (b) { addToggle(b.spec.name, [b.mesh], true); });
  if (parts.points) addToggle('points', [parts.points], true);
  if (parts.contactPoints) addToggle('contact', [parts.contactPoints], true);
  if (parts.slice) addToggle('slice', [parts.slice], true);
  parts.surfaces.forEach(function (sf) { addToggle(sf.spec.model + ' surface', [sf.mesh], true); });
  addSolidToggle(bodies);
}
