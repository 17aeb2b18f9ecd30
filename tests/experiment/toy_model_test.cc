// A model added from outside through the public mechanism alone (docs/architecture.md, "Adding a
// model"): its registry entry carries one pair parameter and one per-body block, and the scene
// reader, the sweeps, the reference and an experiment run take them from there, with no line of
// the harness naming them.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "contact/model_registry.h"
#include "experiment/studies/contact/contact_study.h"
#include "scene/scene.h"
#include "test_support.h"
#include "util/atomic_file.h"
#include "util/error.h"

namespace contactlab {
namespace {

using testing::TempDir;

// The toy's pair key: its spring's gain.
struct ToyGain {
  double gain = 1;  // N/m per unit of charge squared
};
const ParamTable<ToyGain>& ToyGainParams() {
  using P = ParamRows<ToyGain>;
  static const ParamTable<ToyGain> table(
      "toy-spring", "The toy spring's gain.",
      {P::Number("toy_gain", PARAM_MEMBER(gain), Above(0), NoUpperBound(), "toy-spring: gain").Sweepable().Example("3")});
  return table;
}

// The toy's body block: each body's charge.
struct ToyCharge {
  double charge = 1;
};
const ParamTable<ToyCharge>& ToyChargeParams() {
  using P = ParamRows<ToyCharge>;
  static const ParamTable<ToyCharge> table(
      "bodies[].toy", "A body's charge in the toy spring.",
      {P::Number("charge", PARAM_MEMBER(charge), Above(0), NoUpperBound(), "the body's charge").Sweepable().Example("2")});
  return table;
}

// A spring between the bodies' origins, k = gain * charge_A * charge_B: the force on B is
// k (p_A - p_B), applied at B's origin (no torque about it); K_B = -k I on the force block.
class ToySpring final : public ContactModel {
 public:
  explicit ToySpring(double k) : k_(k) {}
  std::string_view name() const override { return "toy-spring"; }
  ContactResult Evaluate(const ContactQuery& q) override {
    ContactResult r;
    r.on_B.force = k_ * (q.X_WA.translation - q.X_WB.translation);
    r.K_B.setZero();
    r.K_B.topLeftCorner<3, 3>() = -k_ * Eigen::Matrix3d::Identity();
    r.stats.points_in_contact = 1;
    return r;
  }
  void Reset() override {}

 private:
  double k_;
};

void RegisterToySpring() {
  RegisterContactModel({
      .name = "toy-spring",
      .description = "a spring between the bodies' origins (a test's model)",
      .make = [](const ContactModelInputs& in) -> std::unique_ptr<ContactModel> {
        const double k = in.Params(ToyGainParams()).gain * in.A.model_blocks().Get(ToyChargeParams()).charge *
                         in.B.model_blocks().Get(ToyChargeParams()).charge;
        return std::make_unique<ToySpring>(k);
      },
      .pair_params = ParamBlock(ToyGainParams()),
      .body_blocks = {ParamBlock(ToyChargeParams(), "toy", "its charge in the toy spring")},
  });
}

const std::string kScene = R"(bodies:
  - {name: ball, mesh: "sphere:0.01", role: pointshell, pose: [0.001, 0.002, 0.015, 1, 0, 0, 0], toy: {charge: 2}}
  - {name: plate, mesh: "box:0.04,0.04,0.01", role: field, toy: {charge: 5}}
model: {toy_gain: 3}
models: [toy-spring]
)";

// The columns of a CSV file: header name -> values of every row.
std::vector<std::vector<std::string>> Rows(const std::filesystem::path& file) {
  std::istringstream in(ReadWholeFile(file));
  std::vector<std::vector<std::string>> rows;
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells;
    std::stringstream ls(line);
    for (std::string c; std::getline(ls, c, ',');) cells.push_back(c);
    rows.push_back(cells);
  }
  return rows;
}
int Column(const std::vector<std::string>& header, const std::string& name) {
  for (std::size_t i = 0; i < header.size(); ++i) {
    if (header[i] == name) return static_cast<int>(i);
  }
  ADD_FAILURE() << "no column " << name;
  return 0;
}

