// Bullet GImpact contact manifolds -> penalty wrench (see bullet_contact_model.h).
#include "baselines/bullet/bullet_contact_model.h"

#include <btBulletCollisionCommon.h>
#include <BulletCollision/Gimpact/btGImpactCollisionAlgorithm.h>
#include <BulletCollision/Gimpact/btGImpactShape.h>
#include <GIMPACTUtils/btGImpactConvexDecompositionShape.h>

#include <cmath>
#include <string>
#include <vector>

#include "contact/contact_accumulator.h"
#include "contact/contact_recorder.h"
#include "contact/friction_matching.h"
#include "util/error.h"

namespace contactlab {
namespace {

// Room for the manifold points of one query that carry friction (those past it carry none; their
// normal force is kept): GImpact reports up to 16 per overlapping triangle pair.
constexpr int kMaxFrictionContacts = 1 << 16;

btTransform ToBullet(const Pose& X) {
  const Eigen::Matrix3d R = X.R();
  btMatrix3x3 basis(R(0, 0), R(0, 1), R(0, 2), R(1, 0), R(1, 1), R(1, 2), R(2, 0), R(2, 1), R(2, 2));
  return btTransform(basis, btVector3(X.translation.x(), X.translation.y(), X.translation.z()));
}

Eigen::Vector3d FromBullet(const btVector3& v) { return {v.x(), v.y(), v.z()}; }

// One body: our copies of the mesh arrays, Bullet's view of them, the shape and the object.
struct BulletBody {
  std::vector<btScalar> vertices;  // (3 #V)
  std::vector<int> indices;        // (3 #T)
  std::unique_ptr<btTriangleIndexVertexArray> arrays;
  std::unique_ptr<btCollisionShape> shape;
  btCollisionObject object;

  void Build(const TriangleMesh& mesh, double margin, BulletShape kind, const std::string& where) {
    if (mesh.empty()) Fail(where, "the mesh '" + mesh.name + "' has no triangles");
    const int n = mesh.num_vertices();
    vertices.reserve(3 * std::size_t(n));
    for (const Eigen::Vector3d& v : mesh.vertices) vertices.insert(vertices.end(), {v.x(), v.y(), v.z()});
    indices.reserve(3 * mesh.triangles.size());
    for (const Eigen::Vector3i& t : mesh.triangles) {
      if (t.minCoeff() < 0 || t.maxCoeff() >= n) Fail(where, "the mesh '" + mesh.name + "' has an invalid vertex index");
      indices.insert(indices.end(), {t[0], t[1], t[2]});
    }
    arrays = std::make_unique<btTriangleIndexVertexArray>(mesh.num_triangles(), indices.data(), int(3 * sizeof(int)), n,
                                                          vertices.data(), int(3 * sizeof(btScalar)));
    switch (kind) {
      case BulletShape::kGImpact: {
        auto gimpact = std::make_unique<btGImpactMeshShape>(arrays.get());
        gimpact->setMargin(margin);
        gimpact->updateBound();
        shape = std::move(gimpact);
        break;
      }
      case BulletShape::kConvexHull: {
        // All vertices, then the hull's own (btConvexHullComputer drops the interior ones).
        auto hull = std::make_unique<btConvexHullShape>(vertices.data(), n, int(3 * sizeof(btScalar)));
        hull->optimizeConvexHull();
        hull->setMargin(margin);
        hull->recalcLocalAabb();
        shape = std::move(hull);
        break;
      }
      case BulletShape::kConvexDecomposition: {
        // The pieces are btConvexHullShapes in the compound's frame; the margin is each piece's.
        auto pieces = std::make_unique<btGImpactConvexDecompositionShape>(arrays.get(), btVector3(1, 1, 1), margin);
        if (pieces->getNumChildShapes() == 0) Fail(where, "the convex decomposition of '" + mesh.name + "' is empty");
        for (int i = 0; i < pieces->getNumChildShapes(); ++i) pieces->getChildShape(i)->setMargin(margin);
        pieces->setMargin(margin);
        pieces->updateBound();
        shape = std::move(pieces);
        break;
      }
    }
    object.setCollisionShape(shape.get());
  }
};

// Sums manifold points into a ContactAccumulator as contactPairTest reports them.
struct Collector final : btCollisionWorld::ContactResultCallback {
  const btCollisionObject* object_B = nullptr;
  Eigen::Matrix3d R_BW;
  Eigen::Vector3d p_WB;
  double margin_sum = 0;
  ContactAccumulator acc;
  std::int64_t reported = 0;
  ContactRecorder contacts;  // the manifold points used (world frame), when kept
  // Friction on: the points matched between queries, this query's sums, A's pose, B's rotation.
  MatchedFrictionAnchors* anchors = nullptr;
  const FrictionParams* friction = nullptr;
  FrictionSums sums;
  Pose X_AW;
  Eigen::Matrix3d R_WB;

