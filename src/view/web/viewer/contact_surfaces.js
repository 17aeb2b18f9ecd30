// Contact surfaces (pressure-field): triangles in the world, coloured by pressure
// (colours.js, PRESSURE_STOPS), drawn over the bodies; on a scene page at the start poses, in a
// replay at the kept frame at or before the one shown.
import { THREE } from './three_global.js';
import { PRESSURE_STOPS } from './colours.js';
import { decode } from './util.js';

// The colour of pressure fraction T (0..1) into OUT[O..O+2], RGB in 0..1.
function pressureColour(t, out, o) {
  t = Math.max(0, Math.min(1, t));
  const a = t < 0.5 ? PRESSURE_STOPS[0] : PRESSURE_STOPS[1], b = t < 0.5 ? PRESSURE_STOPS[1] : PRESSURE_STOPS[2];
  const u = t < 0.5 ? 2 * t : 2 * t - 1;
  for (let k = 0; k < 3; ++k) out[o + k] = (a[k] + u * (b[k] - a[k])) / 255;
}

// An empty surface mesh, added to SCENE.
export function surfaceMesh(scene) {
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.BufferAttribute(new Float32Array(0), 3));
  g.setAttribute('color', new THREE.BufferAttribute(new Float32Array(0), 3));
  const m = new THREE.Mesh(g, new THREE.MeshBasicMaterial({vertexColors: THREE.VertexColors, side: THREE.DoubleSide,
                                                           depthTest: false, transparent: true, opacity: 0.9}));
  m.renderOrder = 4;
  scene.add(m);
  return m;
}

// Shows triangles FIRST..END of CORNERS (9 floats each) and PRESSURE (3 each) on MESH.
export function setSurface(mesh, corners, pressure, pmax, first, end) {
  const pos = corners.slice(9 * first, 9 * end), col = new Float32Array(pos.length);
  for (let i = 0; i < pos.length / 3; ++i) pressureColour(pressure[3 * first + i] / Math.max(pmax, 1e-30), col, 3 * i);
  mesh.geometry.setAttribute('position', new THREE.BufferAttribute(pos, 3));
  mesh.geometry.setAttribute('color', new THREE.BufferAttribute(col, 3));
  mesh.geometry.computeBoundingSphere();
}

// The surfaces of a scene page (the page data's "surfaces"), each added to SCENE: {spec, mesh}.
export function addSceneSurfaces(specs, scene) {
  return specs.map(function (sf) {
    const mesh = surfaceMesh(scene), corners = decode(sf.corners, Float32Array);
    setSurface(mesh, corners, decode(sf.pressure, Float32Array), sf.pmax, 0, corners.length / 9);
    return {spec: sf, mesh: mesh};
  });
}

// Shows on MESH the contact surface of replay track TR at the last kept frame at or before
// FRAMEINDEX (none for a model without one).
export function showTrackSurface(mesh, tr, frameIndex) {
  const sf = tr.surface;
  mesh.userData.model = sf ? tr.name : '';
  if (!sf) { setSurface(mesh, new Float32Array(0), new Float32Array(0), 1, 0, 0); return; }
  let lo = 0, hi = sf.frames.length - 1;
  while (lo < hi) { const mid = (lo + hi + 1) >> 1; if (sf.frames[mid] <= frameIndex) lo = mid; else hi = mid - 1; }
  setSurface(mesh, sf.corners, sf.pressure, sf.pmax, sf.start[lo], sf.start[lo + 1]);
  mesh.userData.frame = sf.frames[lo];
}
