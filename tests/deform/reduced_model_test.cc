#include "deform/reduced_model.h"

#include <gtest/gtest.h>

#include <fstream>

#include "deform/mode_export.h"
#include "beam_fixture.h"
#include "test_support.h"
#include "util/atomic_file.h"
#include "util/error.h"

namespace contactlab {
namespace {

using testing::BeamOptions;
using testing::MakeBeam;

TEST(ReducedModel, FileRoundTripPreservesEverything) {
  testing::TempDir dir;
  const ReducedModel model = BuildReducedModel(MakeBeam(TetSplit::kSix, 8), BeamOptions(6, ReducedModelKind::kStVK), "beam");
  SaveReducedModel(model, dir / "beam.rm");
  const ReducedModel back = LoadReducedModel(dir / "beam.rm");
  EXPECT_EQ(back.source, "beam");
  EXPECT_EQ(back.r(), 6);
  EXPECT_EQ(back.kind(), ReducedModelKind::kStVK);
  EXPECT_EQ(back.mesh.num_tets(), model.mesh.num_tets());
  EXPECT_EQ(back.fixed, model.fixed);
  EXPECT_EQ(back.basis, model.basis);
  EXPECT_EQ(back.eigenvalues, model.eigenvalues);
  EXPECT_EQ(back.forces.cubic(), model.forces.cubic());
  EXPECT_EQ(back.forces.quadratic(), model.forces.quadratic());
  EXPECT_EQ(back.material.poisson_ratio, model.material.poisson_ratio);
  EXPECT_EQ(back.anchoring.kind, Anchoring::Kind::kBelowPlane);
  EXPECT_NE(DescribeReducedModel(back).find("reduced StVK"), std::string::npos);
}

TEST(ReducedModel, CorruptFileIsRejectedNamingTheFile) {
  testing::TempDir dir;
  const ReducedModel model = BuildReducedModel(MakeBeam(TetSplit::kSix, 4), BeamOptions(3, ReducedModelKind::kLinear), "beam");
  SaveReducedModel(model, dir / "beam.rm");
  std::string bytes = ReadWholeFile(dir / "beam.rm");
  bytes[bytes.size() / 2] ^= 0x5a;
  WriteFileAtomically(dir / "bad.rm", bytes);
  try {
    LoadReducedModel(dir / "bad.rm");
    FAIL() << "a corrupt file was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("bad.rm"), std::string::npos);
  }
  EXPECT_THROW(LoadReducedModel(dir / "missing.rm"), Error);
}

TEST(ReducedModel, BadParametersGiveClearErrors) {
  const TetMesh mesh = MakeBeam(TetSplit::kSix, 4);
  auto expect_error = [&](ReducedModelOptions o, const std::string& fragment, const TetMesh* m = nullptr) {
    try {
      BuildReducedModel(m ? *m : mesh, o, "beam.obj");
      ADD_FAILURE() << "accepted; expected an error containing '" << fragment << "'";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("beam.obj"), std::string::npos) << e.what();
    }
  };
  auto o = BeamOptions(4, ReducedModelKind::kStVK);
  o.material.poisson_ratio = 0.5;
  expect_error(o, "Poisson");
  o = BeamOptions(4, ReducedModelKind::kStVK);
  o.material.youngs_modulus = -1;
  expect_error(o, "Young");
  o = BeamOptions(4, ReducedModelKind::kStVK);
  o.anchoring = Anchoring::BelowY(-1);
  expect_error(o, "no vertex");
  // 2 x 1 x 1 cells anchored at one end: 8 free vertices, 24 DOFs.
  const TetMesh tiny = MakeBoxTetMesh(Eigen::Vector3d::Zero(), Eigen::Vector3d(2, 1, 1), 2, 1, 1);
  expect_error(BeamOptions(30, ReducedModelKind::kLinear), "free degrees of freedom", &tiny);
  expect_error(BeamOptions(30, ReducedModelKind::kStVK), "free degrees of freedom", &tiny);
  expect_error(BeamOptions(kMaxReducedModes + 1, ReducedModelKind::kStVK), "modes r");
  expect_error(BeamOptions(0, ReducedModelKind::kStVK), "modes r");
}

TEST(ReducedModel, VtkExportHasOneVectorFieldPerMode) {
  testing::TempDir dir;
  const ReducedModel model = BuildReducedModel(MakeBeam(TetSplit::kSix, 4), BeamOptions(3, ReducedModelKind::kLinear), "beam");
  ExportModesVtk(model, dir / "modes.vtk");
  const std::string text = ReadWholeFile(dir / "modes.vtk");
  EXPECT_EQ(text.rfind("# vtk DataFile Version 3.0", 0), 0u);
  for (int j = 0; j < 3; ++j) EXPECT_NE(text.find("VECTORS mode_" + std::to_string(j)), std::string::npos);
  EXPECT_NE(text.find("CELLS " + std::to_string(model.mesh.num_tets())), std::string::npos);
}

}  // namespace
}  // namespace contactlab
