// The ratcheting search against rigid teeth on rings held by radial springs, whose climb-out torque is a closed form.
//
// n rigid teeth on the flexspline's ring, each with one straight flank at pressure angle α at radius r, facing rigid
// teeth on the circular spline's ring; every tooth pair overlaps radially by h_i at rest. A flank's force F_i along
// its normal has the tangential part F_i·cos α (moment r·cos α per newton: λ) and the radial part F_i·sin α, which
// pushes the flexspline's tooth in and the circular spline's out against radial springs. The flanks' gaps close by
// the normal's share of that radial give (sin α per unit radial motion), so the contact problem's compliance is
// sin²α times the springs' radial compliance, plus a tooth compliance on the diagonal; its solution goes through
// solve_contact as the drive's does. A tooth lets go when its radial separation reaches its overlap.
#include <algorithm>
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "common/error.hpp"
#include "contact/contact_problem.hpp"
#include "contact/ratcheting.hpp"

namespace sw {
namespace {

constexpr double kAlpha = 20 * std::numbers::pi / 180, kR = 0.02, kToothCompliance = 2e-9;  // m, m/N

struct SprungTeeth {
  Eigen::MatrixXd radial;  ///< radial separation per newton of each flank (m/N)
  Eigen::VectorXd overlap;
  std::vector<RatchetTooth> teeth;

