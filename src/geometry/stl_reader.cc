// STL reader, ASCII and binary. Binary is recognised by its size (84 + 50 n bytes for n
// triangles), so binary files whose 80-byte header starts with "solid" are read correctly.
// STL repeats every vertex per facet: vertices are welded by exact position afterwards.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "geometry/line_scanner.h"
#include "geometry/mesh_readers.h"
#include "geometry/weld_vertices.h"

namespace contactlab::internal {
namespace {

constexpr std::size_t kHeaderBytes = 84;   // 80-byte header + uint32 triangle count
constexpr std::size_t kRecordBytes = 50;   // normal, 3 vertices (float32), uint16 attribute

template <typename T>
T LoadLittleEndian(const char* p) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, p, sizeof(T));
  if constexpr (std::endian::native == std::endian::big) std::reverse(bytes, bytes + sizeof(T));
  T v;
  std::memcpy(&v, bytes, sizeof(T));
  return v;
}

bool StartsWithSolid(std::string_view bytes) {
  std::size_t i = 0;
  while (i < bytes.size() && (bytes[i] == ' ' || bytes[i] == '\t' || bytes[i] == '\r' || bytes[i] == '\n')) ++i;
  return bytes.substr(i, 5) == "solid";
}

// True when the first few hundred bytes contain a byte that no ASCII STL holds.
bool HasBinaryBytes(std::string_view bytes) {
  const std::string_view head = bytes.substr(0, 512);
  return std::any_of(head.begin(), head.end(), [](char c) {
    const unsigned char u = static_cast<unsigned char>(c);
    return u == 0 || (u < 32 && u != '\n' && u != '\r' && u != '\t' && u != '\f' && u != '\v') || u >= 127;
  });
}

std::string RecordWhere(std::string_view file, std::uint64_t record, std::uint64_t offset) {
  return std::string(file) + " (binary STL triangle " + std::to_string(record) + ", byte offset " +
         std::to_string(offset) + ")";
}

TriangleMesh ReadBinaryStl(std::string_view bytes, std::string_view file) {
  if (bytes.size() < kHeaderBytes) {
    Fail(file, "truncated binary STL: " + std::to_string(bytes.size()) +
                   " bytes, shorter than the 84-byte header and triangle count");
  }
  const std::uint64_t count = LoadLittleEndian<std::uint32_t>(bytes.data() + 80);
  const std::uint64_t complete = (bytes.size() - kHeaderBytes) / kRecordBytes;
  if (complete < count) {
    const std::uint64_t offset = kHeaderBytes + complete * kRecordBytes;
    Fail(RecordWhere(file, complete, offset),
         "truncated: the header declares " + std::to_string(count) + " triangles (" +
             std::to_string(kHeaderBytes + count * kRecordBytes) + " bytes) but the file has " +
             std::to_string(bytes.size()) + " bytes");
  }
  // Trailing bytes beyond the declared triangles are ignored (some exporters pad files).
  TriangleMesh mesh;
  mesh.vertices.reserve(3 * count);
  mesh.triangles.reserve(count);
  for (std::uint64_t t = 0; t < count; ++t) {
    const std::uint64_t offset = kHeaderBytes + t * kRecordBytes;
    const char* record = bytes.data() + offset;
    for (int k = 0; k < 3; ++k) {
      Eigen::Vector3d p;
      for (int a = 0; a < 3; ++a) p[a] = LoadLittleEndian<float>(record + 12 + 12 * k + 4 * a);
      if (!p.allFinite()) Fail(RecordWhere(file, t, offset), "vertex " + std::to_string(k) + " is not finite");
      mesh.vertices.push_back(p);
    }
    const int base = static_cast<int>(3 * t);
    mesh.triangles.emplace_back(base, base + 1, base + 2);
  }
  return mesh;
}

