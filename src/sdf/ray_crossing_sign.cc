// Signed ray crossings along grid lines with a majority vote (Barbič & James 2008, sec. 2.3).
#include "sdf/ray_crossing_sign.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include "util/progress.h"

namespace contactlab {
namespace {

// A vertex in grid units: U, V across the lines (axes b, c), W along them (axis a).
struct Projected {
  double u, v, w;
};

// Edge function of the directed edge P->Q at (X, Y), evaluated in a canonical vertex order so
// that the reversed edge yields exactly the negated value (one code site, no contraction
// differences: the build uses ISO C++ mode, where GCC does not fuse multiply-adds).
double EdgeFunction(const Projected& p, const Projected& q, double x, double y) {
  const bool swap = (q.u < p.u) || (q.u == p.u && q.v < p.v);
  const Projected& s = swap ? q : p;
  const Projected& e = swap ? p : q;
  const double f = (e.u - s.u) * (y - s.v) - (e.v - s.v) * (x - s.u);
  return swap ? -f : f;
}

// Top-left tie rule: true for exactly one of the directions D and -D (D != 0).
bool OwnsEdge(double du, double dv) { return dv > 0 || (dv == 0 && du < 0); }

struct Crossing {
  int line;   // index of the line within the task (the Q coordinate)
  double t;   // position along the line, grid units
  int sign;   // +1 or -1 by the triangle's facing
};

// Adds one inside vote per grid point for the lines along axis A.
void VoteAlongAxis(const TriangleMesh& mesh, const FieldGrid& grid, int a, std::vector<std::uint8_t>& votes,
                   Progress* progress) {
  const int b = (a + 1) % 3, c = (a + 2) % 3;
  // Parallel over the line coordinate that is slowest in memory, so tasks write apart.
  const int P = (a == 2) ? 1 : 2;
  const int Q = (P == b) ? c : b;
  const int np = grid.dims[P], nq = grid.dims[Q], na = grid.dims[a];
  const double h = grid.spacing;

  // Projected vertices (computed once per vertex, so shared vertices are bit-identical).
  std::vector<Projected> pv(mesh.vertices.size());
  for (std::size_t n = 0; n < pv.size(); ++n) {
    const Eigen::Vector3d g = (mesh.vertices[n] - grid.origin) / h;
    pv[n] = {g[b], g[c], g[a]};
  }
  // Triangles bucketed by the P lines they may cross.
  auto coord_p = [&](const Projected& x) { return P == b ? x.u : x.v; };
  auto coord_q = [&](const Projected& x) { return Q == b ? x.u : x.v; };
  const int num_tri = mesh.num_triangles();
  std::vector<std::array<int, 4>> range(num_tri);  // p_lo, p_hi, q_lo, q_hi
  std::vector<std::int64_t> start(np + 1, 0);
  for (int t = 0; t < num_tri; ++t) {
    const auto& f = mesh.triangles[t];
    const Projected& x0 = pv[f[0]];
    const Projected& x1 = pv[f[1]];
    const Projected& x2 = pv[f[2]];
    const double plo = std::min({coord_p(x0), coord_p(x1), coord_p(x2)});
    const double phi = std::max({coord_p(x0), coord_p(x1), coord_p(x2)});
    const double qlo = std::min({coord_q(x0), coord_q(x1), coord_q(x2)});
    const double qhi = std::max({coord_q(x0), coord_q(x1), coord_q(x2)});
    range[t] = {int(std::clamp(std::ceil(plo), 0.0, double(np))), int(std::clamp(std::floor(phi), -1.0, double(np - 1))),
                int(std::clamp(std::ceil(qlo), 0.0, double(nq))), int(std::clamp(std::floor(qhi), -1.0, double(nq - 1)))};
    if (range[t][2] > range[t][3]) range[t][1] = range[t][0] - 1;  // no line
    for (int p = range[t][0]; p <= range[t][1]; ++p) ++start[p + 1];
  }
  for (int p = 0; p < np; ++p) start[p + 1] += start[p];
  std::vector<std::int32_t> bucket(start[np]);
  {
    std::vector<std::int64_t> fill(start.begin(), start.end() - 1);
    for (int t = 0; t < num_tri; ++t)
      for (int p = range[t][0]; p <= range[t][1]; ++p) bucket[fill[p]++] = t;
  }

  tbb::parallel_for(0, np, [&](int p) {
    std::vector<Crossing> crossings;
    for (std::int64_t e = start[p]; e < start[p + 1]; ++e) {
      const int t = bucket[e];
      const auto& f = mesh.triangles[t];
      const Projected* x[3] = {&pv[f[0]], &pv[f[1]], &pv[f[2]]};
      for (int q = range[t][2]; q <= range[t][3]; ++q) {
        const double qu = (P == b) ? p : q, qv = (P == b) ? q : p;
        double E[3];
        bool pos[3];
        bool degenerate = false;
        for (int k = 0; k < 3; ++k) {
          const Projected& s = *x[k];
          const Projected& d = *x[(k + 1) % 3];
          const double du = d.u - s.u, dv = d.v - s.v;
          if (du == 0 && dv == 0) degenerate = true;
          E[k] = EdgeFunction(s, d, qu, qv);
          pos[k] = E[k] > 0 || (E[k] == 0 && OwnsEdge(du, dv));
        }
        if (degenerate || pos[0] != pos[1] || pos[1] != pos[2]) continue;
        // E[k] belongs to edge k -> k+1, i.e. to the barycentric weight of vertex k+2.
        const double sum = E[0] + E[1] + E[2];
        const double tt = (E[1] * x[0]->w + E[2] * x[1]->w + E[0] * x[2]->w) / sum;
        if (!std::isfinite(tt)) continue;
        crossings.push_back({q, tt, pos[0] ? 1 : -1});
      }
    }
    std::sort(crossings.begin(), crossings.end(), [](const Crossing& l, const Crossing& r) {
      return l.line != r.line ? l.line < r.line : l.t < r.t;
    });
    // Walk each line: the running sum of crossings before a point is its winding number.
    std::size_t n = 0;
    while (n < crossings.size()) {
      const int q = crossings[n].line;
      std::size_t end = n;
      while (end < crossings.size() && crossings[end].line == q) ++end;
      int winding = 0;
      std::size_t next = n;
      Eigen::Vector3i ijk;
      ijk[P] = p;
      ijk[Q] = q;
      for (int i = 0; i < na; ++i) {
        while (next < end && crossings[next].t < i) winding += crossings[next++].sign;
        if (winding != 0) {
          ijk[a] = i;
          votes[grid.Index(ijk.x(), ijk.y(), ijk.z())] += 1;
        }
        if (next == end && winding == 0) break;
      }
      n = end;
    }
    if (progress) progress->Advance();
  });
}

}  // namespace

std::vector<std::uint8_t> ClassifyInsideByRayCrossings(const TriangleMesh& mesh, const FieldGrid& grid,
                                                       bool show_progress) {
  std::vector<std::uint8_t> votes(grid.num_points(), 0);
  std::optional<Progress> progress;
  if (show_progress) progress.emplace("distance field: sign", std::int64_t(2) * grid.dims.z() + grid.dims.y());
  for (int a = 0; a < 3; ++a) VoteAlongAxis(mesh, grid, a, votes, progress ? &*progress : nullptr);
  if (progress) progress->Finish();
  for (auto& v : votes) v = v >= 2 ? 1 : 0;
  return votes;
}

}  // namespace contactlab
