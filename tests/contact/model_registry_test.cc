// The contact-model registry of contact/: models made by name from two bodies and the
// scene's parameters, each declaring what it needs.
#include "contact/model_registry.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <string>

#include "contact/register_contact_models.h"
#include "contact/test_shells.h"
#include "contact/unbuilt_models.h"
#include "pointshell_contact/pointshell_contact_model.h"
#include "test_support.h"
#include "util/error.h"

namespace contactlab {
namespace {

// A body with hand-made data; counts what a factory asked for.
class FakeBody final : public ContactBody {
 public:
  std::string_view body_name() const override { return "fake"; }
  std::shared_ptr<const TriangleMesh> mesh() override {
    ++meshes;
    return nullptr;
  }
  std::shared_ptr<const DistanceField> field() override {
    ++fields;
    return field_;
  }
  std::shared_ptr<const Pointshell> pointshell() override {
    ++shells;
    return shell_;
  }
  std::uint64_t sampling_seed() const override { return 1; }

  std::shared_ptr<const DistanceField> field_;
  std::shared_ptr<const Pointshell> shell_;
  int meshes = 0, fields = 0, shells = 0;
};

// A model of no force, standing for one a user adds in a folder of their own.
// Every model the build holds, the paper's among them, registered as a program does.
const bool kModelsRegistered = (RegisterContactModels(), true);

class NoForceModel final : public ContactModel {
 public:
  std::string_view name() const override { return "no-force"; }
  ContactResult Evaluate(const ContactQuery&) override { return {}; }
  void Reset() override {}
};

// A unit sphere of 64 points as A's pointshell, the first 16 its coarse level (a spiral from
// the south pole up), and the halfspace z < 0 as B's field. Returns the points, A's frame.
std::vector<Eigen::Vector3d> SphereOverHalfspace(FakeBody* A, FakeBody* B) {
  std::vector<Eigen::Vector3d> p, n;
  for (int i = 0; i < 64; ++i) {
    const double z = -1 + (i + 0.5) / 32, r = std::sqrt(1 - z * z), phi = 2.39996 * i;
    p.emplace_back(r * std::cos(phi), r * std::sin(phi), z);
    n.push_back(-p.back());
  }
  A->shell_ = testing::MakeNestedShell(p, n, {16, 64});
  B->field_ = testing::SampleField([](const Eigen::Vector3d& x) { return x.z(); }, Eigen::Vector3d(-2, -2, -2),
                                   Eigen::Vector3d(2, 2, 2), 0.05);
  return p;
}

TEST(ModelRegistry, ThePapersModelsAreBuiltInAndDeclareWhatTheyNeed) {
  for (const char* name : {"pointshell", "pointshell-linear"}) {
    const ContactModelEntry* e = FindContactModel(name);
    ASSERT_NE(e, nullptr) << name;
    EXPECT_TRUE(e->needs.pointshell_A);
    EXPECT_TRUE(e->needs.field_B);
    EXPECT_FALSE(e->needs.mesh_A || e->needs.mesh_B || e->needs.field_A);
    EXPECT_TRUE(e->needs.depth_in_field_voxels);
  }
}

TEST(ModelRegistry, AFactoryGetsTheBodiesAndTheScenesParameters) {
  // A unit sphere of points (A) against the halfspace z < 0 (B), A 0.1 below the plane's top.
  FakeBody A, B;
  const std::vector<Eigen::Vector3d> p = SphereOverHalfspace(&A, &B);
  ContactParams params;
  params.penalty = {.k_C = 123, .L = 0};
  ParamValues own;  // the paper's own keys: level 1, the shell's deepest
  own.Mutable(PointshellOwnParamTable()).level = 1;
  std::unique_ptr<ContactModel> model = MakeContactModel("pointshell-linear", {A, B, params, own}, "test");
  EXPECT_EQ(A.shells, 1);
  EXPECT_EQ(B.fields, 1);
  EXPECT_EQ(A.fields + A.meshes + B.shells + B.meshes, 0);  // nothing it does not need
  auto* paper = dynamic_cast<PointshellContactModel*>(model.get());
  ASSERT_NE(paper, nullptr);
  EXPECT_EQ(paper->params().penalty.k_C, 123);
  EXPECT_EQ(paper->params().level, 1);
  ContactQuery q;
  q.X_WA = Pose::FromTranslation(Eigen::Vector3d(0, 0, 0.9));
  const ContactResult r = model->Evaluate(q);
  EXPECT_GT(r.stats.points_in_contact, 0);
  EXPECT_LT(r.on_B.force.z(), 0);  // B (below) is pushed down
}

// The harness places bodies at a depth with the registry's depth probe (scene/contact_placement.h),
// never with a model named in its code: exactly one entry provides it, and its deepest
// penetration is that of every point of A's deepest level (brute force on a halfspace), also
// when the scene renders a coarser level.
TEST(ModelRegistry, ExactlyOneEntryProvidesTheDepthProbeAndItReachesEveryPoint) {
  int providers = 0;
  for (const ContactModelEntry* e : ContactModelEntries()) providers += e->make_depth_probe ? 1 : 0;
  ASSERT_EQ(providers, 1);
  const ContactModelEntry& entry =
      SoleContactModelWith([](const ContactModelEntry& e) { return bool(e.make_depth_probe); }, "a depth probe", "test");
  // A unit sphere of points (A), 16 on its coarse level and 64 on its deepest, upside down so
  // that its deepest point is on the deepest level only; B the halfspace z < 0.
  FakeBody A, B;
  const std::vector<Eigen::Vector3d> p = SphereOverHalfspace(&A, &B);
  ContactParams params;
  ParamValues own;
  own.Mutable(PointshellOwnParamTable()).level = 0;  // the scene renders the coarse level
  const std::unique_ptr<ContactModel> probe = entry.make_depth_probe({A, B, params, own});
  ContactQuery q;
  q.X_WA = Pose{Eigen::Quaterniond(Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX())), Eigen::Vector3d(0, 0, 0.9)};
  double deepest = 0, deepest_coarse = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double d = -(q.X_WA * p[i]).z();
    deepest = std::max(deepest, d);
    if (i < 16) deepest_coarse = std::max(deepest_coarse, d);
  }
  ASSERT_GT(deepest, deepest_coarse + 0.01);  // the case tells the levels apart
  EXPECT_NEAR(probe->Evaluate(q).stats.max_penetration, deepest, 1e-5);
}

