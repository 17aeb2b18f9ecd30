// The bodies (two, or a scene's many): a group per body at its pose holding its mesh (and A's points, B's slice),
// and the deformation of a deformable body's mesh by a replay's reduced coordinates.
import { THREE } from './three_global.js';
import { bodyColour } from './colours.js';
import { decode, setPose } from './util.js';

// Adds the bodies of SPECS (the page data's "bodies") to SCENE; returns {spec, group, mesh}
// per body, with rest positions, basis and modes for a deformable body of a replay.
export function addBodies(scene, specs) {
  return specs.map(function (b, i) {
    const group = new THREE.Group();
    group.name = b.name;
    setPose(group, b.pose);
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.BufferAttribute(decode(b.positions, Float32Array), 3));
    geometry.setIndex(new THREE.BufferAttribute(decode(b.indices, Uint32Array), 1));
    geometry.computeVertexNormals();
    const material = new THREE.MeshLambertMaterial({color: bodyColour(specs, i), side: THREE.DoubleSide,
                                                    transparent: true, opacity: 0.55, depthWrite: false});
    const mesh = new THREE.Mesh(geometry, material);
    mesh.renderOrder = 2;
    group.add(mesh);
    scene.add(group);
    const body = {spec: b, group: group, mesh: mesh};
    // A deformable body of a replay: rest positions and the reduced basis (#V x 3 x r) at its
    // vertices, so that a frame's coordinates q deform it (u = U q).
    if (b.basis) {
      body.rest = geometry.attributes.position.array.slice();
      body.basis = decode(b.basis, Float32Array);
      body.modes = b.modes;
    }
    return body;
  });
}

// Deforms BODY's mesh by reduced coordinates Q (from OFFSET, body.modes entries).
export function deform(body, q, offset) {
  const pos = body.mesh.geometry.attributes.position, a = pos.array, U = body.basis, r = body.modes;
  for (let n = 0; n < a.length; ++n) {
    let u = 0;
    for (let m = 0; m < r; ++m) u += U[n * r + m] * q[offset + m];
    a[n] = body.rest[n] + u;
  }
  pos.needsUpdate = true;
  body.mesh.geometry.computeVertexNormals();
  body.mesh.geometry.computeBoundingSphere();
}
