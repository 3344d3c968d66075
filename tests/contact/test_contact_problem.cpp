// The contact problem against cases solvable by hand, and the catalog readings of a torque–twist curve.
#include <cmath>

#include <Eigen/LU>
#include <gtest/gtest.h>

#include "common/error.hpp"
#include "contact/contact_problem.hpp"
#include "contact/torque_twist.hpp"

namespace sw {
namespace {

// Independent springs (diagonal A = 1/k), gaps g, arms r: a pair i carries F_i = k_i·(r_i·ψ − g_i) when positive;
// T = Σ r_i·F_i fixes ψ. Two pairs, both closed: ψ = (T + Σ r k g)/(Σ r² k).
TEST(ContactProblem, TwoSpringsWithGapsClosedForm) {
  ContactProblem p;
  const double k1 = 2e8, k2 = 1e8, g1 = 1e-6, g2 = 3e-6, r = 0.02;
  p.A = Eigen::Vector2d(1 / k1, 1 / k2).asDiagonal();
  p.q = Eigen::Vector2d(g1, g2);
  p.lambda = Eigen::Vector2d(r, r);
  const double T = 20.0;
  const double psi = (T + r * (k1 * g1 + k2 * g2)) / (r * r * (k1 + k2));
  ASSERT_GT(r * psi, g2);  // both closed at this torque (the test's premise)
  const ContactSolution s = solve_contact(p, T);
  EXPECT_NEAR(s.twist_rad, psi, 1e-12 * psi);
  EXPECT_NEAR(s.force_N[0], k1 * (r * psi - g1), 1e-9 * T / r);
  EXPECT_NEAR(s.force_N[1], k2 * (r * psi - g2), 1e-9 * T / r);
  EXPECT_NEAR(p.lambda.dot(s.force_N), T, 1e-12 * T);
}

// A third pair whose gap the twist never reaches stays open with zero force and a positive gap.
TEST(ContactProblem, PairThatMustStayOpen) {
  ContactProblem p;
  const double k = 1e8, r = 0.02;
  p.A = Eigen::Vector3d(1 / k, 1 / k, 1 / k).asDiagonal();
  p.q = Eigen::Vector3d(0.0, 1e-6, 50e-6);
  p.lambda = Eigen::Vector3d(r, r, r);
  const double T = 10.0;
  const ContactSolution s = solve_contact(p, T);
  const double psi = (T + r * k * 1e-6) / (2 * r * r * k);  // pairs 0 and 1 closed
  EXPECT_NEAR(s.twist_rad, psi, 1e-12 * psi);
  EXPECT_EQ(s.force_N[2], 0.0);
  EXPECT_NEAR(s.gap_m[2], 50e-6 - r * psi, 1e-15);
  EXPECT_GT(s.gap_m[2], 0.0);
  EXPECT_EQ(s.in_contact(), 2);
}

// Coupled compliance (a full A): against the brute-force answer, enumerating every active set and keeping the one
// that satisfies all Signorini conditions.
/// n coupled contacts: a random positive definite compliance (scale `c`), gaps in [0, 4] µm, arms 0.02 m.
ContactProblem random_problem(int n, double c) {
  const Eigen::MatrixXd B = Eigen::MatrixXd::Random(n, n);
  ContactProblem p;
  p.A = (B * B.transpose() + n * Eigen::MatrixXd::Identity(n, n)) * c;
  p.q = (Eigen::VectorXd::Random(n).array() + 1.0).matrix() * 2e-6;
  p.lambda = Eigen::VectorXd::Constant(n, 0.02);
  return p;
}

/// The KKT system on the contact set S solved afresh (full-pivot LU): the forces on S, then ψ.
Eigen::VectorXd fresh_kkt(const ContactProblem& p, const std::vector<int>& S, double T) {
  const int m = static_cast<int>(S.size());
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(m + 1, m + 1);
  Eigen::VectorXd rhs(m + 1);
  for (int a = 0; a < m; ++a) {
    for (int b = 0; b < m; ++b) K(a, b) = p.A(S[a], S[b]);
    K(a, m) = -p.lambda[S[a]];
    K(m, a) = p.lambda[S[a]];
    rhs[a] = -p.q[S[a]];
  }
  rhs[m] = T;
  return K.fullPivLu().solve(rhs);
}

TEST(ContactProblem, CoupledMatchesEnumeration) {
  const int n = 5;
  ContactProblem p = random_problem(n, 1e-9);
  p.lambda[1] = -0.02;  // a flank of the other side
  const double T = 5.0;
  const ContactSolution s = solve_contact(p, T);
  int valid = 0;
  for (int mask = 1; mask < (1 << n); ++mask) {
    std::vector<int> S;
    for (int i = 0; i < n; ++i)
      if (mask >> i & 1) S.push_back(i);
    const int m = static_cast<int>(S.size());
    const Eigen::VectorXd z = fresh_kkt(p, S, T);
    Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
    for (int a = 0; a < m; ++a) x[S[a]] = z[a];
    const Eigen::VectorXd gap = p.A * x + p.q - z[m] * p.lambda;
    if ((x.array() >= -1e-12).all() && (gap.array() >= -1e-15).all()) {
      ++valid;
      EXPECT_NEAR(s.twist_rad, z[m], 1e-10 * std::abs(z[m]));
      EXPECT_LT((s.force_N - x).cwiseAbs().maxCoeff(), 1e-8 * T / 0.02);
    }
  }
  EXPECT_EQ(valid, 1);  // a convex problem: exactly one active set satisfies the conditions
}

// Reversal symmetry: mirrored flanks (λ → −λ, same gaps) give the mirrored answer.
TEST(ContactProblem, ReversalSymmetry) {
  ContactProblem p;
  p.A = Eigen::Matrix4d::Identity() * 1e-8;
  p.A(0, 2) = p.A(2, 0) = 2e-9;
  p.A(1, 3) = p.A(3, 1) = 2e-9;
  p.q = Eigen::Vector4d(1e-6, 1e-6, 4e-6, 4e-6);
  p.lambda = Eigen::Vector4d(0.02, -0.02, 0.02, -0.02);
  const ContactSolution plus = solve_contact(p, 30.0), minus = solve_contact(p, -30.0);
  EXPECT_NEAR(plus.twist_rad, -minus.twist_rad, 1e-14);
  EXPECT_NEAR(plus.force_N[0], minus.force_N[1], 1e-9);
  EXPECT_NEAR(plus.force_N[2], minus.force_N[3], 1e-9);
  EXPECT_EQ(plus.force_N[1], 0.0);
}

// A warm start changes the path, not the answer: from the previous torque's contact set (feasible) the solution is
// the cold start's in fewer steps; from a set that cannot carry the torque (the other side's flanks) it starts cold.
TEST(ContactProblem, WarmStartGivesTheSameSolution) {
  const int n = 40;
  ContactProblem p = random_problem(n, 1e-10);
  for (int i = 0; i < n; i += 2) p.lambda[i] = -0.02;
  const ContactSolution before = solve_contact(p, 40.0), cold = solve_contact(p, 50.0);
  const ContactSolution warm = solve_contact(p, 50.0, &before.force_N);
  const ContactSolution reversed = solve_contact(p, -50.0);
  const ContactSolution other_side = solve_contact(p, 50.0, &reversed.force_N);
  ASSERT_GT(cold.in_contact(), 4);
  for (const ContactSolution* s : {&warm, &other_side}) {
    EXPECT_NEAR(s->twist_rad, cold.twist_rad, 1e-12 * std::abs(cold.twist_rad));
    EXPECT_LT((s->force_N - cold.force_N).cwiseAbs().maxCoeff(), 1e-9 * cold.force_N.maxCoeff());
  }
  EXPECT_LT(warm.iterations, cold.iterations);
}

// Many coupled contacts (the passive set's factor grows and shrinks by updates through dozens of steps): the answer
// meets the Signorini conditions to round-off and equals the KKT system on its own contact set solved afresh (LU).
TEST(ContactProblem, ManyContactsMeetSignoriniAndTheFreshKkt) {
  const int n = 200;
  ContactProblem p = random_problem(n, 1e-10);
  // Strongly coupled through a few shapes (a low-rank compliance on a small diagonal): contacts leave the set as
  // others join, so the factor is updated both ways.
  const Eigen::MatrixXd B = Eigen::MatrixXd::Random(n, 6);
  p.A = (B * B.transpose() + 0.05 * Eigen::MatrixXd::Identity(n, n)) * 1e-8;
  for (int i = 0; i < n; i += 3) p.lambda[i] = -0.02;
  const Eigen::VectorXd* warm = nullptr;
  ContactSolution last;
  for (const double T : {20.0, 60.0, 200.0, 80.0}) {
    const ContactSolution s = solve_contact(p, T, warm);
    const double f = s.force_N.maxCoeff(), g = p.q.cwiseAbs().maxCoeff();
    const Eigen::VectorXd gap = p.A * s.force_N + p.q - s.twist_rad * p.lambda;
    EXPECT_GE(s.force_N.minCoeff(), 0.0);
    EXPECT_GE(gap.minCoeff(), -1e-10 * g) << "T = " << T;
    EXPECT_LT(gap.cwiseProduct(s.force_N).cwiseAbs().maxCoeff(), 1e-10 * g * f);
    EXPECT_NEAR(p.lambda.dot(s.force_N), T, 1e-12 * T);
    std::vector<int> S;
    for (int i = 0; i < n; ++i)
      if (s.force_N[i] > 0) S.push_back(i);
    ASSERT_GT(S.size(), 5u) << "T = " << T;  // the test's premise: a set of several contacts
    const int m = static_cast<int>(S.size());
    const Eigen::VectorXd z = fresh_kkt(p, S, T);
    EXPECT_NEAR(s.twist_rad, z[m], 1e-10 * std::abs(z[m]));
    for (int a = 0; a < m; ++a) EXPECT_NEAR(s.force_N[S[a]], z[a], 1e-9 * f);
    last = s;
    warm = &last.force_N;
  }
}

TEST(ContactProblem, NoFlankForTheTorqueIsRefused) {
  ContactProblem p;
  p.A = Eigen::Matrix2d::Identity() * 1e-8;
  p.q = Eigen::Vector2d(1e-6, 1e-6);
  p.lambda = Eigen::Vector2d(0.02, 0.03);
  EXPECT_THROW(solve_contact(p, -1.0), InputError);
}

// With no clearance and no friction the drive is linear: the catalog's lost motion is the elastic twist between
// ±4 % of rated torque, 2·0.04·T_R/K.
TEST(TorqueTwist, LostMotionOfALinearDriveIsElastic) {
  const double K = 1.4e4, T_R = 31.0;
  TorqueTwist c;
  for (int i = -20; i <= 20; ++i) {
    c.torque_Nm.push_back(T_R * i / 20);
    c.twist_rad.push_back(T_R * i / 20 / K);
  }
  EXPECT_NEAR(lost_motion_rad(c, T_R), 2 * 0.04 * T_R / K, 1e-12);
  const SegmentLaw law = segment_law(c, 3.9, 12.0, T_R);
  EXPECT_NEAR(law.k1_Nm_per_rad, K, 1e-6 * K);
  EXPECT_NEAR(law.k3_Nm_per_rad, K, 1e-6 * K);
}

// No clearance (q = 0), no friction: the contact problem is linear in T (the active set does not change with |T|), so
// the curve it gives has no jump and the catalog's lost motion is the elastic twist 2·0.04·T_R/K, K its slope.
TEST(TorqueTwist, ContactWithoutClearanceGivesElasticLostMotion) {
  const int n = 6;
  Eigen::MatrixXd B = Eigen::MatrixXd::Random(n, n);
  ContactProblem p;
  p.A = (B * B.transpose() + n * Eigen::MatrixXd::Identity(n, n)) * 1e-9;
  p.q = Eigen::VectorXd::Zero(n);
  p.lambda.resize(n);
  p.lambda << 0.02, -0.02, 0.021, -0.019, 0.018, -0.022;  // both flanks of three teeth
  const double T_R = 31;
  TorqueTwist c;
  for (int i = -20; i <= 20; ++i) {
    const double T = i == 0 ? 1e-9 : T_R * i / 20;
    c.torque_Nm.push_back(i == 0 ? 0.0 : T);
    c.twist_rad.push_back(solve_contact(p, T).twist_rad);
  }
  const double K_plus = T_R / c.twist_rad.back(), K_minus = -T_R / c.twist_rad.front();
  const double expected = 0.04 * T_R / K_plus + 0.04 * T_R / K_minus;
  EXPECT_NEAR(lost_motion_rad(c, T_R) / expected, 1.0, 1e-9);
  EXPECT_NEAR(c.twist_rad[20], 0.0, 1e-12);  // no dead band
}

// A curve built from a three-segment law with play: the secants at the law's own breakpoints return its stiffnesses,
// the fit finds breakpoints near them, and lost motion holds the play.
TEST(TorqueTwist, SegmentLawRecoveredWithPlay) {
  SegmentLaw truth;
  truth.t1_Nm = 3.9;
  truth.t2_Nm = 12;
  truth.k1_Nm_per_rad = 1.0e4;
  truth.k2_Nm_per_rad = 1.4e4;
  truth.k3_Nm_per_rad = 1.6e4;
  const double T_R = 31, play = 2e-4;
  TorqueTwist c;
  for (int i = -310; i <= 310; ++i) {
    const double T = 0.1 * i;
    if (i == 0) {
      c.torque_Nm.insert(c.torque_Nm.end(), {0.0, 0.0});
      c.twist_rad.insert(c.twist_rad.end(), {-play / 2, play / 2});
      continue;
    }
    c.torque_Nm.push_back(T);
    c.twist_rad.push_back((T > 0 ? 1 : -1) * (play / 2 + truth.twist_rad(std::abs(T))));
  }
  const SegmentLaw at_catalog = segment_law(c, 3.9, 12, T_R);
  // The play sits in the first segment's secant: K1 = T1/(φ_law(T1) + play/2).
  EXPECT_NEAR(at_catalog.k1_Nm_per_rad, 3.9 / (3.9 / 1e4 + play / 2), 1e-6 * 1e4);
  EXPECT_NEAR(at_catalog.k2_Nm_per_rad, 1.4e4, 1e-6 * 1.4e4);
  EXPECT_NEAR(at_catalog.k3_Nm_per_rad, 1.6e4, 1e-6 * 1.6e4);
  EXPECT_NEAR(lost_motion_rad(c, T_R), play + 2 * 0.04 * T_R / 1e4, 1e-9);
  const SegmentLaw fit = fitted_segment_law(c, T_R);
  EXPECT_TRUE(fit.breakpoints_fitted);
  EXPECT_NEAR(fit.k3_Nm_per_rad, 1.6e4, 0.05 * 1.6e4);
}

}  // namespace
}  // namespace sw
