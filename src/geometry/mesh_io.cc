// LoadMesh / SaveMesh: format dispatch by extension, the load-time scale and pose, and the
// writers (OBJ, OFF, binary STL, binary PLY). The readers live in *_reader.cc.
#include "geometry/mesh_io.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>

#include "geometry/mesh_readers.h"
#include "util/atomic_file.h"
#include "util/error.h"
#include "util/gzip_file.h"
#include "util/number_text.h"

namespace contactlab {
namespace {

std::string LowerExtension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

void AppendInt(long long v, std::string* out) {
  char buffer[24];
  const auto [ptr, ec] = std::to_chars(buffer, buffer + sizeof(buffer), v);
  out->append(buffer, ptr);
}

// Appends the little-endian bytes of V.
template <typename T>
void AppendLittleEndian(T v, std::string* out) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &v, sizeof(T));
  if constexpr (std::endian::native == std::endian::big) std::reverse(bytes, bytes + sizeof(T));
  out->append(bytes, sizeof(T));
}

void CheckSavable(const TriangleMesh& mesh, const std::filesystem::path& path) {
  const int n = mesh.num_vertices();
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    const Eigen::Vector3i& f = mesh.triangles[t];
    if ((f.array() < 0).any() || (f.array() >= n).any()) {
      Fail(path.string(), "cannot save: triangle " + std::to_string(t) + " has a vertex index out of range");
    }
  }
  // No program reads "inf" or "nan" back as a coordinate, and LoadMesh refuses any beyond
  // kMaxCoordinate: nothing is written that the readers would refuse.
  for (int v = 0; v < n; ++v) {
    if (!mesh.vertices[v].allFinite()) {
      Fail(path.string(), "cannot save: vertex " + std::to_string(v) + " has a non-finite coordinate (" +
                              std::to_string(mesh.vertices[v].x()) + ", " + std::to_string(mesh.vertices[v].y()) +
                              ", " + std::to_string(mesh.vertices[v].z()) + "); nothing written");
    }
    if (!(mesh.vertices[v].cwiseAbs().maxCoeff() <= kMaxCoordinate)) {
      char buf[200];
      std::snprintf(buf, sizeof buf,
                    "cannot save: vertex %d has |coordinate| %.3g m, beyond the %.0e m the mesh readers accept; "
                    "nothing written",
                    v, mesh.vertices[v].cwiseAbs().maxCoeff(), kMaxCoordinate);
      Fail(path.string(), buf);
    }
  }
}

std::string ObjText(const TriangleMesh& mesh) {
  std::string out = "# ContactLab\n";
  out.reserve(mesh.vertices.size() * 60 + mesh.triangles.size() * 24);
  for (const Eigen::Vector3d& p : mesh.vertices) {
    out += "v ";
    AppendNumber(p.x(), &out);
    out += ' ';
    AppendNumber(p.y(), &out);
    out += ' ';
    AppendNumber(p.z(), &out);
    out += '\n';
  }
  for (const Eigen::Vector3i& t : mesh.triangles) {
    out += "f ";
    AppendInt(t[0] + 1, &out);
    out += ' ';
    AppendInt(t[1] + 1, &out);
    out += ' ';
    AppendInt(t[2] + 1, &out);
    out += '\n';
  }
  return out;
}

std::string OffText(const TriangleMesh& mesh) {
  std::string out = "OFF\n# ContactLab\n";
  out.reserve(mesh.vertices.size() * 60 + mesh.triangles.size() * 24);
  AppendInt(mesh.num_vertices(), &out);
  out += ' ';
  AppendInt(mesh.num_triangles(), &out);
  out += " 0\n";
  for (const Eigen::Vector3d& p : mesh.vertices) {
    AppendNumber(p.x(), &out);
    out += ' ';
    AppendNumber(p.y(), &out);
    out += ' ';
    AppendNumber(p.z(), &out);
    out += '\n';
  }
  for (const Eigen::Vector3i& t : mesh.triangles) {
    out += "3 ";
    AppendInt(t[0], &out);
    out += ' ';
    AppendInt(t[1], &out);
    out += ' ';
    AppendInt(t[2], &out);
    out += '\n';
  }
  return out;
}

// Binary STL: 80-byte header (not starting with "solid"), uint32 count, 50 bytes per
// triangle (float normal, 3 float vertices, uint16 attribute). Positions are rounded to float.
std::string StlBytes(const TriangleMesh& mesh) {
  std::string out(80, ' ');
  const std::string title = "ContactLab binary STL: " + mesh.name;
  out.replace(0, std::min<std::size_t>(title.size(), 80), title.substr(0, 80));
  out.reserve(84 + 50 * mesh.triangles.size());
  AppendLittleEndian<std::uint32_t>(static_cast<std::uint32_t>(mesh.triangles.size()), &out);
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    const Eigen::Vector3d n = mesh.FaceNormal(t);
    for (int a = 0; a < 3; ++a) AppendLittleEndian<float>(static_cast<float>(n[a]), &out);
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d& p = mesh.vertices[mesh.triangles[t][k]];
      for (int a = 0; a < 3; ++a) AppendLittleEndian<float>(static_cast<float>(p[a]), &out);
    }
    AppendLittleEndian<std::uint16_t>(0, &out);
  }
  return out;
}

