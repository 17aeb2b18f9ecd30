// The sec. 5 halfspace terms of many points in contact at once (Barbič & James 2008): the
// per-point force d N, its torque and the four gradient sums of ContactAccumulator::Add with
// g = N, formed and summed several points per instruction (Google Highway, the instruction set
// chosen at run time as for sdf/batch_distance.h). The paper's model collects its points in
// contact in a HalfspaceContactBuffer and adds them a buffer at a time, for every combination of
// rigid or deformable pointshell and grid or deformed field
// (src/pointshell_contact/pointshell_field_model.h).
#pragma once

#include <cstdint>

#include "contact/contact_accumulator.h"
#include "pointshell/pointshell.h"
#include "sdf/batch_distance.h"

namespace contactlab {

// Where the points in contact are, in A's frame: point i at (x[i], y[i], z[i]) with inward
// unit normal (nx[i], ny[i], nz[i]). A rigid pointshell's own arrays, or the deformed
// positions and corrected normals a deformable one writes for its points in contact.
struct ContactPointArrays {
  const float *x, *y, *z;
  const float *nx, *ny, *nz;
  static ContactPointArrays Of(const Pointshell& s) {
    return {s.x.data(), s.y.data(), s.z.data(), s.nx.data(), s.ny.data(), s.nz.data()};
  }
};

// Adds to ACC the points i = INDEX[k], k < N, of P, each at p_B = R p_i + t (X) with inward
// normal N_B = R n_i and distance D[k] < 0, under the halfspace rule. Equal to N calls of
// ContactAccumulator::Add to float rounding: the terms are formed and summed in float in A's
// frame, then rotated into B's and added to ACC's double sums. Allocates nothing.
void AddHalfspaceContacts(const ContactPointArrays& P, const BatchTransform& X, const std::int32_t* index,
                          const float* d, int n, ContactAccumulator* acc);
inline void AddHalfspaceContacts(const Pointshell& s, const BatchTransform& X, const std::int32_t* index,
                                 const float* d, int n, ContactAccumulator* acc) {
  AddHalfspaceContacts(ContactPointArrays::Of(s), X, index, d, n, acc);
}

// Points in contact of one query, added to an accumulator kCapacity at a time (so the float
// partial sums stay short). Each flush adds the next kCapacity points in the order they were
// collected, however they were grouped, so the sums depend only on that order. Flush()
// before reading the accumulator. A flush hook, when given, sees each added run of points too
// (a deformable body's reduced force: one call per up to kCapacity points, not per point).
class HalfspaceContactBuffer {
 public:
  static constexpr int kCapacity = 256;
  static constexpr int kPadding = 64;  // room for one vector stored past kCapacity
  // Called with the points INDEX[0..n) and their D as they are added to the accumulator.
  using FlushHook = void (*)(void* context, const std::int32_t* index, const float* d, int n);

  HalfspaceContactBuffer(const ContactPointArrays& P, const BatchTransform& X, ContactAccumulator* acc,
                         FlushHook hook = nullptr, void* hook_context = nullptr)
      : P_(P), X_(X), acc_(acc), hook_(hook), hook_context_(hook_context) {}
  HalfspaceContactBuffer(const Pointshell& s, const BatchTransform& X, ContactAccumulator* acc)
      : HalfspaceContactBuffer(ContactPointArrays::Of(s), X, acc) {}
  HalfspaceContactBuffer(const HalfspaceContactBuffer&) = delete;
  HalfspaceContactBuffer& operator=(const HalfspaceContactBuffer&) = delete;

  // Adds the points in contact among N evaluated ones: point INDEX[k] (BEGIN + k when INDEX is
  // null) when D[k] < 0. Picks them several at a time (vector compress, run-time dispatch).
  void Collect(int begin, const std::int32_t* index, const float* d, int n);
  // Adds every point collected so far.
  void Flush() {
    if (size_ > 0) Add(size_);
    size_ = 0;
  }

  // For the vector code: the first free entry (with at least kPadding floats of room behind
  // it), and M more points written there.
  std::int32_t* free_index() { return index_ + size_; }
  float* free_d() { return d_ + size_; }
  void Added(int m) {
    size_ += m;
    if (size_ >= kCapacity) {  // add the first kCapacity, keep the rest
      Add(kCapacity);
      size_ -= kCapacity;
      for (int k = 0; k < size_; ++k) {
        index_[k] = index_[kCapacity + k];
        d_[k] = d_[kCapacity + k];
      }
    }
  }

 private:
  void Add(int n) {
    AddHalfspaceContacts(P_, X_, index_, d_, n, acc_);
    if (hook_ != nullptr) hook_(hook_context_, index_, d_, n);
  }

  const ContactPointArrays P_;
  const BatchTransform X_;
  ContactAccumulator* acc_;
  FlushHook hook_;
  void* hook_context_;
  int size_ = 0;  // < kCapacity between calls
  std::int32_t index_[kCapacity + kPadding];
  float d_[kCapacity + kPadding];
};

}  // namespace contactlab
