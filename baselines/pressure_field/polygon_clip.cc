// Clipping the contact surface's polygons to the bodies' insides (polygon_clip.h).
#include "baselines/pressure_field/polygon_clip.h"

namespace contactlab {
namespace {

// Clips the convex polygon IN (N vertices) to the side where the field SELECTed is <= 0; OUT
// holds up to N + 1 vertices. Returns their number.
template <class Select>
int ClipInside(const PolyVertex* in, int n, Select value, PolyVertex* out, VertexOrigin* origin) {
  int m = 0;
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    const PolyVertex& a = in[i];
    const PolyVertex& b = in[j];
    const double va = value(a), vb = value(b);
    if (va <= 0) {
      if (origin) origin[m] = {i, -1, 0.0};
      out[m++] = a;
    }
    if ((va <= 0) != (vb <= 0)) {
      const double t = va / (va - vb);
      if (origin) origin[m] = {i, j, t};
      out[m++] = Lerp(a, b, t);
    }
  }
  return m;
}

}  // namespace

const PolyVertex* ClipToOverlap(PolyVertex (&buffers)[2][kMaxPolygon], int* m, VertexOrigin* origin) {
  *m = ClipInside(buffers[0], *m, [](const PolyVertex& v) { return v.phi_M + v.phi_L; }, buffers[1], origin);
  return buffers[1];
}

}  // namespace contactlab
