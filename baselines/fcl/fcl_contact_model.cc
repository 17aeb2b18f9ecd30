// FCL mesh-mesh contacts -> penalty wrench (see fcl_contact_model.h).
#include "baselines/fcl/fcl_contact_model.h"

#include <cmath>
#include <fcl/fcl.h>
#include <string>

#include "contact/contact_accumulator.h"
#include "contact/contact_recorder.h"
#include "contact/friction_matching.h"
#include "util/error.h"

namespace contactlab {
namespace {

void CheckMesh(const TriangleMesh& mesh, const std::string& where) {
  if (mesh.empty()) Fail(where, "the mesh '" + mesh.name + "' has no triangles");
  const int n = mesh.num_vertices();
  for (const Eigen::Vector3i& t : mesh.triangles) {
    if (t.minCoeff() < 0 || t.maxCoeff() >= n) Fail(where, "the mesh '" + mesh.name + "' has an invalid vertex index");
  }
}

template <class BV>
std::shared_ptr<fcl::CollisionGeometryd> MakeBvh(const TriangleMesh& mesh) {
  std::vector<fcl::Vector3d> vertices(mesh.vertices.begin(), mesh.vertices.end());
  std::vector<fcl::Triangle> triangles;
  triangles.reserve(mesh.triangles.size());
  for (const Eigen::Vector3i& t : mesh.triangles) triangles.emplace_back(t[0], t[1], t[2]);
  auto bvh = std::make_shared<fcl::BVHModel<BV>>();
  bvh->beginModel(int(triangles.size()), int(vertices.size()));
  bvh->addSubModel(vertices, triangles);
  bvh->endModel();
  bvh->computeLocalAABB();
  return bvh;
}

// fcl::Convex of the mesh's vertices and no faces: FCL then finds support points by a linear
// search over the vertices (it walks edges only on a watertight face list, which would stop at
// a local maximum on a concave mesh), so the shape is exactly the vertices' convex hull.
std::shared_ptr<fcl::CollisionGeometryd> MakeConvex(const TriangleMesh& mesh) {
  auto vertices = std::make_shared<const std::vector<fcl::Vector3d>>(mesh.vertices.begin(), mesh.vertices.end());
  auto faces = std::make_shared<const std::vector<int>>();
  auto convex = std::make_shared<fcl::Convexd>(vertices, 0, faces, /*throw_if_invalid=*/false);
  convex->computeLocalAABB();
  return convex;
}

std::shared_ptr<fcl::CollisionGeometryd> MakeGeometry(const TriangleMesh& mesh, const FclContactParams& params,
                                                      const std::string& where) {
  CheckMesh(mesh, where);
  if (params.own.shape == FclShape::kConvex) return MakeConvex(mesh);
  switch (params.own.bv) {
    case FclBv::kObbrss: return MakeBvh<fcl::OBBRSSd>(mesh);
    case FclBv::kObb: return MakeBvh<fcl::OBBd>(mesh);
    case FclBv::kKios: return MakeBvh<fcl::kIOSd>(mesh);
  }
  Fail(where, "unknown fcl_bv");
}

}  // namespace

struct FclContactModel::Impl {
  std::shared_ptr<const TriangleMesh> mesh_A, mesh_B;  // kept alive for the caller's sake
  std::shared_ptr<fcl::CollisionGeometryd> geometry_A, geometry_B;
  std::unique_ptr<fcl::CollisionObjectd> object_A, object_B;
  fcl::CollisionRequestd request;
  fcl::CollisionResultd result;  // reused: clear() keeps the contact vector's capacity
  ContactRecorder contacts;      // the latest query's contacts (world frame), when kept
  MatchedFrictionAnchors anchors;  // friction on: the contacts matched between queries
};

FclContactModel::FclContactModel(std::shared_ptr<const TriangleMesh> mesh_A, std::shared_ptr<const TriangleMesh> mesh_B,
                                 const FclContactParams& params)
    : impl_(std::make_unique<Impl>()), params_(params) {
  const std::string where = "contact model fcl";
  if (!mesh_A || !mesh_B) Fail(where, "needs both meshes");
  CheckPenaltyParams(params.penalty, where);
  if (params.own.max_contacts <= 0) Fail(where, "fcl_max_contacts must be positive");
  impl_->mesh_A = std::move(mesh_A);
  impl_->mesh_B = std::move(mesh_B);
  impl_->geometry_A = MakeGeometry(*impl_->mesh_A, params, where + " (body A)");
  impl_->geometry_B = MakeGeometry(*impl_->mesh_B, params, where + " (body B)");
  impl_->object_A = std::make_unique<fcl::CollisionObjectd>(impl_->geometry_A);
  impl_->object_B = std::make_unique<fcl::CollisionObjectd>(impl_->geometry_B);
  impl_->request = fcl::CollisionRequestd(std::size_t(params.own.max_contacts), /*enable_contact=*/true);
  if (params.friction.on()) impl_->anchors = MatchedFrictionAnchors(params.own.max_contacts, params.friction.match_radius);
}

void FclContactModel::Reset() { impl_->anchors.Reset(); }

FclContactModel::~FclContactModel() = default;

bool FclContactModel::KeepContacts(int max_contacts) {
  impl_->contacts.Keep(max_contacts, false, params_.friction.on());
  return true;
}

void FclContactModel::LatestContacts(ContactList* out) const { impl_->contacts.Fill(Pose(), 1.0, out); }

ContactResult FclContactModel::Evaluate(const ContactQuery& query) {
  Impl& m = *impl_;
  // Place both objects; OBBRSS, OBB and kIOS traversal use the transforms without copying the
  // models (the other BVs copy both hierarchies inside fcl::collide, fcl_params.h).
  m.object_A->setTransform(query.X_WA.R(), query.X_WA.translation);
  m.object_B->setTransform(query.X_WB.R(), query.X_WB.translation);
  m.object_A->computeAABB();
  m.object_B->computeAABB();
  m.result.clear();
  fcl::collide(m.object_A.get(), m.object_B.get(), m.request, m.result);

  // Each contact in B's frame: force on B is k δ n (n from A to B), i.e. d = -δ, N = -n.
  const Eigen::Matrix3d R_BW = query.X_WB.R().transpose();
  const Eigen::Vector3d& p_WB = query.X_WB.translation;
  ContactAccumulator acc;
  m.contacts.Clear();
  const bool keep = m.contacts.keeping();
  const bool friction_on = params_.friction.on();
  FrictionSums friction;
  const Pose X_AW = query.X_WA.Inverse();
  if (friction_on) m.anchors.BeginQuery(query.X_WB.Inverse() * query.X_WA);
  const std::size_t num = m.result.numContacts();
  for (std::size_t i = 0; i < num; ++i) {
    const fcl::Contactd& c = m.result.getContact(i);
    const double depth = c.penetration_depth;
    if (!(depth > 0) || !c.normal.allFinite()) continue;
    const Eigen::Vector3d p_B = R_BW * (c.pos - p_WB);
    const Eigen::Vector3d N_B = -(R_BW * c.normal);
    acc.Add(p_B, N_B, -depth, N_B);
    if (keep) m.contacts.Add(c.pos, c.normal.normalized(), depth);
    if (friction_on) {
      const Eigen::Vector3d n_B = N_B.normalized();
      Eigen::Vector3d u;
      const bool slid = m.anchors.Add(X_AW * c.pos, p_B, n_B, depth, n_B, params_.friction, &friction, &u);
      if (keep) m.contacts.AddFriction(query.X_WB.R() * (depth * u), !slid);
    }
  }
  ContactResult out;
  acc.Finish(params_.penalty, query.X_WB, &out);
  if (friction_on) FinishFriction(friction, params_.penalty, acc.count(), params_.friction, query.X_WB, &m.contacts, &out);
  out.stats.nodes_visited = std::int64_t(num);
  return out;
}

}  // namespace contactlab
