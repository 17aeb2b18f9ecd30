// Checks shared by the FCL and Bullet baseline tests: a tessellated box A pressed into a
// larger box B, the wrench's sign, its torque about B's origin, the zero wrench when apart,
// and K_B against central differences; and bad values of a model's own scene keys refused.
#pragma once

#include <gtest/gtest.h>

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "contact/contact_model.h"
#include "scene/scene.h"
#include "geometry/procedural_shapes.h"
#include "util/config_node.h"
#include "util/error.h"

namespace contactlab::testing {

// Makes a model of mesh A against mesh B (both in body frames) with stiffness k_C and L.
using PenaltyModelMaker = std::function<std::unique_ptr<ContactModel>(
    std::shared_ptr<const TriangleMesh>, std::shared_ptr<const TriangleMesh>, double k_C, int L)>;

// Box A (half extents 1/30, 1/40, 1/50 m) above a wide box B (half 1/10, 1/10, 1/20 m, top
// face at z = 1/20 in B's frame), B placed at p_WB with a yaw so nothing is axis-aligned in
// the world; A's bottom face DEPTH below B's top face, A yawed too.
struct BoxOnBox {
  std::shared_ptr<const TriangleMesh> A = std::make_shared<TriangleMesh>(
      MakeBox(Eigen::Vector3d(1.0 / 30, 1.0 / 40, 1.0 / 50), 3));
  std::shared_ptr<const TriangleMesh> B = std::make_shared<TriangleMesh>(
      MakeBox(Eigen::Vector3d(1.0 / 10, 1.0 / 10, 1.0 / 20), 6));
  ContactQuery Query(double depth) const {
    ContactQuery q;
    q.X_WB.translation = Eigen::Vector3d(0.01 / 3, -0.02 / 3, -1.0 / 20);
    q.X_WB.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()));
    q.X_WA.translation = Eigen::Vector3d(0.007, 0.003, 1.0 / 50 - depth);
    q.X_WA.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(-0.2, Eigen::Vector3d::UnitZ()));
    return q;
  }
};

inline void ExpectForceOnBPointsAwayFromA(const PenaltyModelMaker& make) {
  BoxOnBox s;
  auto model = make(s.A, s.B, 2000, 10);
  const ContactResult r = model->Evaluate(s.Query(0.001));
  ASSERT_GT(r.stats.points_in_contact, 0);
  const Eigen::Vector3d& F = r.on_B.force;
  // A presses down on B: the force on B points down (-z), mostly vertical.
  EXPECT_LT(F.z(), 0) << "force " << F.transpose();
  EXPECT_GT(-F.z(), 0.9 * F.norm()) << "force " << F.transpose();
  EXPECT_GT(r.stats.max_penetration, 0.0);
}

inline void ExpectTorqueAboutBsOrigin(const PenaltyModelMaker& make) {
  // The same world geometry with B's origin moved by c (mesh shifted by -c in B's frame):
  // the force is the same and the torque about the new origin is τ - (c_W × F).
  BoxOnBox s;
  const Eigen::Vector3d c_B(0.05, -0.03, 0.02);
  auto shifted = std::make_shared<TriangleMesh>(*s.B);
  shifted->Transform(1.0, Eigen::Matrix3d::Identity(), -c_B);
  auto m0 = make(s.A, s.B, 2000, 10);
  auto m1 = make(s.A, shifted, 2000, 10);
  const ContactQuery q0 = s.Query(0.001);
  ContactQuery q1 = q0;
  q1.X_WB.translation = q0.X_WB * c_B;
  const ContactResult r0 = m0->Evaluate(q0), r1 = m1->Evaluate(q1);
  ASSERT_GT(r0.stats.points_in_contact, 0);
  const double scale = r0.on_B.force.norm();
  EXPECT_LT((r1.on_B.force - r0.on_B.force).norm(), 1e-6 * scale);
  const Eigen::Vector3d c_W = q1.X_WB.translation - q0.X_WB.translation;
  const Eigen::Vector3d expected = r0.on_B.torque - c_W.cross(r0.on_B.force);
  EXPECT_LT((r1.on_B.torque - expected).norm(), 1e-6 * scale * 0.1) << r1.on_B.torque.transpose() << " vs "
                                                                     << expected.transpose();
  // And the torque is not trivially zero here (the contact is off B's origin).
  EXPECT_GT(r0.on_B.torque.norm(), 1e-3 * scale * 0.01);
}

