#include "experiment/body_memory.h"

#include <vector>

namespace contactlab {
namespace {

template <class T>
std::int64_t Bytes(const std::vector<T>& v) {
  return std::int64_t(v.size()) * std::int64_t(sizeof(T));
}

}  // namespace

std::int64_t FieldBytes(const DistanceField& field) { return field.memory_bytes(); }

std::int64_t PointshellBytes(const Pointshell& p) {
  return Bytes(p.x) + Bytes(p.y) + Bytes(p.z) + Bytes(p.nx) + Bytes(p.ny) + Bytes(p.nz) + Bytes(p.level_point_end) +
         Bytes(p.level_node_begin) + Bytes(p.node_point) + Bytes(p.node_radius) + Bytes(p.child_begin) +
         Bytes(p.node_parent);
}

}  // namespace contactlab
