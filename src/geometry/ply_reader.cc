// PLY reader (ascii, binary_little_endian, binary_big_endian): vertex x, y, z (any scalar
// type) and the face list "vertex_indices" or "vertex_index"; every other element and
// property, list or scalar, is skipped. Polygons are fan-triangulated.
#include <algorithm>
#include <bit>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "geometry/line_scanner.h"
#include "geometry/mesh_readers.h"

namespace contactlab::internal {
namespace {

enum class PlyType { kInt8, kUint8, kInt16, kUint16, kInt32, kUint32, kFloat32, kFloat64 };

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::kFloat32;  // of the values (of the items, for a list)
  bool is_list = false;
  PlyType count_type = PlyType::kUint8;  // lists only
};

struct PlyElement {
  std::string name;
  long long count = 0;
  std::vector<PlyProperty> properties;
};

enum class PlyFormat { kAscii, kBinaryLittleEndian, kBinaryBigEndian };

struct PlyHeader {
  PlyFormat format = PlyFormat::kAscii;
  std::vector<PlyElement> elements;
  std::size_t data_offset = 0;  // first byte after "end_header\n"
  long data_line = 0;           // line number of the first data line (ascii)
};

bool ParseType(std::string_view name, PlyType* type) {
  if (name == "char" || name == "int8") *type = PlyType::kInt8;
  else if (name == "uchar" || name == "uint8") *type = PlyType::kUint8;
  else if (name == "short" || name == "int16") *type = PlyType::kInt16;
  else if (name == "ushort" || name == "uint16") *type = PlyType::kUint16;
  else if (name == "int" || name == "int32") *type = PlyType::kInt32;
  else if (name == "uint" || name == "uint32") *type = PlyType::kUint32;
  else if (name == "float" || name == "float32") *type = PlyType::kFloat32;
  else if (name == "double" || name == "float64") *type = PlyType::kFloat64;
  else return false;
  return true;
}

std::size_t TypeSize(PlyType type) {
  switch (type) {
    case PlyType::kInt8:
    case PlyType::kUint8: return 1;
    case PlyType::kInt16:
    case PlyType::kUint16: return 2;
    case PlyType::kInt32:
    case PlyType::kUint32:
    case PlyType::kFloat32: return 4;
    case PlyType::kFloat64: return 8;
  }
  return 0;
}

bool IsInteger(PlyType type) { return type != PlyType::kFloat32 && type != PlyType::kFloat64; }

PlyHeader ParseHeader(std::string_view bytes, std::string_view file) {
  PlyHeader header;
  LineScanner scanner(bytes, file);
  if (!scanner.NextLine() || scanner.NextToken() != "ply" || !scanner.AtLineEnd()) {
    FailAtLine(file, 1, "not a PLY file: the first line must be 'ply'");
  }
  bool have_format = false;
  while (true) {
    if (!scanner.NextLine()) scanner.Fail("truncated header: no 'end_header' line");
    const std::string_view key = scanner.NextToken();
    if (key == "end_header") {
      header.data_offset = scanner.offset();
      header.data_line = scanner.line_number() + 1;
      break;
    }
    if (key.empty() || key == "comment" || key == "obj_info") continue;
    if (key == "format") {
      const std::string_view format = scanner.NextToken();
      if (format == "ascii") header.format = PlyFormat::kAscii;
      else if (format == "binary_little_endian") header.format = PlyFormat::kBinaryLittleEndian;
      else if (format == "binary_big_endian") header.format = PlyFormat::kBinaryBigEndian;
      else scanner.Fail("unknown PLY format '" + QuoteToken(format) + "'");
      have_format = true;
    } else if (key == "element") {
      PlyElement element;
      // Names are kept as quoted for messages: the ones the reader looks for (vertex, face,
      // x, y, z, vertex_indices, vertex_index) are short plain ASCII, which quoting keeps as is.
      element.name = QuoteToken(scanner.NextToken());
      if (element.name.empty()) scanner.Fail("element without a name");
      element.count = scanner.ReadInt("element count");
      if (element.count < 0 || element.count >= INT_MAX) scanner.Fail("element count out of range");
      header.elements.push_back(std::move(element));
    } else if (key == "property") {
      if (header.elements.empty()) scanner.Fail("property before any element");
      PlyProperty property;
      std::string_view type_name = scanner.NextToken();
      if (type_name == "list") {
        property.is_list = true;
        const std::string_view count_type = scanner.NextToken();
        if (!ParseType(count_type, &property.count_type) || !IsInteger(property.count_type)) {
          scanner.Fail("bad list count type '" + QuoteToken(count_type) + "'");
        }
        type_name = scanner.NextToken();
      }
      if (!ParseType(type_name, &property.type)) scanner.Fail("unknown property type '" + QuoteToken(type_name) + "'");
      property.name = QuoteToken(scanner.NextToken());
      if (property.name.empty()) scanner.Fail("property without a name");
      header.elements.back().properties.push_back(std::move(property));
    } else {
      scanner.Fail("unexpected header line '" + QuoteToken(scanner.line()) + "'");
    }
  }
  if (!have_format) FailAtLine(file, 2, "no 'format' line in the PLY header");
  return header;
}

// Where the mesh lives in the header: the vertex element and its x, y, z properties, and
// the face element and its index list.
struct PlyLayout {
  int vertex_element = -1;
  int xyz[3] = {-1, -1, -1};
  int face_element = -1;
  int face_list = -1;
};

PlyLayout FindLayout(const PlyHeader& header, std::string_view file) {
  PlyLayout layout;
  for (int e = 0; e < static_cast<int>(header.elements.size()); ++e) {
    const PlyElement& element = header.elements[e];
    if (element.name == "vertex" && layout.vertex_element < 0) {
      layout.vertex_element = e;
      for (int p = 0; p < static_cast<int>(element.properties.size()); ++p) {
        const PlyProperty& property = element.properties[p];
        for (int a = 0; a < 3; ++a) {
          if (property.name == std::string(1, char('x' + a)) && !property.is_list) layout.xyz[a] = p;
        }
      }
    } else if (element.name == "face" && layout.face_element < 0) {
      layout.face_element = e;
      for (int p = 0; p < static_cast<int>(element.properties.size()); ++p) {
        const PlyProperty& property = element.properties[p];
        if (property.is_list && (property.name == "vertex_indices" || property.name == "vertex_index")) {
          if (!IsInteger(property.type)) Fail(file, "PLY face index list '" + property.name + "' is not of an integer type");
          layout.face_list = p;
        }
      }
    }
  }
  if (layout.vertex_element < 0) Fail(file, "PLY header has no 'vertex' element");
  if (layout.xyz[0] < 0 || layout.xyz[1] < 0 || layout.xyz[2] < 0) {
    Fail(file, "PLY 'vertex' element lacks one of the scalar properties x, y, z");
  }
  if (layout.face_element < 0) Fail(file, "PLY header has no 'face' element: the mesh has no triangles");
  if (layout.face_list < 0) Fail(file, "PLY 'face' element has no list property 'vertex_indices' or 'vertex_index'");
  return layout;
}

// Reads binary values of any PLY type, swapping bytes when the file's order is not the host's.
class BinaryCursor {
 public:
  BinaryCursor(std::string_view bytes, std::size_t offset, bool swap) : bytes_(bytes), offset_(offset), swap_(swap) {}
  bool Has(std::size_t n) const { return offset_ <= bytes_.size() && bytes_.size() - offset_ >= n; }
  std::size_t offset() const { return offset_; }
  void Skip(std::size_t n) { offset_ += n; }
  // Precondition: Has(TypeSize(type)).
  double ReadDouble(PlyType type) {
    switch (type) {
      case PlyType::kInt8: return Load<std::int8_t>();
      case PlyType::kUint8: return Load<std::uint8_t>();
      case PlyType::kInt16: return Load<std::int16_t>();
      case PlyType::kUint16: return Load<std::uint16_t>();
      case PlyType::kInt32: return Load<std::int32_t>();
      case PlyType::kUint32: return Load<std::uint32_t>();
      case PlyType::kFloat32: return Load<float>();
      case PlyType::kFloat64: return Load<double>();
    }
    return 0;
  }
  // Precondition: Has(TypeSize(type)), TYPE an integer type.
  long long ReadInt(PlyType type) {
    switch (type) {
      case PlyType::kInt8: return Load<std::int8_t>();
      case PlyType::kUint8: return Load<std::uint8_t>();
      case PlyType::kInt16: return Load<std::int16_t>();
      case PlyType::kUint16: return Load<std::uint16_t>();
      case PlyType::kInt32: return Load<std::int32_t>();
      case PlyType::kUint32: return Load<std::uint32_t>();
      default: return 0;
    }
  }

