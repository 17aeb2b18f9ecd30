#include "scene/reduced_coordinates.h"

#include <cmath>
#include <cstdio>
#include <vector>

#include "scene/scene_assets.h"
#include "geometry/triangle_mesh.h"
#include "util/atomic_file.h"
#include "util/error.h"
#include "util/parse_number.h"

namespace contactlab {

ReducedState ParseReducedCoordinates(const std::string& text, BodyAssets& body, const std::string& option) {
  const std::string who = option + " (body '" + body.spec().name + "')";
  if (!body.deformable()) Fail(who, "the body is rigid: it has no deformable block, so it takes no q");
  std::string values = text;
  std::string source = who;
  if (!text.empty() && text[0] == '@') {
    const std::string file = text.substr(1);
    try {
      values = ReadWholeFile(file);
    } catch (const Error& e) {
      Fail(who, std::string("cannot read the q file: ") + e.what());
    }
    source = who + " file " + file;
  }
  // Comments out, then split on commas and white space.
  std::vector<std::string> tokens;
  std::string token;
  bool comment = false;
  for (const char c : values + "\n") {
    if (c == '\n') comment = false;
    if (c == '#') comment = true;
    const bool separator = comment || c == ',' || c == ' ' || c == '\t' || c == '\n' || c == '\r';
    if (!separator) {
      token += c;
    } else if (!token.empty()) {
      tokens.push_back(token);
      token.clear();
    }
  }
  // Each value a finite number first, so that "hello" is named as what it is, not counted.
  const int r = body.reduced_model()->r();
  ReducedState state(r);
  for (std::size_t j = 0; j < tokens.size(); ++j) {
    const std::optional<double> v = ParseDouble(tokens[j]);
    if (!v) {
      Fail(source, "value " + std::to_string(j + 1) + " '" + QuoteToken(tokens[j]) + "' is not a finite number");
    }
    if (int(j) < r) state.q[int(j)] = *v;
  }
  if (int(tokens.size()) != r) {
    Fail(source, std::to_string(tokens.size()) + " values given; the body has r = " + std::to_string(r) +
                     " reduced coordinates");
  }
  // Finite coordinates may still deform the body beyond what doubles hold (q = 1e308): every
  // node's displacement U_v q, its squared length and its displaced position must be finite.
  // And within the coordinates ContactLab accepts anywhere (kMaxCoordinate, the mesh readers'
  // limit): q = 1e30 exported a mesh of 1e30 m that no command would read back, and squared
  // distances of such points overflow.
  const auto model = body.reduced_model();
  const Eigen::VectorXd u = model->basis * state.q;
  for (int v = 0; v < model->mesh.num_vertices(); ++v) {
    const Eigen::Vector3d u_v = u.segment<3>(3 * v);
    const Eigen::Vector3d x_v = model->mesh.vertices[v] + u_v;
    if (!u_v.allFinite() || !std::isfinite(u_v.squaredNorm()) || !x_v.allFinite()) {
      Fail(source, "these coordinates deform the body beyond finite numbers (node " + std::to_string(v) +
                       " moves by " + std::to_string(u_v.norm()) + " m); give smaller values");
    }
    if (!(x_v.cwiseAbs().maxCoeff() <= kMaxCoordinate)) {
      char at[64];
      std::snprintf(at, sizeof at, "%.3g", x_v.cwiseAbs().maxCoeff());
      Fail(source, "these coordinates move node " + std::to_string(v) + " of the simulation mesh to |coordinate| " +
                       at + " m, beyond the 1e9 m every mesh, field and body must stay within (the mesh "
                       "readers' limit, kMaxCoordinate); give smaller values");
    }
  }
  return state;
}

}  // namespace contactlab
