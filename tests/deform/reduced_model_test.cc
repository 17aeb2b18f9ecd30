#include "deform/reduced_model.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "deform/mode_export.h"
#include "beam_fixture.h"
#include "test_support.h"
#include "util/atomic_file.h"
#include "util/binary_io.h"
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

// A checksum-valid file whose cubic coefficients claim 0 x 2^62 (no values, so the value
// count matched) is refused at once: it made the finiteness check loop over 2^62 columns.
// Found by tests/fuzz/fuzz_reduced_model.
TEST(ReducedModel, EmptyMatrixWithAnAbsurdDimensionIsRefused) {
  testing::TempDir dir;
  const ReducedModel model = BuildReducedModel(MakeBeam(TetSplit::kSix, 4), BeamOptions(3, ReducedModelKind::kLinear), "beam");
  SaveReducedModel(model, dir / "beam.rm");
  const std::string bytes = ReadWholeFile(dir / "beam.rm");
  // Container: magic[8] u32 version u64 size | payload | u32 CRC. The payload ends with the
  // cubic coefficients (i64 rows, i64 cols, u64 count, count doubles), then two doubles.
  const std::string payload = bytes.substr(20, bytes.size() - 24);
  const std::size_t cubic = 24 + 8 * std::size_t(model.forces.cubic().size());
  BinaryWriter w;
  for (const char c : payload.substr(0, payload.size() - 16 - cubic)) w.Put<char>(c);
  w.Put<std::int64_t>(0);
  w.Put<std::int64_t>(std::int64_t(1) << 62);
  w.Put<std::uint64_t>(0);
  for (const char c : payload.substr(payload.size() - 16)) w.Put<char>(c);
  w.Save(dir / "absurd.rm", "CLRM", 1);
  try {
    LoadReducedModel(dir / "absurd.rm");
    FAIL() << "a 0 x 2^62 matrix was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("absurd.rm"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("cubic coefficients: 0 x 4611686018427387904"), std::string::npos) << e.what();
  }
  // The same file with the original header loads: only the dimension was wrong.
  BinaryWriter same;
  for (const char c : payload) same.Put<char>(c);
  same.Save(dir / "same.rm", "CLRM", 1);
  EXPECT_EQ(LoadReducedModel(dir / "same.rm").r(), 3);
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

// reduce-export's basis and vertices read back bit for bit (they were printed with 9 digits).
TEST(ReducedModel, VtkExportReadsBackBitForBit) {
  testing::TempDir dir;
  const ReducedModel model = BuildReducedModel(MakeBeam(TetSplit::kSix, 4), BeamOptions(3, ReducedModelKind::kLinear), "beam");
  const double scale = 1.0 / 3;
  ExportModesVtk(model, dir / "modes.vtk", scale);
  std::istringstream in(ReadWholeFile(dir / "modes.vtk"));
  std::string line;
  while (std::getline(in, line) && line.rfind("POINTS ", 0) != 0) {}
  for (const Eigen::Vector3d& p : model.mesh.vertices) {
    std::string x, y, z;
    in >> x >> y >> z;
    EXPECT_EQ(Eigen::Vector3d(std::strtod(x.c_str(), nullptr), std::strtod(y.c_str(), nullptr), std::strtod(z.c_str(), nullptr)), p);
  }
  int checked = 0;
  for (int j = 0; j < model.r(); ++j) {
    while (std::getline(in, line) && line != "VECTORS mode_" + std::to_string(j) + " double") {}
    for (int row = 0; row < model.basis.rows(); ++row) {
      std::string cell;
      in >> cell;
      EXPECT_EQ(std::strtod(cell.c_str(), nullptr), scale * model.basis(row, j)) << "mode " << j << " row " << row;
      ++checked;
    }
  }
  EXPECT_EQ(checked, model.basis.size());
}

}  // namespace
}  // namespace contactlab