inline void ExpectZeroWrenchWhenApart(const PenaltyModelMaker& make) {
  BoxOnBox s;
  auto model = make(s.A, s.B, 2000, 10);
  const ContactResult r = model->Evaluate(s.Query(-0.01));  // 1 cm gap
  EXPECT_EQ(r.stats.points_in_contact, 0);
  EXPECT_EQ(r.on_B.force, Eigen::Vector3d::Zero());
  EXPECT_EQ(r.on_B.torque, Eigen::Vector3d::Zero());
  EXPECT_EQ(r.K_B, Matrix6d::Zero());
}

// K_B's translation columns against central differences of the wrench, L/l scaling off so
// the stiffness is k_C per contact, for a flat face-on-face contact whose contact set does
// not change within the step.
inline void ExpectTranslationGradientMatchesFiniteDifferences(const PenaltyModelMaker& make) {
  BoxOnBox s;
  auto model = make(s.A, s.B, 2000, 0);
  const ContactQuery q = s.Query(0.001);
  const ContactResult r = model->Evaluate(q);
  ASSERT_GT(r.stats.points_in_contact, 0);
  const double h = 1e-5;
  const double scale = r.K_B.block<3, 3>(0, 0).norm();
  ASSERT_GT(scale, 0);
  for (int i = 0; i < 3; ++i) {
    ContactQuery qp = q, qm = q;
    qp.X_WB.translation[i] += h;
    qm.X_WB.translation[i] -= h;
    const Vector6d fd = (model->Evaluate(qp).on_B.AsVector() - model->Evaluate(qm).on_B.AsVector()) / (2 * h);
    // The diagonal (along the motion) tightly; the whole column loosely, because the rim
    // contacts (A's side faces crossing B's top) may carry a sideways normal whose depth,
    // local to a triangle pair, changes with the motion (Bullet's clipping does).
    EXPECT_NEAR(fd[i], r.K_B(i, i), 0.01 * scale) << "column " << i;
    EXPECT_LT((fd.head<3>() - r.K_B.block<3, 1>(0, i)).norm(), 0.05 * scale)
        << "column " << i << ": finite differences " << fd.head<3>().transpose() << ", K_B "
        << r.K_B.block<3, 1>(0, i).transpose();
  }
}

// A ball over a plate read as the scene file s.yaml, its model block holding KEYS (the inside
// of a YAML flow mapping, on line 5).
inline std::string BallOverPlateWithModelKeys(const std::string& keys) {
  return "name: s\nbodies:\n"
         "  - {name: ball, mesh: \"sphere:0.01\", role: pointshell}\n"
         "  - {name: plate, mesh: \"box:0.05,0.05,0.01\", role: field}\n"
         "model: {" + keys + "}\n";
}

// Each BAD (keys, message): reading the scene with those model keys throws an Error whose text
// holds MESSAGE; GOOD keys are read without one.
inline void ExpectModelKeysRefused(const std::vector<std::pair<std::string, std::string>>& bad, const std::string& good) {
  for (const auto& [keys, message] : bad) {
    try {
      ParseScene(ConfigNode::LoadString(BallOverPlateWithModelKeys(keys), "s.yaml"));
      ADD_FAILURE() << keys << " was accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
    }
  }
  EXPECT_NO_THROW(ParseScene(ConfigNode::LoadString(BallOverPlateWithModelKeys(good), "s.yaml")));
}

}  // namespace contactlab::testing
