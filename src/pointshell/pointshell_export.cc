// PLY / CSV export of a pointshell level (Barbič & James 2008, sec. 2.4).
#include "pointshell/pointshell_export.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <string>
#include <vector>

#include "util/atomic_file.h"
#include "util/error.h"
#include "util/number_text.h"

namespace contactlab {

void ExportPointshell(const Pointshell& s, int level, const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (ext != ".ply" && ext != ".csv") Fail(path.string(), "unknown export format (expected .ply or .csv)");
  if (level < 0 || level >= s.num_levels()) {
    Fail(path.string(), "level " + std::to_string(level) + " is outside [0, " + std::to_string(s.num_levels()) + ")");
  }
  const std::int32_t n = s.level_point_end[level];
  if (ext == ".ply") {
    WriteFileAtomically(path, [&](std::ostream& out) {
      out << "ply\nformat ascii 1.0\ncomment contactlab pointshell level " << level << " (method " << s.method
          << ", inward normals)\nelement vertex " << n
          << "\nproperty float x\nproperty float y\nproperty float z\nproperty float nx\nproperty float ny\n"
             "property float nz\nend_header\n";
      std::string text;
      for (std::int32_t i = 0; i < n; ++i) {
        const std::string what = "point " + std::to_string(i);
        const float values[6] = {s.x[i], s.y[i], s.z[i], s.nx[i], s.ny[i], s.nz[i]};
        for (int c = 0; c < 6; ++c) {
          AppendNumber(values[c], &text, what);
          text += c < 5 ? ' ' : '\n';
        }
      }
      out << text;
    });
    return;
  }
  // CSV: introduction level, parent point of the first instance, radius on LEVEL.
  std::vector<int> intro(n, 0);
  for (int l = s.num_levels() - 1; l >= 0; --l)
    for (std::int32_t i = 0; i < std::min(n, s.level_point_end[l]); ++i) intro[i] = l;
  std::vector<std::int32_t> parent(n, -1);
  std::vector<float> radius(n, 0.f);
  for (int l = 0; l <= level; ++l) {
    for (std::int32_t node = s.level_node_begin[l]; node < s.level_node_begin[l + 1]; ++node) {
      const std::int32_t p = s.node_point[node];
      if (intro[p] == l && s.node_parent[node] >= 0) parent[p] = s.node_point[s.node_parent[node]];
      if (l == level) radius[p] = s.node_radius[node];
    }
  }
  WriteFileAtomically(path, [&](std::ostream& out) {
    std::string text = "x,y,z,nx,ny,nz,level,parent,radius\n";
    for (std::int32_t i = 0; i < n; ++i) {
      const std::string what = "point " + std::to_string(i);
      for (const float v : {s.x[i], s.y[i], s.z[i], s.nx[i], s.ny[i], s.nz[i]}) {
        AppendNumber(v, &text, what);
        text += ',';
      }
      text += std::to_string(intro[i]) + ',' + std::to_string(parent[i]) + ',';
      AppendNumber(radius[i], &text, what + " radius");
      text += '\n';
    }
    out << text;
  });
}

}  // namespace contactlab
