// The force arrow of a replay or a live view: the force on the moving (haptic) body, red, at
// its origin.
import { THREE } from './three_global.js';
import { FORCE_COLOUR } from './colours.js';

// Points ARROW from P (x, y, z) along F (a THREE.Vector3 of length FM > 0, scaled in place to
// unit length), LEN long.
export function aimArrow(arrow, p, f, fm, len) {
  arrow.position.set(p[0], p[1], p[2]);
  arrow.setDirection(f.multiplyScalar(1 / fm));
  arrow.setLength(Math.max(len, 1e-6), 0.25 * len, 0.12 * len);
}

// The force arrow (red) of a replay or a live view, hidden until there is a force to show.
export function addForceArrow(scene) {
  const arrow = new THREE.ArrowHelper(new THREE.Vector3(0, 0, 1), new THREE.Vector3(), 0.01, FORCE_COLOUR);
  arrow.visible = false;
  // Drawn over everything: it starts at the moving body's origin, often inside a body.
  arrow.renderOrder = 3;
  arrow.line.material.depthTest = false;
  arrow.cone.material.depthTest = false;
  scene.add(arrow);
  return arrow;
}
