// Every baseline made through the registry of contact/ from two bodies, with no experiment
// code: each asks for exactly the body data it declares, pushes the way the contact does, and
// rejects a bad penalty parameter.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "contact/register_contact_models.h"
#include "contact/model_registry.h"
#include "geometry/procedural_shapes.h"
#include "pointshell/build_pointshell.h"
#include "sdf/build_distance_field.h"
#include "util/error.h"

namespace contactlab {
namespace {

// A procedural body whose data is built on first use; counts what was asked for.
class ShapeBody final : public ContactBody {
 public:
  explicit ShapeBody(TriangleMesh mesh) : mesh_(std::make_shared<const TriangleMesh>(std::move(mesh))) {}
  std::string_view body_name() const override { return "shape"; }
  std::shared_ptr<const TriangleMesh> mesh() override {
    ++meshes;
    return mesh_;
  }
  std::shared_ptr<const DistanceField> field() override {
    ++fields;
    if (!field_) {
      DistanceFieldOptions o;
      o.resolution = 24;
      o.show_progress = false;
      field_ = std::make_shared<const DistanceField>(BuildDistanceField(*mesh_, o));
    }
    return field_;
  }
  std::shared_ptr<const Pointshell> pointshell() override {
    ++shells;
    if (!shell_) {
      PointshellOptions o;
      o.method = PointshellMethod::kRandom;
      o.num_points = 512;
      o.num_levels = 2;
      o.show_progress = false;
      shell_ = std::make_shared<const Pointshell>(BuildPointshell(*field(), o));
      --fields;
    }
    return shell_;
  }
  std::uint64_t sampling_seed() const override { return 1; }
  void ResetCounts() { meshes = fields = shells = 0; }

  int meshes = 0, fields = 0, shells = 0;

 private:
  std::shared_ptr<const TriangleMesh> mesh_;
  std::shared_ptr<const DistanceField> field_;
  std::shared_ptr<const Pointshell> shell_;
};

TEST(BaselineRegistry, EveryModelAsksForWhatItDeclaresAndPushesTheBoxDown) {
  RegisterContactModels();
  ShapeBody ball(MakeSphere(0.02, 3));                       // A
  ShapeBody box(MakeBox(Eigen::Vector3d(0.04, 0.04, 0.01), 2));  // B, top face at z = 0.01
  const ContactParams params;
  const ParamValues own;  // every model's own keys at their defaults
  ContactQuery q;
  q.X_WA = Pose::FromTranslation(Eigen::Vector3d(0.001, -0.002, 0.0285));  // 1.5 mm deep
  int models = 0;
  for (const std::string& name : ContactModelNames()) {
    const ContactModelEntry* e = FindContactModel(name);
    if (e == nullptr) continue;
    SCOPED_TRACE(name);
    ball.ResetCounts();
    box.ResetCounts();
    std::unique_ptr<ContactModel> model = MakeContactModel(name, {ball, box, params, own}, "test");
    EXPECT_EQ(ball.shells > 0, e->needs.pointshell_A);
    EXPECT_EQ(ball.fields > 0, e->needs.field_A);
    EXPECT_EQ(ball.meshes > 0, e->needs.mesh_A);
    EXPECT_EQ(box.fields > 0, e->needs.field_B);
    EXPECT_EQ(box.meshes > 0, e->needs.mesh_B);
    EXPECT_EQ(box.shells, 0);
    const ContactResult r = model->Evaluate(q);
    EXPECT_GT(r.stats.points_in_contact, 0);
    EXPECT_LT(r.on_B.force.z(), 0);
    EXPECT_LT(r.on_B.force.head<2>().norm(), 0.5 * std::abs(r.on_B.force.z()));
    ++models;
  }
  EXPECT_EQ(models, int(ContactModelNames().size()));
}

// The registry holds exactly the models the build promises, by name: dropping or renaming one
// (a registration left out of its folder's CMakeLists.txt, say) fails here, not silently in
// every loop over ContactModelNames().
TEST(BaselineRegistry, RegistersExactlyTheModelsOfTheBuild) {
  RegisterContactModels();
  std::vector<std::string> models = {"bullet",        "fcl",           "inner-spheres",
                                     "pointshell",    "pointshell-ccd", "pointshell-linear",
                                     "pressure-field", "vps",           "vps-repulsion"};
  std::vector<std::string> references;
#ifdef CONTACTLAB_HAVE_CGAL
  models.push_back("reference");  // offline: dense quadrature with CGAL's exact distances
  references = {"eq2-halfspace", "volume"};
#endif
  std::sort(models.begin(), models.end());
  EXPECT_EQ(ContactModelNames(), models);
  EXPECT_EQ(ReferenceModelNames(), references);
}

TEST(BaselineRegistry, EveryModelRejectsANegativeStiffness) {
  RegisterContactModels();
  ShapeBody ball(MakeSphere(0.02, 2));
  ShapeBody box(MakeBox(Eigen::Vector3d(0.04, 0.04, 0.01), 1));
  ContactParams params;
  params.penalty.k_C = -5;
  const ParamValues own;
  for (const std::string& name : ContactModelNames()) {
    const ContactModelEntry* e = FindContactModel(name);
    if (e == nullptr) continue;
    try {
      MakeContactModel(name, {ball, box, params, own}, "test");
      ADD_FAILURE() << name << " accepted k_C = -5";
    } catch (const Error& err) {
      EXPECT_NE(std::string(err.what()).find("k_C"), std::string::npos) << name << ": " << err.what();
    }
  }
}

}  // namespace
}  // namespace contactlab
