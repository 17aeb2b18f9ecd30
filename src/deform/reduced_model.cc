// Precomputation and files of reduced deformable models (Barbič & James 2008, sec. 4.1).
#include "deform/reduced_model.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <sstream>

#include "deform/modal_analysis.h"
#include "deform/nonlinear_basis.h"
#include "util/binary_io.h"
#include "util/error.h"
#include "util/progress.h"

namespace contactlab {
namespace {

constexpr char kMagic[] = "CLRM";
constexpr std::uint32_t kVersion = 1;

void PutMatrix(BinaryWriter& w, const Eigen::MatrixXd& m) {
  w.Put<std::int64_t>(m.rows());
  w.Put<std::int64_t>(m.cols());
  w.PutArray(std::vector<double>(m.data(), m.data() + m.size()));
}

Eigen::MatrixXd GetMatrix(BinaryReader& r, const std::string& what) {
  const auto rows = r.Get<std::int64_t>(what + " rows");
  const auto cols = r.Get<std::int64_t>(what + " cols");
  const std::vector<double> v = r.GetArray<double>(what);
  // rows x cols must equal the values read, without overflow; and since an empty matrix
  // (0 x n) holds no values, nothing else bounds n: each dimension is also held to
  // max(values, 1024), or a corrupt 0 x 2^62 matrix made later whole-matrix checks run for hours.
  const std::uint64_t n = v.size(), limit = std::max<std::uint64_t>(n, 1024);
  const bool fits = rows >= 0 && cols >= 0 && std::uint64_t(rows) <= limit && std::uint64_t(cols) <= limit &&
                    (cols == 0 ? n == 0 : std::uint64_t(rows) == n / std::uint64_t(cols) && n % std::uint64_t(cols) == 0);
  if (!fits) {
    r.Corrupt(what + ": " + std::to_string(rows) + " x " + std::to_string(cols) + " does not match " +
              std::to_string(v.size()) + " values");
  }
  return Eigen::Map<const Eigen::MatrixXd>(v.data(), rows, cols);
}

}  // namespace

Eigen::VectorXd ModeFrequencies(const ReducedModel& model) {
  return model.eigenvalues.array().max(0.0).sqrt() / (2 * std::numbers::pi);
}

ReducedModel BuildReducedModel(const TetMesh& mesh, const ReducedModelOptions& options, const std::string& source) {
  const auto start = std::chrono::steady_clock::now();
  const std::string where = "reduce " + source;
  options.material.Validate(where);
  const int r = options.modes;
  if (r < 1 || r > kMaxReducedModes) {
    Fail(where, "the number of modes r must be in [1, " + std::to_string(kMaxReducedModes) + "], got " + std::to_string(r));
  }
  if (options.linear_modes < 0 || options.linear_modes > r) Fail(where, "linear_modes must be in [0, r]");

  ReducedModel model;
  model.source = source;
  model.mesh = mesh;
  model.anchoring = options.anchoring;
  model.material = options.material;
  model.mass = options.mass;
  model.fixed = FindFixedVertices(mesh, options.anchoring, where);

  int free_dofs = 0;
  for (auto f : model.fixed) free_dofs += f ? 0 : 3;
  const int deformable_dofs = free_dofs - (options.anchoring.anchored() ? 0 : 6);
  if (r > deformable_dofs) {
    Fail(where, "r = " + std::to_string(r) + " exceeds the " + std::to_string(deformable_dofs) +
                    " free degrees of freedom of the simulation mesh; use fewer modes or more cells");
  }

  // Full FEM matrices.
  const StVKFem fem(mesh, options.material, where);
  const SparseMatrixd M = fem.MassMatrix(options.mass);
  const SparseMatrixd K = fem.LinearStiffness();

  // Linear modes; for reduced StVK also modal derivatives and mass-PCA.
  const bool linear = options.kind == ReducedModelKind::kLinear;
  const int m = linear ? r : (options.linear_modes > 0 ? options.linear_modes : DefaultLinearModeCount(r));
  const LinearModes modes = ComputeLinearModes(K, M, model.fixed, m, where);
  model.eigenvalues = modes.eigenvalues;
  model.eigen_residual = modes.max_relative_residual;
  if (linear) {
    model.basis = modes.shapes;
  } else {
    if (m + m * (m + 1) / 2 < r) {
      Fail(where, "r = " + std::to_string(r) + " exceeds the " + std::to_string(m + m * (m + 1) / 2) +
                      " linear modes and modal derivatives of " + std::to_string(m) + " modes");
    }
    Eigen::MatrixXd derivatives;
    {
      Progress progress("modal derivatives", m * (m + 1) / 2);
      derivatives = ComputeModalDerivatives(fem, mesh, K, M, model.fixed, modes,
                                            options.show_progress ? &progress : nullptr, where);
    }
    model.basis = MassPca(ScaledModesAndDerivatives(modes, derivatives, M), M, r, where);
  }
  {
    Progress progress(linear ? "reduced stiffness" : "cubic polynomials", fem.num_tets());
    model.forces = ReducedInternalForces::Compute(fem, model.basis, options.kind,
                                                  options.show_progress ? &progress : nullptr);
  }
  model.build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return model;
}

void SaveReducedModel(const ReducedModel& model, const std::filesystem::path& path) {
  BinaryWriter w;
  w.PutString(model.source);
  w.Put<std::int32_t>(std::int32_t(model.kind()));
  w.Put<std::int32_t>(model.mass == MassKind::kLumped ? 0 : 1);
  w.Put<double>(model.material.youngs_modulus);
  w.Put<double>(model.material.poisson_ratio);
  w.Put<double>(model.material.density);
  // Anchoring.
  const Anchoring& a = model.anchoring;
  w.Put<std::int32_t>(std::int32_t(a.kind));
  for (int c = 0; c < 3; ++c) w.Put<double>(a.normal[c]);
  w.Put<double>(a.offset);
  for (int c = 0; c < 3; ++c) w.Put<double>(a.box.min[c]);
  for (int c = 0; c < 3; ++c) w.Put<double>(a.box.max[c]);
  // Mesh.
  w.Put<double>(model.mesh.cell_size);
  std::vector<double> verts;
  verts.reserve(3 * model.mesh.vertices.size());
  for (const auto& p : model.mesh.vertices) verts.insert(verts.end(), {p.x(), p.y(), p.z()});
  w.PutArray(verts);
  std::vector<std::int32_t> tets;
  tets.reserve(4 * model.mesh.tets.size());
  for (const auto& t : model.mesh.tets) tets.insert(tets.end(), {t[0], t[1], t[2], t[3]});
  w.PutArray(tets);
  w.PutArray(model.fixed);
  // Basis, modes and polynomial coefficients.
  PutMatrix(w, model.basis);
  PutMatrix(w, model.eigenvalues);
  PutMatrix(w, model.forces.linear());
  PutMatrix(w, model.forces.quadratic());
  PutMatrix(w, model.forces.cubic());
  w.Put<double>(model.eigen_residual);
  w.Put<double>(model.build_seconds);
  w.Save(path, kMagic, kVersion);
}

ReducedModel LoadReducedModel(const std::filesystem::path& path) {
  BinaryReader r(path, kMagic, kVersion);
  ReducedModel model;
  model.source = r.GetString("source");
  const auto kind = r.Get<std::int32_t>("model kind");
  if (kind != 0 && kind != 1) r.Corrupt("unknown model kind " + std::to_string(kind));
  const auto mass = r.Get<std::int32_t>("mass kind");
  if (mass != 0 && mass != 1) r.Corrupt("unknown mass kind " + std::to_string(mass));
  model.mass = mass == 0 ? MassKind::kLumped : MassKind::kConsistent;
  model.material.youngs_modulus = r.Get<double>("E");
  model.material.poisson_ratio = r.Get<double>("nu");
  model.material.density = r.Get<double>("rho");
  model.material.Validate(r.file());
  Anchoring& a = model.anchoring;
  const auto akind = r.Get<std::int32_t>("anchoring kind");
  if (akind < 0 || akind > 3) r.Corrupt("unknown anchoring kind " + std::to_string(akind));
  a.kind = Anchoring::Kind(akind);
  for (int c = 0; c < 3; ++c) a.normal[c] = r.Get<double>("anchoring normal");
  a.offset = r.Get<double>("anchoring offset");
  for (int c = 0; c < 3; ++c) a.box.min[c] = r.Get<double>("anchoring box");
  for (int c = 0; c < 3; ++c) a.box.max[c] = r.Get<double>("anchoring box");
  model.mesh.cell_size = r.Get<double>("cell size");
  const std::vector<double> verts = r.GetArray<double>("vertices");
  const std::vector<std::int32_t> tets = r.GetArray<std::int32_t>("tets");
  if (verts.size() % 3 != 0 || tets.size() % 4 != 0 || tets.empty()) r.Corrupt("mesh arrays have impossible sizes");
  const int nv = int(verts.size() / 3);
  for (int v = 0; v < nv; ++v) model.mesh.vertices.emplace_back(verts[3 * v], verts[3 * v + 1], verts[3 * v + 2]);
  for (std::size_t t = 0; t < tets.size(); t += 4) {
    for (int c = 0; c < 4; ++c)
      if (tets[t + c] < 0 || tets[t + c] >= nv) r.Corrupt("tet " + std::to_string(t / 4) + " has an out-of-range vertex");
    model.mesh.tets.emplace_back(tets[t], tets[t + 1], tets[t + 2], tets[t + 3]);
  }
  model.fixed = r.GetArray<std::uint8_t>("fixed flags");
  if (int(model.fixed.size()) != nv) r.Corrupt("fixed flags do not match the vertex count");
  model.basis = GetMatrix(r, "basis");
  if (model.basis.rows() != 3 * nv || model.basis.cols() < 1 || model.basis.cols() > kMaxReducedModes) {
    r.Corrupt("basis size does not match the mesh");
  }
  const Eigen::MatrixXd eig = GetMatrix(r, "eigenvalues");
  if (eig.cols() != 1) r.Corrupt("eigenvalues are not a vector");
  model.eigenvalues = eig.col(0);
  Eigen::MatrixXd A = GetMatrix(r, "linear coefficients");
  Eigen::MatrixXd B = GetMatrix(r, "quadratic coefficients");
  Eigen::MatrixXd C = GetMatrix(r, "cubic coefficients");
  if (A.rows() != model.basis.cols()) r.Corrupt("coefficient size does not match the basis");
  model.forces = ReducedInternalForces(ReducedModelKind(kind), std::move(A), std::move(B), std::move(C), r.file());
  model.eigen_residual = r.Get<double>("eigen residual");
  model.build_seconds = r.Get<double>("build seconds");
  r.ExpectEnd();
  return model;
}

std::string DescribeReducedModel(const ReducedModel& model) {
  std::ostringstream s;
  const Aabb b = model.mesh.Bounds();
  int fixed = 0;
  for (auto f : model.fixed) fixed += f;
  s << "source:        " << model.source << "\n"
    << "kind:          " << (model.kind() == ReducedModelKind::kStVK ? "reduced StVK (cubic polynomials)" : "linear modal")
    << "\n"
    << "modes r:       " << model.r() << "\n"
    << "mesh:          " << model.mesh.num_vertices() << " vertices, " << model.mesh.num_tets() << " tets, cell "
    << model.mesh.cell_size << " m, volume " << model.mesh.Volume() << " m^3\n"
    << "box:           [" << b.min.transpose() << "] .. [" << b.max.transpose() << "]\n"
    << "anchoring:     " << model.anchoring.Describe() << " (" << fixed << " fixed vertices)\n"
    << "material:      E " << model.material.youngs_modulus << " Pa, nu " << model.material.poisson_ratio << ", rho "
    << model.material.density << " kg/m^3, " << (model.mass == MassKind::kLumped ? "lumped" : "consistent") << " mass\n"
    << "frequencies:   " << ModeFrequencies(model).transpose() << " Hz\n"
    << "eig residual:  " << model.eigen_residual << "\n"
    << "coefficients:  " << (model.forces.linear().size() + model.forces.quadratic().size() + model.forces.cubic().size())
    << " doubles\n"
    << "build time:    " << model.build_seconds << " s\n";
  return s.str();
}

}  // namespace contactlab
