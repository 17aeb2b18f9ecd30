// The pointshell of body A, coloured by the level that adds each point, and on a scene page
// the points in contact at the start poses.
import { THREE } from './three_global.js';
import { CONTACT_COLOUR, LEVEL_COLOURS } from './colours.js';
import { decode } from './util.js';

// The points of PS (the page data's "pointshell") at POSITIONS, coloured by level.
function levelPoints(ps, positions) {
  const levels = decode(ps.level, Uint8Array);
  const colours = new Float32Array(levels.length * 3);
  const c = new THREE.Color();
  for (let i = 0; i < levels.length; ++i) {
    c.set(LEVEL_COLOURS[levels[i] % LEVEL_COLOURS.length]);
    colours[3 * i] = c.r; colours[3 * i + 1] = c.g; colours[3 * i + 2] = c.b;
  }
  const pg = new THREE.BufferGeometry();
  pg.setAttribute('position', new THREE.BufferAttribute(positions, 3));
  pg.setAttribute('color', new THREE.BufferAttribute(colours, 3));
  const points = new THREE.Points(pg, new THREE.PointsMaterial({size: 2.5, sizeAttenuation: false,
                                                                vertexColors: THREE.VertexColors}));
  points.renderOrder = 1;
  return points;
}

// The points of PS at POSITIONS flagged in contact, larger and red; null when none is.
function startContactPoints(ps, positions) {
  const flags = decode(ps.contact, Uint8Array), touching = [];
  for (let m = 0; m < flags.length; ++m) {
    if (flags[m]) touching.push(positions[3 * m], positions[3 * m + 1], positions[3 * m + 2]);
  }
  if (touching.length === 0) return null;
  const cg = new THREE.BufferGeometry();
  cg.setAttribute('position', new THREE.BufferAttribute(new Float32Array(touching), 3));
  // Drawn through everything: the contact region is usually hidden inside the other body.
  // Transparent, so that it is drawn with (after, by renderOrder) the translucent bodies.
  const contactPoints = new THREE.Points(cg, new THREE.PointsMaterial({size: 4, sizeAttenuation: false, color: CONTACT_COLOUR,
                                                                       depthTest: false, transparent: true, depthWrite: false}));
  contactPoints.renderOrder = 5;
  return contactPoints;
}

// Adds DATA's pointshell (when it has one) to its body of BODIES: {points, contactPoints},
// each null when absent. The points in contact at the start poses are drawn on a scene page
// only: in a replay or live view the bodies move on.
export function addPointshell(data, bodies) {
  if (!data.pointshell) return {points: null, contactPoints: null};
  const ps = data.pointshell;
  const positions = decode(ps.positions, Float32Array);
  const points = levelPoints(ps, positions);
  bodies[ps.body].group.add(points);
  let contactPoints = null;
  if (ps.contact && !data.replay && !data.live) {
    contactPoints = startContactPoints(ps, positions);
    if (contactPoints) bodies[ps.body].group.add(contactPoints);
  }
  return {points: points, contactPoints: contactPoints};
}