// solid NAME / facet normal nx ny nz / outer loop / vertex x y z (3 or more) / endloop /
// endfacet / endsolid NAME; several solids may follow each other.
TriangleMesh ReadAsciiStl(std::string_view text, std::string_view file) {
  TriangleMesh mesh;
  LineScanner scanner(text, file);
  std::vector<int> polygon;
  bool in_loop = false;
  long loop_line = 0;
  long facet_line = 0;  // line of the open 'facet', 0 when none is open
  long solid_line = 0;  // line of the open 'solid', 0 when none is open
  long last_line = 0;
  while (scanner.NextLine()) {
    last_line = scanner.line_number();
    const std::string_view key = scanner.NextToken();
    if (key.empty()) continue;
    if (key == "vertex") {
      if (!in_loop) scanner.Fail("'vertex' outside an 'outer loop'");
      const double x = scanner.ReadDouble("vertex x coordinate");
      const double y = scanner.ReadDouble("vertex y coordinate");
      const double z = scanner.ReadDouble("vertex z coordinate");
      polygon.push_back(static_cast<int>(mesh.vertices.size()));
      mesh.vertices.emplace_back(x, y, z);
    } else if (key == "outer") {
      if (in_loop) scanner.Fail("'outer loop' inside another loop");
      in_loop = true;
      loop_line = scanner.line_number();
      polygon.clear();
    } else if (key == "endloop") {
      if (!in_loop) scanner.Fail("'endloop' without 'outer loop'");
      if (polygon.size() < 3) {
        scanner.Fail("facet with " + std::to_string(polygon.size()) + " vertices (at least 3 needed)");
      }
      AppendFan(polygon.data(), static_cast<int>(polygon.size()), &mesh);
      in_loop = false;
    } else if (key == "facet") {
      // Structure only; facet normals are recomputed from the vertices.
      if (facet_line != 0) scanner.Fail("'facet' before the 'endfacet' of the facet on line " + std::to_string(facet_line));
      facet_line = scanner.line_number();
    } else if (key == "endfacet") {
      if (in_loop) scanner.Fail("'endfacet' inside an 'outer loop' (missing 'endloop')");
      facet_line = 0;
    } else if (key == "solid") {
      solid_line = scanner.line_number();
    } else if (key == "endsolid") {
      if (facet_line != 0) scanner.Fail("'endsolid' inside the facet opened on line " + std::to_string(facet_line));
      solid_line = 0;
    } else {
      scanner.Fail("unexpected '" + QuoteToken(key) + "' in ASCII STL");
    }
  }
  if (in_loop) FailAtLine(file, loop_line, "truncated: the file ends inside this 'outer loop'");
  // A file cut between facets still parses line by line: only the closing keywords tell.
  if (facet_line != 0) {
    FailAtLine(file, last_line, "truncated: the file ends inside the facet opened on line " + std::to_string(facet_line));
  }
  if (solid_line != 0) {
    FailAtLine(file, last_line,
               "truncated: the file ends without the 'endsolid' closing the 'solid' on line " + std::to_string(solid_line));
  }
  return mesh;
}

}  // namespace

TriangleMesh ReadStl(std::string_view bytes, std::string_view file) {
  // Binary when the size matches the declared count; ASCII when it starts with "solid" and
  // looks like text; otherwise binary (and a size mismatch is reported as truncation).
  bool binary = true;
  if (bytes.size() >= kHeaderBytes) {
    const std::uint64_t count = LoadLittleEndian<std::uint32_t>(bytes.data() + 80);
    const bool size_matches = bytes.size() == kHeaderBytes + count * kRecordBytes;
    binary = size_matches || !StartsWithSolid(bytes) || HasBinaryBytes(bytes);
  } else {
    binary = !StartsWithSolid(bytes);
  }
  TriangleMesh mesh = binary ? ReadBinaryStl(bytes, file) : ReadAsciiStl(bytes, file);
  if (mesh.triangles.empty()) Fail(file, "no facets: the mesh has no triangles");
  return WeldExactDuplicateVertices(mesh);
}

}  // namespace contactlab::internal