TEST(ToyModel, ItsKeysAreReadCheckedAndDocumentedFromItsEntryAlone) {
  RegisterToySpring();
  TempDir dir;
  std::ofstream(dir / "scene.yaml") << kScene;
  const Scene scene = LoadScene(dir / "scene.yaml");
  EXPECT_EQ(scene.model_params.Get(ToyGainParams()).gain, 3);
  EXPECT_EQ(scene.pointshell_body.model_blocks.Get(ToyChargeParams()).charge, 2);
  EXPECT_EQ(scene.field_body.model_blocks.Get(ToyChargeParams()).charge, 5);
  // Checked where declared: a value out of range and a key the block lacks name file, line, key.
  std::ofstream(dir / "bad.yaml") << "bodies:\n  - {mesh: \"sphere:0.01\", role: pointshell, toy: {charge: -1}}\n"
                                     "  - {mesh: \"sphere:0.01\", role: field}\n";
  std::string e = testing::ErrorOf([&] { LoadScene(dir / "bad.yaml"); });
  EXPECT_NE(e.find("bad.yaml:2"), std::string::npos) << e;
  EXPECT_NE(e.find("charge"), std::string::npos) << e;
  std::ofstream(dir / "bad.yaml") << "bodies:\n  - {mesh: \"sphere:0.01\", role: pointshell}\n"
                                     "  - {mesh: \"sphere:0.01\", role: field}\nmodel: {toy_gian: 2}\n";
  e = testing::ErrorOf([&] { LoadScene(dir / "bad.yaml"); });
  EXPECT_NE(e.find("toy_gian: unknown key"), std::string::npos) << e;
  // The reference lists both.
  const std::string reference = SceneReference();
  EXPECT_NE(reference.find("`toy_gain`"), std::string::npos);
  EXPECT_NE(reference.find("### `bodies[].toy`"), std::string::npos);
  // A key another model already has is refused when the tables are built.
  RegisterContactModel({.name = "toy-clash",
                        .make = [](const ContactModelInputs&) -> std::unique_ptr<ContactModel> { return nullptr; },
                        .pair_params = ParamBlock(ContactParamTable())});
  EXPECT_THROW(SceneReference(), std::logic_error);
  RegisterContactModel({.name = "toy-clash",
                        .make = [](const ContactModelInputs&) -> std::unique_ptr<ContactModel> { return nullptr; }});
  EXPECT_NO_THROW(SceneReference());
}

TEST(ToyModel, RunsInAnExperimentWithItsPairKeySwept) {
  RegisterToySpring();
  TempDir dir;
  std::ofstream(dir / "scene.yaml") << kScene;
  std::ofstream(dir / "run.yaml") << "name: toy\nscene: scene.yaml\nmodels: [toy-spring]\nmoving_body: ball\n"
                                     "trajectory: {type: slide, duration: 0.01}\n"
                                     "sweep: {toy_gain: [3, 7], pointshell_charge: [2, 4]}\n";
  const ExperimentConfig config = LoadExperimentConfig(dir / "run.yaml");
  ASSERT_EQ(ExpandJobs(config).size(), 4u);
  RunOptions o;
  o.out_dir = dir / "out";
  o.assets.cache_dir = dir / "cache";
  o.assets.verbose = false;
  o.progress = false;
  RunExperiment(config, o);
  // Every cycle of every job: the force on B is gain * charge_A * 5 * (p_A - p_B), B at the
  // origin; cycles.csv records the force on the moving body, A: its opposite.
  const auto rows = Rows(dir / "out" / "cycles.csv");
  ASSERT_GT(rows.size(), 4u);
  const auto& h = rows.front();
  const int job = Column(h, "job"), x = Column(h, "x"), y = Column(h, "y"), z = Column(h, "z"), fx = Column(h, "fx"),
            fy = Column(h, "fy"), fz = Column(h, "fz");
  const double k_of_job[] = {3 * 2 * 5, 3 * 4 * 5, 7 * 2 * 5, 7 * 4 * 5};
  int checked = 0;
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const auto& r = rows[i];
    const double k = k_of_job[std::stoi(r[job])];
    const double p[] = {std::stod(r[x]), std::stod(r[y]), std::stod(r[z])};
    const double f[] = {std::stod(r[fx]), std::stod(r[fy]), std::stod(r[fz])};
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(f[a], -k * p[a], 1e-6 * k) << "row " << i << " axis " << a;
    ++checked;
  }
  EXPECT_EQ(checked, static_cast<int>(rows.size()) - 1);
}

}  // namespace
}  // namespace contactlab
