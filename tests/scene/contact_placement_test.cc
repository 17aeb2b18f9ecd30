// PlaceAtDepth (scene/contact_placement.h) against a closed form: a model whose penetration is
// the distance A has moved past a plane, so the placement's travel is known exactly.
#include "scene/contact_placement.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace contactlab {
namespace {

// A's origin past the plane x = PLANE_X (moving along +x): that far, in metres.
class PlaneDepthModel final : public ContactModel {
 public:
  explicit PlaneDepthModel(double plane_x) : plane_x_(plane_x) {}
  std::string_view name() const override { return "plane-depth"; }
  ContactResult Evaluate(const ContactQuery& q) override {
    ++queries;
    ContactResult r;
    r.stats.max_penetration = std::max(0.0, q.X_WA.translation.x() - plane_x_);
    return r;
  }
  void Reset() override {}
  long queries = 0;

 private:
  double plane_x_;
};

// `contact --touch 1e-9` never finished: the march took steps of depth / 4 over the whole
// travel, and below about 1e-16 m a step no longer moved s at all. Every depth, down to one far
// below the resolution of the position, is placed within the bound on queries, at the first
// position past the plane that is depth deep (to 1 % of it, or to the position's resolution).
TEST(PlaceAtDepth, AnyDepthIsPlacedWithinTheBoundOnQueries) {
  const double plane = 0.3, travel = 0.8;
  for (const double depth : {1e-3, 1e-6, 1e-9, 1e-12, 1e-20}) {
    SCOPED_TRACE(depth);
    PlaneDepthModel model(plane);
    const Placement p = PlaceAtDepth(model, Pose::Identity(), Pose::Identity(), Eigen::Vector3d::UnitX(), depth, travel);
    ASSERT_TRUE(p.found);
    // The coarse march's 4,097 steps, the fine one's 4,098 within a coarse step, the 64
    // halvings and the final query.
    EXPECT_LE(model.queries, 8260);
    EXPECT_GE(p.depth, depth);
    const double resolution = 4 * std::nextafter(plane, 1.0) - 4 * plane;  // a few ulps of s
    EXPECT_LE(p.travel - (plane + depth), std::max(0.01 * depth, resolution));
    EXPECT_DOUBLE_EQ(p.X_WA.translation.x(), p.travel);
  }
}

// A depth the travel never reaches is reported not found, and A stays where it started.
TEST(PlaceAtDepth, ADepthBeyondTheTravelIsNotFound) {
  PlaneDepthModel model(0.3);
  const Placement p = PlaceAtDepth(model, Pose::Identity(), Pose::Identity(), Eigen::Vector3d::UnitX(), 0.6, 0.8);
  EXPECT_FALSE(p.found);
  EXPECT_EQ(p.X_WA.translation, Eigen::Vector3d::Zero());
  EXPECT_LE(model.queries, kPlacementCoarseSteps + 1);
}

}  // namespace
}  // namespace contactlab