  btScalar addSingleResult(btManifoldPoint& cp, const btCollisionObjectWrapper* wrap0, int, int,
                           const btCollisionObjectWrapper* wrap1, int, int) override {
    ++reported;
    // m_normalWorldOnB lies on the callback's object 1 and points toward its object 0.
    Eigen::Vector3d n_W = FromBullet(cp.m_normalWorldOnB);
    if (wrap1->getCollisionObject() != object_B) n_W = -n_W;
    const double depth = -double(cp.getDistance()) - margin_sum;
    if (!(depth > 0) || !n_W.allFinite()) return 0;
    const Eigen::Vector3d p_W = 0.5 * (FromBullet(cp.m_positionWorldOnA) + FromBullet(cp.m_positionWorldOnB));
    const Eigen::Vector3d N_B = R_BW * n_W;
    const Eigen::Vector3d p_B = R_BW * (p_W - p_WB);
    acc.Add(p_B, N_B, -depth, N_B);
    if (contacts.keeping()) contacts.Add(p_W, -n_W.normalized(), depth);
    if (anchors != nullptr) {
      const Eigen::Vector3d n_B = N_B.normalized();
      Eigen::Vector3d u;
      const bool slid = anchors->Add(X_AW * p_W, p_B, n_B, depth, n_B, *friction, &sums, &u);
      if (contacts.keeping()) contacts.AddFriction(R_WB * (depth * u), !slid);
    }
    return 0;
  }
};

}  // namespace

struct BulletContactModel::Impl {
  std::shared_ptr<const TriangleMesh> mesh_A, mesh_B;
  btDefaultCollisionConfiguration configuration;
  btCollisionDispatcher dispatcher{&configuration};
  btDbvtBroadphase broadphase;
  btCollisionWorld world{&dispatcher, &broadphase, &configuration};
  btGImpactCollisionAlgorithm::CreateFunc closest_points_func;
  BulletBody A, B;
  Collector collector;
  MatchedFrictionAnchors anchors;  // friction on
};

BulletContactModel::BulletContactModel(std::shared_ptr<const TriangleMesh> mesh_A,
                                       std::shared_ptr<const TriangleMesh> mesh_B, const BulletContactParams& params)
    : impl_(std::make_unique<Impl>()), params_(params) {
  const std::string where = "contact model bullet";
  if (!mesh_A || !mesh_B) Fail(where, "needs both meshes");
  CheckPenaltyParams(params.penalty, where);
  const BulletOwnParams& own = params.own;
  if (!(own.margin >= 0) || !std::isfinite(own.margin)) {
    Fail(where, "bullet_margin must be finite and non-negative");
  }
  Impl& m = *impl_;
  m.mesh_A = std::move(mesh_A);
  m.mesh_B = std::move(mesh_B);
  // GImpact for ordinary collision pairs, and for closest-point queries (contactPairTest).
  btGImpactCollisionAlgorithm::registerAlgorithm(&m.dispatcher);
  m.dispatcher.registerClosestPointsCreateFunc(GIMPACT_SHAPE_PROXYTYPE, GIMPACT_SHAPE_PROXYTYPE,
                                               &m.closest_points_func);
  m.A.Build(*m.mesh_A, own.margin, own.shape, where + " (body A)");
  m.B.Build(*m.mesh_B, own.margin, own.shape, where + " (body B)");
  m.collector.object_B = &m.B.object;
  m.collector.margin_sum = own.subtract_margins ? 2 * own.margin : 0.0;
  if (params.friction.on()) {
    m.anchors = MatchedFrictionAnchors(kMaxFrictionContacts, params.friction.match_radius);
    m.collector.anchors = &m.anchors;
    m.collector.friction = &params_.friction;
  }
}

void BulletContactModel::Reset() { impl_->anchors.Reset(); }

BulletContactModel::~BulletContactModel() = default;

bool BulletContactModel::KeepContacts(int max_contacts) {
  impl_->collector.contacts.Keep(max_contacts, false, params_.friction.on());
  return true;
}

void BulletContactModel::LatestContacts(ContactList* out) const { impl_->collector.contacts.Fill(Pose(), 1.0, out); }

ContactResult BulletContactModel::Evaluate(const ContactQuery& query) {
  Impl& m = *impl_;
  // Place both objects and reset the collector.
  m.A.object.setWorldTransform(ToBullet(query.X_WA));
  m.B.object.setWorldTransform(ToBullet(query.X_WB));
  Collector& c = m.collector;
  c.R_BW = query.X_WB.R().transpose();
  c.p_WB = query.X_WB.translation;
  c.acc = ContactAccumulator();
  c.reported = 0;
  c.contacts.Clear();
  if (c.anchors != nullptr) {
    c.anchors->BeginQuery(query.X_WB.Inverse() * query.X_WA);
    c.sums.Clear();
    c.X_AW = query.X_WA.Inverse();
    c.R_WB = query.X_WB.R();
  }
  // Manifold points of A (object 0) against B (object 1).
  m.world.contactPairTest(&m.A.object, &m.B.object, c);
  ContactResult out;
  c.acc.Finish(params_.penalty, query.X_WB, &out);
  if (c.anchors != nullptr) {
    FinishFriction(c.sums, params_.penalty, c.acc.count(), params_.friction, query.X_WB, &c.contacts, &out);
  }
  out.stats.nodes_visited = c.reported;
  return out;
}

}  // namespace contactlab
