// A slice of body B's distance field: green inside (d < 0), purple outside, paler near the
// surface, black on the zero contour, darker isolines every 4 grid cells.
import { THREE } from './three_global.js';
import { decode } from './util.js';

// The colour of distance D (SCALE: the largest |d| of the slice) into OUT[O..O+3], RGBA bytes.
function sliceColour(d, scale, out, o) {
  const t = Math.min(1, Math.abs(d) / scale);
  if (d < 0) { out[o] = 40 + 60 * (1 - t); out[o + 1] = 110 + 120 * (1 - t); out[o + 2] = 70 + 90 * (1 - t); }
  else { out[o] = 110 + 110 * (1 - t); out[o + 1] = 50 + 60 * (1 - t); out[o + 2] = 130 + 110 * (1 - t); }
  out[o + 3] = 255;
}

// The RGBA texture of slice S (the page data's "slice"), a texel per sample.
function sliceTexture(s) {
  const values = decode(s.values, Float32Array);
  const w = s.width, h = s.height;
  const rgba = new Uint8Array(w * h * 4);
  const scale = Math.max(Math.abs(s.min), Math.abs(s.max), 1e-12);
  const iso = 4 * s.spacing;
  for (let j = 0; j < h; ++j) {
    for (let k = 0; k < w; ++k) {
      const n = j * w + k, v0 = values[n];
      sliceColour(v0, scale, rgba, 4 * n);
      // A contour passes between this sample and its right or upper neighbour: the zero
      // contour (sign change) in black, an isoline (another multiple of ISO) darkened.
      const band = Math.floor(v0 / iso);
      let zero = false, line = false;
      const neighbours = [k + 1 < w ? values[n + 1] : v0, j + 1 < h ? values[n + w] : v0];
      for (let m = 0; m < 2; ++m) {
        if ((v0 < 0) !== (neighbours[m] < 0)) zero = true;
        else if (Math.floor(neighbours[m] / iso) !== band) line = true;
      }
      if (zero) { rgba[4 * n] = rgba[4 * n + 1] = rgba[4 * n + 2] = 0; }
      else if (line) { rgba[4 * n] *= 0.7; rgba[4 * n + 1] *= 0.7; rgba[4 * n + 2] *= 0.7; }
    }
  }
  const texture = new THREE.DataTexture(rgba, w, h, THREE.RGBAFormat);
  texture.magFilter = THREE.NearestFilter;
  texture.minFilter = THREE.LinearFilter;
  texture.generateMipmaps = false;
  texture.needsUpdate = true;
  return texture;
}

// Adds slice S to its body of BODIES: a quad from the centre of sample (0, 0) to the centre of
// sample (w-1, h-1), textured by sliceTexture. Returns the quad.
export function addFieldSlice(s, bodies) {
  const texture = sliceTexture(s);
  const w = s.width, h = s.height;
  const P = function (a, b) {
    return [s.corner[0] + a * s.u[0] + b * s.v[0], s.corner[1] + a * s.u[1] + b * s.v[1],
            s.corner[2] + a * s.u[2] + b * s.v[2]];
  };
  const quad = [].concat(P(0, 0), P(w - 1, 0), P(w - 1, h - 1), P(0, h - 1));
  const du = 0.5 / w, dv = 0.5 / h;
  const sg = new THREE.BufferGeometry();
  sg.setAttribute('position', new THREE.BufferAttribute(new Float32Array(quad), 3));
  sg.setAttribute('uv', new THREE.BufferAttribute(new Float32Array([du, dv, 1 - du, dv, 1 - du, 1 - dv, du, 1 - dv]), 2));
  sg.setIndex([0, 1, 2, 0, 2, 3]);
  const slice = new THREE.Mesh(sg, new THREE.MeshBasicMaterial({map: texture, side: THREE.DoubleSide}));
  slice.renderOrder = 0;
  bodies[s.body].group.add(slice);
  return slice;
}
