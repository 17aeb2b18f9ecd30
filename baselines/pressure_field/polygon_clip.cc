// Clipping the contact surface's polygons to the bodies' insides (polygon_clip.h).
#include "baselines/pressure_field/polygon_clip.h"

namespace contactlab {
namespace {

// Clips the convex polygon IN (N vertices) to the side where the field SELECTed is <= 0; OUT
// holds up to N + 1 vertices. Returns their number.
template <class Select>
int ClipInside(const PolyVertex* in, int n, Select value, PolyVertex* out) {
  int m = 0;
  for (int i = 0; i < n; ++i) {
    const PolyVertex& a = in[i];
    const PolyVertex& b = in[(i + 1) % n];
    const double va = value(a), vb = value(b);
    if (va <= 0) out[m++] = a;
    if ((va <= 0) != (vb <= 0)) out[m++] = Lerp(a, b, va / (va - vb));
  }
  return m;
}

}  // namespace

const PolyVertex* ClipToOverlap(PolyVertex (&buffers)[2][kMaxPolygon], int* m) {
  *m = ClipInside(buffers[0], *m, [](const PolyVertex& v) { return v.phi_M + v.phi_L; }, buffers[1]);
  return buffers[1];
}

}  // namespace contactlab
