// Exact point-triangle distance (Barbič & James 2008, sec. 2.3: the distance field samples the
// exact distance to the surface). Region-based closest point (Ericson, Real-Time Collision
// Detection, sec. 5.1.5) with guards for degenerate (zero-area or zero-length) triangles.
#pragma once

#include <algorithm>

namespace contactlab {

namespace internal {

inline double Dot3(const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// Squared distance from P to the segment A-B (a point when A == B).
inline double PointSegmentDistanceSquared(const double* p, const double* a, const double* b) {
  const double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double ap[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
  const double len2 = Dot3(ab, ab);
  const double t = len2 > 0 ? std::clamp(Dot3(ap, ab) / len2, 0.0, 1.0) : 0.0;
  const double d[3] = {ap[0] - t * ab[0], ap[1] - t * ab[1], ap[2] - t * ab[2]};
  return Dot3(d, d);
}

}  // namespace internal

// Squared Euclidean distance from point P to the closed triangle (A, B, C); every argument
// points at 3 doubles (metres). Exact up to double rounding for every triangle, degenerate
// ones included (they are treated as the union of their edges). Never allocates or throws.
inline double PointTriangleDistanceSquared(const double* p, const double* a, const double* b,
                                           const double* c) {
  using internal::Dot3;
  const double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double ac[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double ap[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
  // Degenerate triangles (no area) are the union of their edges.
  const double n[3] = {ab[1] * ac[2] - ab[2] * ac[1], ab[2] * ac[0] - ab[0] * ac[2], ab[0] * ac[1] - ab[1] * ac[0]};
  if (!(Dot3(n, n) > 1e-24 * Dot3(ab, ab) * Dot3(ac, ac))) {
    return std::min({internal::PointSegmentDistanceSquared(p, a, b),
                     internal::PointSegmentDistanceSquared(p, b, c),
                     internal::PointSegmentDistanceSquared(p, c, a)});
  }
  auto dist2_to = [p](double x, double y, double z) {
    const double d[3] = {p[0] - x, p[1] - y, p[2] - z};
    return Dot3(d, d);
  };
  // Vertex region A.
  const double d1 = Dot3(ab, ap), d2 = Dot3(ac, ap);
  if (d1 <= 0 && d2 <= 0) return Dot3(ap, ap);
  // Vertex region B.
  const double bp[3] = {p[0] - b[0], p[1] - b[1], p[2] - b[2]};
  const double d3 = Dot3(ab, bp), d4 = Dot3(ac, bp);
  if (d3 >= 0 && d4 <= d3) return Dot3(bp, bp);
  // Edge region AB.
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = (d1 - d3) > 0 ? d1 / (d1 - d3) : 0.0;
    return dist2_to(a[0] + v * ab[0], a[1] + v * ab[1], a[2] + v * ab[2]);
  }
  // Vertex region C.
  const double cp[3] = {p[0] - c[0], p[1] - c[1], p[2] - c[2]};
  const double d5 = Dot3(ab, cp), d6 = Dot3(ac, cp);
  if (d6 >= 0 && d5 <= d6) return Dot3(cp, cp);
  // Edge region AC.
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = (d2 - d6) > 0 ? d2 / (d2 - d6) : 0.0;
    return dist2_to(a[0] + w * ac[0], a[1] + w * ac[1], a[2] + w * ac[2]);
  }
  // Edge region BC.
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double den = (d4 - d3) + (d5 - d6);
    const double w = den > 0 ? (d4 - d3) / den : 0.0;
    return dist2_to(b[0] + w * (c[0] - b[0]), b[1] + w * (c[1] - b[1]), b[2] + w * (c[2] - b[2]));
  }
  // Face region.
  const double den = va + vb + vc;
  const double v = vb / den, w = vc / den;
  return dist2_to(a[0] + v * ab[0] + w * ac[0], a[1] + v * ab[1] + w * ac[1], a[2] + v * ab[2] + w * ac[2]);
}

}  // namespace contactlab
