// The vectorised halfspace sums against ContactAccumulator::Add in double, point by point, with
// p_B = R p + t and N_B = R n formed in double: equal to float rounding, for batch sizes on and
// off the vector width, and through the buffer that picks the points in contact.
#include "contact/halfspace_contacts.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>
#include <vector>

namespace contactlab {
namespace {

struct Fixture {
  Pointshell s;
  BatchTransform X;
  Eigen::Matrix3d R;
  Eigen::Vector3d t;

  explicit Fixture(int points, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1.f, 1.f);
    for (int i = 0; i < points; ++i) {
      s.x.push_back(0.05f * u(rng));
      s.y.push_back(0.05f * u(rng));
      s.z.push_back(0.05f * u(rng));
      Eigen::Vector3f n(u(rng), u(rng), u(rng));
      n.normalize();
      s.nx.push_back(n.x());
      s.ny.push_back(n.y());
      s.nz.push_back(n.z());
    }
    R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    t = Eigen::Vector3d(0.02, -0.01, 0.03);
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) X.r[3 * i + j] = float(R(i, j));
      X.t[i] = float(t[i]);
    }
  }

  // The reference: Add per point, in double, from the same float inputs.
  void Reference(int i, float d, ContactAccumulator* acc) const {
    Eigen::Matrix3d Rf;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) Rf(r, c) = X.r[3 * r + c];
    const Eigen::Vector3d tf(X.t[0], X.t[1], X.t[2]);
    const Eigen::Vector3d p = Rf * Eigen::Vector3d(s.x[i], s.y[i], s.z[i]) + tf;
    const Eigen::Vector3d N = Rf * Eigen::Vector3d(s.nx[i], s.ny[i], s.nz[i]);
    acc->Add(p, N, d, N);
  }
};

void ExpectSameResult(const ContactAccumulator& got, const ContactAccumulator& want) {
  PenaltyParams penalty;
  penalty.k_C = 1000;
  penalty.L = 0;
  const Pose X_WB = Pose::Identity();
  ContactResult a, b;
  got.Finish(penalty, X_WB, &a);
  want.Finish(penalty, X_WB, &b);
  EXPECT_EQ(a.stats.points_in_contact, b.stats.points_in_contact);
  EXPECT_DOUBLE_EQ(a.stats.max_penetration, b.stats.max_penetration);
  // Float rounding of the terms and of sums of at most a few hundred of them.
  const double f_scale = b.on_B.force.norm() + 1e-3 * b.stats.points_in_contact;
  EXPECT_LT((a.on_B.force - b.on_B.force).norm(), 2e-5 * f_scale);
  EXPECT_LT((a.on_B.torque - b.on_B.torque).norm(), 2e-5 * 0.1 * f_scale);
  const double k_scale = b.K_B.cwiseAbs().maxCoeff();
  EXPECT_GT(k_scale, 0);
  EXPECT_LT((a.K_B - b.K_B).cwiseAbs().maxCoeff(), 2e-5 * k_scale);
}

TEST(HalfspaceContacts, EqualAccumulatorAddToFloatRounding) {
  const Fixture f(600, 3);
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> pick(0, 599);
  std::uniform_real_distribution<float> depth(1e-5f, 2e-3f);
  for (const int n : {1, 7, 15, 16, 17, 33, 100, 256}) {
    std::vector<std::int32_t> index(n);
    std::vector<float> d(n);
    ContactAccumulator got, want;
    for (int k = 0; k < n; ++k) {
      index[k] = pick(rng);
      d[k] = -depth(rng);
      f.Reference(index[k], d[k], &want);
    }
    AddHalfspaceContacts(f.s, f.X, index.data(), d.data(), n, &got);
    SCOPED_TRACE(n);
    ExpectSameResult(got, want);
  }
}

TEST(HalfspaceContacts, BufferAddsExactlyThePointsInContact) {
  const int points = 3000;
  const Fixture f(points, 5);
  std::mt19937 rng(13);
  std::uniform_real_distribution<float> u(-2e-3f, 1e-3f);
  std::vector<float> d(points);
  for (float& v : d) v = u(rng);
  d[17] = 0.f;  // touching is not contact
  // Every point in order (the linear traversal), and a scattered subset (a tree level).
  std::vector<std::int32_t> scattered;
  for (int i = points - 1; i >= 0; i -= 3) scattered.push_back(i);
  std::vector<float> scattered_d;
  for (std::int32_t i : scattered) scattered_d.push_back(d[i]);

  ContactAccumulator got, want;
  HalfspaceContactBuffer buffer(f.s, f.X, &got);
  for (int begin = 0; begin < points; begin += 500) buffer.Collect(begin, nullptr, d.data() + begin, 500);
  buffer.Collect(0, scattered.data(), scattered_d.data(), int(scattered.size()));
  buffer.Flush();
  int in_contact = 0;
  for (int i = 0; i < points; ++i) {
    if (d[i] < 0.f) {
      f.Reference(i, d[i], &want);
      ++in_contact;
    }
  }
  for (std::size_t k = 0; k < scattered.size(); ++k) {
    if (scattered_d[k] < 0.f) {
      f.Reference(scattered[k], scattered_d[k], &want);
      ++in_contact;
    }
  }
  ASSERT_GT(in_contact, 2 * HalfspaceContactBuffer::kCapacity);  // several flushes
  EXPECT_EQ(got.count(), in_contact);
  ExpectSameResult(got, want);
}

}  // namespace
}  // namespace contactlab
