// Small helpers of the viewer: typed arrays from the page data, poses, DOM elements, numbers.

// Base64 text of little-endian bytes -> typed array of TYPE.
export function decode(text, Type) {
  const bin = atob(text);
  const bytes = new Uint8Array(bin.length);
  for (let i = 0; i < bin.length; ++i) bytes[i] = bin.charCodeAt(i);
  return new Type(bytes.buffer);
}

// Puts OBJECT at pose P: [x, y, z, qw, qx, qy, qz].
export function setPose(object, p) {
  object.position.set(p[0], p[1], p[2]);
  object.quaternion.set(p[4], p[5], p[6], p[3]).normalize();
}

// A new TAG element with the attributes ATTRS and, when given, the text TEXT.
export function el(tag, attrs, text) {
  const e = document.createElement(tag);
  for (const k in attrs) e.setAttribute(k, attrs[k]);
  if (text !== undefined) e.textContent = text;
  return e;
}

// '#rrggbb' of the colour number C.
export function hex(c) { return '#' + ('000000' + c.toString(16)).slice(-6); }

// V with DIGITS (default 3) significant digits.
export function fmt(v, digits) { return Number(v).toPrecision(digits || 3); }