  RatchetSolve solve() const {
    return [this](double T, const std::vector<bool>& carry) -> std::optional<RatchetState> {
      std::vector<Eigen::Index> keep;
      for (std::size_t t = 0; t < carry.size(); ++t)
        if (carry[t]) keep.push_back(static_cast<Eigen::Index>(t));
      if (keep.empty()) return std::nullopt;
      ContactProblem p;
      p.A = std::sin(kAlpha) * radial(keep, keep) * std::sin(kAlpha);
      p.A.diagonal().array() += kToothCompliance;
      p.q = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(keep.size()));
      p.lambda = Eigen::VectorXd::Constant(static_cast<Eigen::Index>(keep.size()), kR * std::cos(kAlpha));
      const ContactSolution s = solve_contact(p, T);
      Eigen::VectorXd f = Eigen::VectorXd::Zero(overlap.size());
      f(keep) = s.force_N;
      RatchetState st;
      st.overlap_m = overlap - radial * f * std::sin(kAlpha);
      for (Eigen::Index i = 0; i < f.size(); ++i) st.loaded.push_back(f[i] > 0);
      st.twist_rad = s.twist_rad;
      return st;
    };
  }
};

SprungTeeth sprung(const Eigen::MatrixXd& radial, const Eigen::VectorXd& overlap) {
  SprungTeeth s{radial, overlap, {}};
  for (Eigen::Index i = 0; i < overlap.size(); ++i)
    s.teeth.push_back({static_cast<int>(i), 0.1 * static_cast<double>(i), overlap[i]});
  return s;
}

// Each tooth on its own radial spring k (flexspline and circular spline in series): the carrying teeth share the
// torque equally, F = T/(m·r·cos α), and part by F·sin α/k. The shallowest lets go first and its share passes to the
// others, so the teeth hold T as long as some round of the cascade stops:
//     T_ratchet = max_j (n − j)·r·cos α·k·h_(j) / sin α   (h sorted ascending),
// and the first release is at j = 0. With h = 10, 25, 30, 40 µm: the first at 4·10, the ratcheting at 3·25 (the
// cascade matters: the deepest tooth alone would hold 40).
TEST(Ratcheting, IndependentSpringsLetGoShallowestFirstAsTheClosedForm) {
  const double k = 5e7;  // N/m per tooth, both rings in series
  const Eigen::Vector4d h(30e-6, 10e-6, 40e-6, 25e-6);
  const SprungTeeth s = sprung(Eigen::Matrix4d::Identity() / k, h);
  const double unit = kR * std::cos(kAlpha) * k / std::sin(kAlpha);  // N·m per metre of overlap per tooth
  const double first = 4 * 10e-6 * unit, expected = 3 * 25e-6 * unit;
  const Ratcheting r = ratcheting_torque(s.teeth, s.solve(), 0.2 * first, 10 * expected, 1e-5);
  std::printf("independent springs: ratcheting %.4f N*m (closed form %.4f), first release %.4f (%.4f)\n",
              r.torque_Nm, expected, r.first_release_Nm, first);
  // The bisection's tolerance (1e-5) and the cascade's exact threshold: 1e-4 is far inside the 1 % the check needs.
  EXPECT_NEAR(r.torque_Nm, expected, 1e-4 * expected);
  EXPECT_NEAR(r.first_release_Nm, first, 1e-4 * first);
  EXPECT_EQ(r.first_tooth, 1);  // the 10 µm tooth
  // Just below: the three deepest hold, the 25 µm tooth with next to nothing left.
  EXPECT_EQ(r.teeth_holding, 3);
  EXPECT_EQ(r.last_tooth, 3);
  EXPECT_LT(r.last_overlap_m, 1e-3 * 25e-6);
  EXPECT_GE(r.last_overlap_m, 0.0);
}

// The flexspline's teeth on one rigid ring held by a single radial spring K that lets it shrink as a whole (the
// circular spline rigid): every tooth parts by the total radial force over K, Σ F·sin α / K = T·tan α/(r·K), whichever
// teeth carry. Releasing a tooth changes nothing for the others, so the deepest tooth decides:
//     T_ratchet = r·K·h_max / tan α.
TEST(Ratcheting, ARingShrinkingAsAWholeLetsGoAtTheDeepestTooth) {
  const double K = 2e8;
  const Eigen::Vector4d h(30e-6, 10e-6, 40e-6, 25e-6);
  const SprungTeeth s = sprung(Eigen::Matrix4d::Constant(1 / K), h);
  const double expected = kR * K * 40e-6 / std::tan(kAlpha), first = kR * K * 10e-6 / std::tan(kAlpha);
  const Ratcheting r = ratcheting_torque(s.teeth, s.solve(), 0.5 * first, 10 * expected, 1e-5);
  std::printf("ring on one spring: ratcheting %.4f N*m (closed form %.4f)\n", r.torque_Nm, expected);
  EXPECT_NEAR(r.torque_Nm, expected, 1e-4 * expected);
  EXPECT_NEAR(r.first_release_Nm, first, 1e-4 * first);
  EXPECT_EQ(r.teeth_holding, 1);
  EXPECT_EQ(r.last_tooth, 2);
}

TEST(Ratcheting, NotReachedBelowTheCeilingIsInfinite) {
  const SprungTeeth s = sprung(Eigen::Matrix2d::Identity() / 5e7, Eigen::Vector2d(10e-6, 20e-6));
  const Ratcheting r = ratcheting_torque(s.teeth, s.solve(), 1.0, 2.0);
  EXPECT_TRUE(std::isinf(r.torque_Nm));
  EXPECT_EQ(r.ceiling_Nm, 2.0);
  EXPECT_TRUE(std::isinf(r.first_release_Nm));
}

TEST(Ratcheting, RefusesAStartThatDoesNotHoldAndBadBounds) {
  const SprungTeeth s = sprung(Eigen::Matrix2d::Identity() / 5e7, Eigen::Vector2d(10e-6, 20e-6));
  EXPECT_THROW(ratcheting_torque(s.teeth, s.solve(), 1e4, 2e4), InputError);
  EXPECT_THROW(ratcheting_torque(s.teeth, s.solve(), 0.0, 2.0), std::invalid_argument);
  EXPECT_THROW(ratcheting_torque(s.teeth, s.solve(), 2.0, 1.0), std::invalid_argument);
}

}  // namespace
}  // namespace sw
