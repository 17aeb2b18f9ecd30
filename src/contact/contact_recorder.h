// Keeps the contacts of one query for ContactModel::LatestContacts (contact_model.h): a model
// reserves room once, outside the haptic cycle (Keep), then records into it during Evaluate
// without allocating, and turns the record into a world-frame ContactList on request (Fill).
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cstdint>
#include <vector>

#include "contact/contact_model.h"
#include "geometry/pose.h"

namespace contactlab {

class ContactRecorder {
 public:
  // Reserves room for MAX_CONTACTS contacts (<= 0: keep none from now on); WITH_SURFACE: an
  // area and a pressure per contact too. Allocates; not for the haptic cycle.
  void Keep(int max_contacts, bool with_surface = false, bool with_friction = false) {
    capacity_ = std::max(0, max_contacts);
    with_surface_ = with_surface;
    with_friction_ = with_friction;
    Clear();
    // Reserved, not filled: room a query never uses is never touched.
    const std::size_t n = std::size_t(capacity_);
    p_.reserve(n);
    n_.reserve(n);
    depth_.reserve(n);
    area_.reserve(with_surface ? n : 0);
    pressure_.reserve(with_surface ? n : 0);
    tangential_.reserve(with_friction ? n : 0);
    sticking_.reserve(with_friction ? n : 0);
  }
  // True once Keep asked for room: Evaluate records only then.
  bool keeping() const { return capacity_ > 0; }

  // At the start of an Evaluate: forgets the previous query's contacts. Allocation-free.
  void Clear() {
    p_.clear(), n_.clear(), depth_.clear(), area_.clear(), pressure_.clear();  // capacity kept
    tangential_.clear(), sticking_.clear();
    not_kept_ = 0;
    tangential_scale_ = 1;
  }
  // One contact in the model's recording frame F (see Fill): point P_F (metres), unit normal
  // N_F, depth (metres), and for a surface model its AREA (m^2) and mean PRESSURE (Pa). Past
  // the room reserved it is counted, not kept. Allocation-free, throws nothing.
  void Add(const Eigen::Vector3d& p_F, const Eigen::Vector3d& n_F, double depth, double area = 0,
           double pressure = 0) {
    if (int(p_.size()) >= capacity_) {
      ++not_kept_;
      return;
    }
    p_.push_back(p_F);  // within the capacity reserved: no allocation
    n_.push_back(n_F);
    depth_.push_back(depth);
    if (with_surface_) area_.push_back(area), pressure_.push_back(pressure);
  }
  // With friction kept (Keep's WITH_FRICTION): the friction force on B of the contact Add
  // recorded last, in the recording frame and in units Fill multiplies by the factor given to
  // ScaleTangential, and whether it sticks. Allocation-free; a contact not kept is skipped.
  void AddFriction(const Eigen::Vector3d& tangential_F, bool sticking) {
    if (!with_friction_ || tangential_.size() >= p_.size()) return;
    tangential_.push_back(tangential_F);
    sticking_.push_back(sticking ? 1 : 0);
  }
  // The factor Fill multiplies the friction forces recorded by (known once a query's sums are).
  void ScaleTangential(double factor) { tangential_scale_ = factor; }
  int size() const { return int(p_.size()); }
  std::int64_t not_kept() const { return not_kept_; }

  // The contacts recorded, moved into the world by X_WF (F: the frame they were recorded in),
  // each normal times NORMAL_SIGN (+1 or -1: a model that recorded the force on A's side),
  // replacing OUT's contents. Allocates.
  void Fill(const Pose& X_WF, double normal_sign, ContactList* out) const {
    out->Clear();
    const Eigen::Matrix3d R = X_WF.R();
    const std::size_t n = p_.size();
    out->points.resize(n);
    out->normals.resize(n);
    out->depths = depth_;
    for (std::size_t i = 0; i < n; ++i) {
      out->points[i] = R * p_[i] + X_WF.translation;
      out->normals[i] = normal_sign * (R * n_[i]);
    }
    if (with_surface_) {
      out->areas = area_;
      out->pressures = pressure_;
    }
    if (with_friction_ && tangential_.size() == n) {
      out->tangential.resize(n);
      for (std::size_t i = 0; i < n; ++i) out->tangential[i] = tangential_scale_ * (R * tangential_[i]);
      out->sticking = sticking_;
    }
    out->not_kept = not_kept_;
  }

 private:
  int capacity_ = 0;
  std::int64_t not_kept_ = 0;
  bool with_surface_ = false;
  bool with_friction_ = false;
  double tangential_scale_ = 1;
  // The contacts recorded (#C <= capacity_ each, capacity_ reserved), in the recording frame.
  std::vector<Eigen::Vector3d> p_, n_;   // (#C) metres; unit normals
  std::vector<double> depth_;            // (#C) metres
  std::vector<double> area_, pressure_;  // (#C, or empty) m^2, Pa
  std::vector<Eigen::Vector3d> tangential_;  // (#C, or empty) friction on B, before tangential_scale_
  std::vector<std::uint8_t> sticking_;       // (#C, or empty)
};

}  // namespace contactlab