// Binary little-endian PLY: double x y z per vertex, "list uchar int vertex_indices" per face.
std::string PlyBytes(const TriangleMesh& mesh) {
  std::string name = mesh.name;
  std::replace_if(name.begin(), name.end(), [](char c) { return c == '\n' || c == '\r'; }, ' ');
  std::string out = "ply\nformat binary_little_endian 1.0\ncomment ContactLab " + name + "\n";
  out += "element vertex " + std::to_string(mesh.num_vertices()) + "\n";
  out += "property double x\nproperty double y\nproperty double z\n";
  out += "element face " + std::to_string(mesh.num_triangles()) + "\n";
  out += "property list uchar int vertex_indices\nend_header\n";
  out.reserve(out.size() + 24 * mesh.vertices.size() + 13 * mesh.triangles.size());
  for (const Eigen::Vector3d& p : mesh.vertices) {
    for (int a = 0; a < 3; ++a) AppendLittleEndian<double>(p[a], &out);
  }
  for (const Eigen::Vector3i& t : mesh.triangles) {
    AppendLittleEndian<std::uint8_t>(3, &out);
    for (int k = 0; k < 3; ++k) AppendLittleEndian<std::int32_t>(t[k], &out);
  }
  return out;
}

}  // namespace

TriangleMesh LoadMesh(const std::filesystem::path& path, const MeshLoadOptions& options) {
  const std::string file = path.string();
  // Options and format first, so a bad call fails before reading anything.
  if (!(options.scale > 0) || !std::isfinite(options.scale)) {
    Fail(file, "load scale must be positive and finite, got " + std::to_string(options.scale));
  }
  if (!options.rotation.allFinite() || !options.translation.allFinite()) {
    Fail(file, "load rotation and translation must be finite");
  }
  // A ".gz" name holds the format named before it ("dragon.obj.gz").
  const bool gzipped = IsGzipName(path);
  const std::filesystem::path inner = WithoutGzipSuffix(path);
  const std::string ext = LowerExtension(inner);
  if (ext != ".obj" && ext != ".off" && ext != ".stl" && ext != ".ply") {
    Fail(file, "unknown mesh format '" + ext + (gzipped ? ".gz" : "") +
                   "' (expected .obj, .off, .stl or .ply, optionally gzip-compressed as .obj.gz etc.)");
  }
  CheckInputFile(path, "mesh file");
  const std::string bytes = gzipped ? ReadGzipFile(path) : ReadWholeFile(path);

  // Parse.
  TriangleMesh mesh;
  if (ext == ".obj") {
    mesh = internal::ReadObj(bytes, file);
  } else if (ext == ".off") {
    mesh = internal::ReadOff(bytes, file);
  } else if (ext == ".stl") {
    mesh = internal::ReadStl(bytes, file);
  } else {
    mesh = internal::ReadPly(bytes, file);
  }
  mesh.name = inner.filename().string();

  // p <- R (s p - c) + t, c the centre of the scaled bounding box when centring.
  const double s = options.scale;
  const Eigen::Vector3d c = options.center ? Eigen::Vector3d(s * mesh.Bounds().center()) : Eigen::Vector3d::Zero();
  const bool identity = s == 1.0 && !options.center && options.rotation == Eigen::Matrix3d::Identity() &&
                        options.translation.isZero(0);
  if (!identity) {
    for (Eigen::Vector3d& p : mesh.vertices) p = options.rotation * (s * p - c) + options.translation;
  }
  // Finite but huge coordinates (1e30, or a scale of 1e300) overflow later in squared
  // distances; say so here rather than "a sample is not finite" from the field builder.
  double largest = 0;
  for (const Eigen::Vector3d& p : mesh.vertices) largest = std::max(largest, p.cwiseAbs().maxCoeff());
  if (!(largest <= kMaxCoordinate)) {
    char buf[200];
    std::snprintf(buf, sizeof buf, "coordinates out of range: |coordinate| reaches %.3g m%s (the limit is %.0e m)",
                  largest, s != 1.0 ? " after scaling" : "", kMaxCoordinate);
    Fail(file, buf);
  }
  return mesh;
}

void SaveMesh(const TriangleMesh& mesh, const std::filesystem::path& path) {
  const std::string ext = LowerExtension(path);
  if (ext != ".obj" && ext != ".off" && ext != ".stl" && ext != ".ply") {
    Fail(path.string(), "unknown mesh format '" + ext + "' (expected .obj, .off, .stl or .ply)");
  }
  CheckSavable(mesh, path);
  if (ext == ".obj") {
    WriteFileAtomically(path, ObjText(mesh));
  } else if (ext == ".off") {
    WriteFileAtomically(path, OffText(mesh));
  } else if (ext == ".stl") {
    WriteFileAtomically(path, StlBytes(mesh));
  } else {
    WriteFileAtomically(path, PlyBytes(mesh));
  }
}

}  // namespace contactlab
