// The contact surface in one lattice cell: Kuhn tetrahedra, their cut by the gap's zero set,
// clipping and integration (cell_surface.h; Elandt et al. 2019).
#include "baselines/pressure_field/cell_surface.h"

namespace contactlab {
namespace {

// The six Kuhn tetrahedra of a cube: corners by bit (x = 1, y = 2, z = 4), each from corner 0 to
// corner 7 along the axes in one order.
constexpr int kTets[6][4] = {{0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7}, {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7}};

// The zero set of the gap on tetrahedron TET of CELL, written to POLY: a triangle when one
// corner is alone on its side, else a quad. Returns its vertex count, 0 when the gap keeps one
// sign. *TOWARD: from the positive corners' mean to the others', the way g decreases.
int CutTetrahedron(const LatticeCell& cell, const int* tet, PolyVertex* poly, Eigen::Vector3d* toward,
                   VertexOrigin* origin) {
  const double* g = cell.g;
  int pos[4], neg[4], np = 0, nn = 0;
  for (int t = 0; t < 4; ++t) (g[tet[t]] > 0 ? pos[np++] : neg[nn++]) = tet[t];
  if (np == 0 || nn == 0) return 0;
  int m = 0;
  auto cut = [&](int p, int q) {
    const double t = g[p] / (g[p] - g[q]);
    if (origin) origin[m] = {p, q, t};
    poly[m++] = Lerp(cell.corner[p], cell.corner[q], t);
  };
  if (np == 1) {
    for (int t = 0; t < 3; ++t) cut(pos[0], neg[t]);
  } else if (nn == 1) {
    for (int t = 0; t < 3; ++t) cut(pos[t], neg[0]);
  } else {
    cut(pos[0], neg[0]);
    cut(pos[0], neg[1]);
    cut(pos[1], neg[1]);
    cut(pos[1], neg[0]);
  }
  *toward = Eigen::Vector3d::Zero();
  for (int t = 0; t < nn; ++t) *toward += cell.corner[neg[t]].x / nn;
  for (int t = 0; t < np; ++t) *toward -= cell.corner[pos[t]].x / np;
  return m;
}

// A cell's corners by bit (x = 1, y = 2, z = 4) as offsets from its first vertex in a block.
constexpr int kCornerOffset[8] = {0, 1, kVerts, kVerts + 1, kVerts * kVerts, kVerts * kVerts + 1,
                                  kVerts * kVerts + kVerts, kVerts * kVerts + kVerts + 1};

}  // namespace

void LoadBlockVertices(const float* phi_M, const float* phi_L, const PressureLaw& law, BlockVertices* v) {
  for (int i = 0; i < kBlockVerts; ++i) {
    const double pm = phi_M[i], pl = phi_L[i];
    const double g = law.Gap(pm, pl);
    v->g[i] = g;
    v->flags[i] =
        std::uint8_t((g > 0 ? kGapPositive : 0) | (pm > 0 ? kOutsideM : 0) | (pl > 0 ? kOutsideL : 0) |
                     (pm + pl <= 0 ? kOverlapped : 0));
  }
}

CellFlags CornerFlags(const BlockVertices& v, int ci, int cj, int ck) {
  const std::uint8_t* f = v.flags + VertexIndex(ci, cj, ck);
  CellFlags out{0xFF, 0};
  for (const int off : kCornerOffset) {
    out.all &= f[off];
    out.any |= f[off];
  }
  return out;
}

bool MayHoldSurface(CellFlags f, bool clip_M, bool clip_L) {
  return (f.any & kGapPositive) && !(f.all & kGapPositive) && !(clip_M && (f.all & kOutsideM)) &&
         !(clip_L && (f.all & kOutsideL));
}

int CellCornerVertex(int ci, int cj, int ck, int c) { return VertexIndex(ci, cj, ck) + kCornerOffset[c]; }

void LoadCell(const float* phi_M, const float* phi_L, const BlockVertices& v, const Eigen::Vector3d& x0, double h,
              int ci, int cj, int ck, LatticeCell* cell) {
  const int v0 = VertexIndex(ci, cj, ck);
  std::uint8_t overlapped_at = 0;
  for (int c = 0; c < 8; ++c) {
    const int i = v0 + kCornerOffset[c];
    PolyVertex& corner = cell->corner[c];
    corner.phi_M = phi_M[i];
    corner.phi_L = phi_L[i];
    corner.x = x0 + h * Eigen::Vector3d(ci + (c & 1), cj + ((c >> 1) & 1), ck + ((c >> 2) & 1));
    cell->g[c] = v.g[i];
    overlapped_at |= (v.flags[i] & kOverlapped) ? std::uint8_t(1 << c) : 0;
  }
  cell->overlapped_at = overlapped_at;
}

double IntegrateCell(const LatticeCell& cell, const PressureLaw& law, PressureSums* sums, SurfaceRecord* record,
                     CornerSensitivity* b) {
  double cell_area = 0;
  VertexOrigin cut_origin[kMaxPolygon], clip_origin[kMaxPolygon];
  const bool adjoints = b != nullptr;
  for (const auto& tet : kTets) {
    PolyVertex buffers[2][kMaxPolygon];
    Eigen::Vector3d toward;
    int m = CutTetrahedron(cell, tet, buffers[0], &toward, adjoints ? cut_origin : nullptr);
    if (m == 0) continue;
    const int cut_vertices = m;
    // A tetrahedron whose corners all overlap overlaps throughout (the fields are linear on
    // it): nothing to clip.
    const int corners = (1 << tet[0]) | (1 << tet[1]) | (1 << tet[2]) | (1 << tet[3]);
    const bool inside = (cell.overlapped_at & corners) == corners;
    const PolyVertex* poly = inside ? buffers[0] : ClipToOverlap(buffers, &m, adjoints ? clip_origin : nullptr);
    if (m < 3) continue;
    const double sign = IntegratePolygon(poly, m, toward, law, sums, &cell_area, record);
    if (adjoints && inside) {
      CutPolygonAdjoints(cell, poly, m, sign, law, cut_origin, b);  // no clip: one pass
    } else if (adjoints) {
      // Backwards: the integration, the clip, the cut.
      VertexAdjoint adjoint[kMaxPolygon], cut[kMaxPolygon];
      PolygonAdjoints(poly, m, sign, law, adjoint);
      for (int i = 0; i < cut_vertices; ++i) {
        cut[i].x.setZero();
        cut[i].s.setZero();
      }
      ClipAdjoints(buffers[0], clip_origin, adjoint, m, cut);
      CutAdjoints(cell, law, cut_origin, cut, cut_vertices, b);
    }
  }
  return cell_area;
}

}  // namespace contactlab