// `model.stiffness: matched` scales every model to the entry that declares itself the
// stiffness reference, never to a name in the harness's code: exactly one does, and it is a model
// compared in experiments (not a reference-only entry).
TEST(ModelRegistry, ExactlyOneEntryIsTheStiffnessReference) {
  std::vector<std::string> references;
  for (const ContactModelEntry* e : ContactModelEntries()) {
    if (e->stiffness_reference) references.push_back(e->name);
  }
  ASSERT_EQ(references.size(), 1u);
  const auto names = ContactModelNames();
  EXPECT_NE(std::find(names.begin(), names.end(), references.front()), names.end());
}

// A trait no entry, or more than one, declares is an error naming the trait and the entries.
TEST(ModelRegistry, ASoleEntryLookupRefusesNoneAndSeveral) {
  const auto message = [](const std::function<bool(const ContactModelEntry&)>& has) {
    try {
      SoleContactModelWith(has, "a made-up trait", "here");
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string none = message([](const ContactModelEntry&) { return false; });
  EXPECT_NE(none.find("here: no registered contact model declares a made-up trait"), std::string::npos) << none;
  // "pointshell" and "pointshell-linear" both start with "pointshell".
  const std::string several = message([](const ContactModelEntry& e) { return e.name.rfind("pointshell", 0) == 0; });
  EXPECT_NE(several.find("here: several registered contact models declare a made-up trait: pointshell"),
            std::string::npos)
      << several;
}

TEST(ModelRegistry, AModelRegisteredFromOutsideIsMadeByName) {
  ContactModelEntry e;
  e.name = "no-force";
  e.description = "test model";
  e.make = [](const ContactModelInputs&) -> std::unique_ptr<ContactModel> { return std::make_unique<NoForceModel>(); };
  RegisterContactModel(e);
  const std::vector<std::string> names = ContactModelNames();
  EXPECT_TRUE(std::is_sorted(names.begin(), names.end()));
  EXPECT_NE(std::find(names.begin(), names.end(), "no-force"), names.end());
  FakeBody A, B;
  const ContactParams params;
  const ParamValues own;
  EXPECT_EQ(MakeContactModel("no-force", {A, B, params, own}, "test")->name(), "no-force");
}

TEST(ModelRegistry, AnUnknownNameListsTheKnownOnes) {
  FakeBody A, B;
  const ContactParams params;
  const ParamValues own;
  try {
    MakeContactModel("pointshel", {A, B, params, own}, "scene.yaml");
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("scene.yaml: unknown contact model 'pointshel'"), std::string::npos) << m;
    EXPECT_NE(m.find("pointshell-linear"), std::string::npos) << m;
  }
  ContactModelEntry nameless;
  EXPECT_THROW(RegisterContactModel(nameless), Error);
}

// A model recorded as not built into the program (a build without what it needs) is refused
// with the reason, not as an unknown name; a registered model of that name is made as before.
TEST(ModelRegistry, AModelNotBuiltInIsRefusedWithTheReason) {
  FakeBody A, B;
  const ContactParams params;
  const ParamValues own;
  RegisterUnbuiltContactModel("test-unbuilt", "it needs a test library (configure with -DTEST=ON)");
  EXPECT_EQ(UnbuiltContactModelReason("test-unbuilt"), "it needs a test library (configure with -DTEST=ON)");
  EXPECT_FALSE(UnbuiltContactModelReason("pointshel").has_value());
  const std::string m = testing::ErrorOf([&] { MakeContactModel("test-unbuilt", {A, B, params, own}, "exp.yaml:4"); });
  EXPECT_EQ(m, "exp.yaml:4: contact model 'test-unbuilt' is not built into this program: it needs a test library "
               "(configure with -DTEST=ON)");
}

}  // namespace
}  // namespace contactlab
