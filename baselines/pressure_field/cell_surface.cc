// The contact surface in one lattice cell: Kuhn tetrahedra, their cut by the gap's zero set,
// clipping and integration (cell_surface.h; Elandt et al. 2019).
#include "baselines/pressure_field/cell_surface.h"

#include "baselines/pressure_field/lattice_blocks.h"

namespace contactlab {
namespace {

// The six Kuhn tetrahedra of a cube: corners by bit (x = 1, y = 2, z = 4), each from corner 0 to
// corner 7 along the axes in one order.
constexpr int kTets[6][4] = {{0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7}, {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7}};

// The zero set of the gap on tetrahedron TET of CELL, written to POLY: a triangle when one
// corner is alone on its side, else a quad. Returns its vertex count, 0 when the gap keeps one
// sign. *TOWARD: from the positive corners' mean to the others', the way g decreases.
int CutTetrahedron(const LatticeCell& cell, const int* tet, PolyVertex* poly, Eigen::Vector3d* toward) {
  const double* g = cell.g;
  int pos[4], neg[4], np = 0, nn = 0;
  for (int t = 0; t < 4; ++t) (g[tet[t]] > 0 ? pos[np++] : neg[nn++]) = tet[t];
  if (np == 0 || nn == 0) return 0;
  int m = 0;
  auto cut = [&](int p, int q) { return Lerp(cell.corner[p], cell.corner[q], g[p] / (g[p] - g[q])); };
  if (np == 1) {
    for (int t = 0; t < 3; ++t) poly[m++] = cut(pos[0], neg[t]);
  } else if (nn == 1) {
    for (int t = 0; t < 3; ++t) poly[m++] = cut(pos[t], neg[0]);
  } else {
    poly[m++] = cut(pos[0], neg[0]);
    poly[m++] = cut(pos[0], neg[1]);
    poly[m++] = cut(pos[1], neg[1]);
    poly[m++] = cut(pos[1], neg[0]);
  }
  *toward = Eigen::Vector3d::Zero();
  for (int t = 0; t < nn; ++t) *toward += cell.corner[neg[t]].x / nn;
  for (int t = 0; t < np; ++t) *toward -= cell.corner[pos[t]].x / np;
  return m;
}

}  // namespace

bool LoadCell(const float* phi_M, const float* phi_L, int ci, int cj, int ck, const PressureLaw& law, bool clip_M,
              bool clip_L, LatticeCell* cell) {
  cell->positive = 0;
  cell->outside_M = cell->outside_L = cell->overlapped = true;
  for (int c = 0; c < 8; ++c) {
    const int di = c & 1, dj = (c >> 1) & 1, dk = (c >> 2) & 1;
    const int v = VertexIndex(ci + di, cj + dj, ck + dk);
    PolyVertex& corner = cell->corner[c];
    corner.phi_M = phi_M[v];
    corner.phi_L = phi_L[v];
    cell->g[c] = law.Gap(corner.phi_M, corner.phi_L);
    cell->positive += cell->g[c] > 0;
    cell->outside_M = cell->outside_M && corner.phi_M > 0;
    cell->outside_L = cell->outside_L && corner.phi_L > 0;
    cell->overlapped = cell->overlapped && corner.phi_M + corner.phi_L <= 0;
  }
  return !(cell->positive == 0 || cell->positive == 8 || (clip_M && cell->outside_M) || (clip_L && cell->outside_L));
}

void PlaceCorners(const Eigen::Vector3d& x0, double h, int ci, int cj, int ck, LatticeCell* cell) {
  for (int c = 0; c < 8; ++c) {
    cell->corner[c].x = x0 + h * Eigen::Vector3d(ci + (c & 1), cj + ((c >> 1) & 1), ck + ((c >> 2) & 1));
  }
}

double IntegrateCell(const LatticeCell& cell, const PressureLaw& law, PressureSums* sums, SurfaceRecord* record) {
  double cell_area = 0;
  for (const auto& tet : kTets) {
    PolyVertex buffers[2][kMaxPolygon];
    Eigen::Vector3d toward;
    int m = CutTetrahedron(cell, tet, buffers[0], &toward);
    if (m == 0) continue;
    // A cell where the bodies overlap at every corner overlaps throughout (the fields are
    // linear on each tetrahedron): nothing to clip.
    const PolyVertex* poly = cell.overlapped ? buffers[0] : ClipToOverlap(buffers, &m);
    if (m < 3) continue;
    IntegratePolygon(poly, m, toward, law, sums, &cell_area, record);
  }
  return cell_area;
}

}  // namespace contactlab