 private:
  template <typename T>
  T Load() {
    char raw[sizeof(T)];
    std::memcpy(raw, bytes_.data() + offset_, sizeof(T));
    if (swap_) std::reverse(raw, raw + sizeof(T));
    offset_ += sizeof(T);
    T v;
    std::memcpy(&v, raw, sizeof(T));
    return v;
  }

  std::string_view bytes_;
  std::size_t offset_;
  bool swap_;
};

std::string RecordWhere(std::string_view file, const PlyElement& element, long long record, std::size_t offset) {
  return std::string(file) + " (PLY element '" + element.name + "' record " + std::to_string(record) + " of " +
         std::to_string(element.count) + ", byte offset " + std::to_string(offset) + ")";
}

// Counts record R of ELEMENT as stepped through, against STATS' budget (nothing without STATS).
void CountVisit(PlyReadStats* stats, std::string_view file, const PlyElement& element, long long r) {
  if (stats == nullptr) return;
  ++stats->records_visited;
  if (stats->max_records_visited >= 0 && stats->records_visited > stats->max_records_visited) {
    Fail(std::string(file) + " (PLY element '" + element.name + "' record " + std::to_string(r) + ")",
         "the reader stepped through more than " + std::to_string(stats->max_records_visited) + " records");
  }
}

void ReadBinaryBody(std::string_view bytes, std::string_view file, const PlyHeader& header, const PlyLayout& layout,
                    TriangleMesh* mesh, PlyReadStats* stats) {
  const bool file_big = header.format == PlyFormat::kBinaryBigEndian;
  const bool host_big = std::endian::native == std::endian::big;
  BinaryCursor cursor(bytes, header.data_offset, file_big != host_big);
  const long long num_vertices = header.elements[layout.vertex_element].count;
  std::vector<int> polygon;
  for (int e = 0; e < static_cast<int>(header.elements.size()); ++e) {
    const PlyElement& element = header.elements[e];
    const bool is_vertex = e == layout.vertex_element;
    const bool is_face = e == layout.face_element;
    // A record without properties holds no bytes: nothing to read, however large the count
    // (up to 2^31 empty iterations otherwise).
    if (element.properties.empty()) {
      if (stats) stats->records_skipped += element.count;
      continue;
    }
    for (long long r = 0; r < element.count; ++r) {
      CountVisit(stats, file, element, r);
      const std::size_t record_offset = cursor.offset();
      const auto truncated = [&]() {
        Fail(RecordWhere(file, element, r, record_offset),
             "truncated: the file ends inside this record (" + std::to_string(bytes.size()) + " bytes)");
      };
      Eigen::Vector3d p = Eigen::Vector3d::Zero();
      for (int q = 0; q < static_cast<int>(element.properties.size()); ++q) {
        const PlyProperty& property = element.properties[q];
        if (!property.is_list) {
          if (!cursor.Has(TypeSize(property.type))) truncated();
          if (is_vertex && (q == layout.xyz[0] || q == layout.xyz[1] || q == layout.xyz[2])) {
            p[q == layout.xyz[0] ? 0 : q == layout.xyz[1] ? 1 : 2] = cursor.ReadDouble(property.type);
          } else {
            cursor.Skip(TypeSize(property.type));
          }
          continue;
        }
        // A list: its count, then that many items.
        if (!cursor.Has(TypeSize(property.count_type))) truncated();
        const long long n = cursor.ReadInt(property.count_type);
        if (n < 0) Fail(RecordWhere(file, element, r, record_offset), "negative list length in '" + property.name + "'");
        const std::size_t item = TypeSize(property.type);
        if (!cursor.Has(std::size_t(n) * item)) truncated();
        if (!(is_face && q == layout.face_list)) {
          cursor.Skip(std::size_t(n) * item);
          continue;
        }
        if (n < 3) {
          Fail(RecordWhere(file, element, r, record_offset),
               "face with " + std::to_string(n) + " vertices (at least 3 needed)");
        }
        polygon.clear();
        for (long long k = 0; k < n; ++k) {
          const long long index = cursor.ReadInt(property.type);
          if (index < 0 || index >= num_vertices) {
            Fail(RecordWhere(file, element, r, record_offset),
                 "face vertex index " + std::to_string(index) + " out of range [0, " + std::to_string(num_vertices) + ")");
          }
          polygon.push_back(static_cast<int>(index));
        }
        AppendFan(polygon.data(), static_cast<int>(polygon.size()), mesh);
      }
      if (is_vertex) {
        if (!p.allFinite()) Fail(RecordWhere(file, element, r, record_offset), "vertex coordinate is not finite");
        mesh->vertices.push_back(p);
      }
    }
  }
}

void ReadAsciiBody(std::string_view bytes, std::string_view file, const PlyHeader& header, const PlyLayout& layout,
                   TriangleMesh* mesh, PlyReadStats* stats) {
  LineScanner scanner(bytes.substr(header.data_offset), file, header.data_line);
  const long long num_vertices = header.elements[layout.vertex_element].count;
  std::vector<int> polygon;
  for (int e = 0; e < static_cast<int>(header.elements.size()); ++e) {
    const PlyElement& element = header.elements[e];
    const bool is_vertex = e == layout.vertex_element;
    const bool is_face = e == layout.face_element;
    // One record per line.
    for (long long r = 0; r < element.count; ++r) {
      CountVisit(stats, file, element, r);
      if (!scanner.NextContentLine()) {
        scanner.Fail("truncated: file ends after " + std::to_string(r) + " of " + std::to_string(element.count) +
                     " '" + element.name + "' elements");
      }
      Eigen::Vector3d p = Eigen::Vector3d::Zero();
      for (int q = 0; q < static_cast<int>(element.properties.size()); ++q) {
        const PlyProperty& property = element.properties[q];
        if (!property.is_list) {
          if (is_vertex && (q == layout.xyz[0] || q == layout.xyz[1] || q == layout.xyz[2])) {
            const int a = q == layout.xyz[0] ? 0 : q == layout.xyz[1] ? 1 : 2;
            p[a] = scanner.ReadDouble(std::string("vertex ") + char('x' + a) + " coordinate");
          } else {
            scanner.SkipToken("property '" + property.name + "'");
          }
          continue;
        }
        const long long n = scanner.ReadInt("length of list '" + property.name + "'");
        if (n < 0) scanner.Fail("negative list length in '" + property.name + "'");
        if (!(is_face && q == layout.face_list)) {
          for (long long k = 0; k < n; ++k) scanner.SkipToken("item of list '" + property.name + "'");
          continue;
        }
        if (n < 3) scanner.Fail("face with " + std::to_string(n) + " vertices (at least 3 needed)");
        polygon.clear();
        for (long long k = 0; k < n; ++k) {
          const long long index = scanner.ReadInt("face vertex index");
          if (index < 0 || index >= num_vertices) {
            scanner.Fail("face vertex index " + std::to_string(index) + " out of range [0, " +
                         std::to_string(num_vertices) + ")");
          }
          polygon.push_back(static_cast<int>(index));
        }
        AppendFan(polygon.data(), static_cast<int>(polygon.size()), mesh);
      }
      if (is_vertex) mesh->vertices.emplace_back(p);
    }
  }
}

}  // namespace

TriangleMesh ReadPly(std::string_view bytes, std::string_view file, PlyReadStats* stats) {
  const PlyHeader header = ParseHeader(bytes, file);
  const PlyLayout layout = FindLayout(header, file);
  TriangleMesh mesh;
  // Reserve no more than the data could hold, so a corrupt count cannot allocate without bound.
  const std::size_t data_bytes = bytes.size() - header.data_offset;
  mesh.vertices.reserve(std::min<std::size_t>(header.elements[layout.vertex_element].count, data_bytes / 3 + 1));
  mesh.triangles.reserve(std::min<std::size_t>(header.elements[layout.face_element].count, data_bytes / 4 + 1));
  if (header.format == PlyFormat::kAscii) {
    ReadAsciiBody(bytes, file, header, layout, &mesh, stats);
  } else {
    ReadBinaryBody(bytes, file, header, layout, &mesh, stats);
  }
  if (mesh.triangles.empty()) Fail(file, "no faces: the mesh has no triangles");
  return mesh;
}

}  // namespace contactlab::internal
