// The whole drive's torque–twist curve against a drive whose twist has a closed form: the designed size-17 drive's
// flanks (their gaps at rest, levers and tooth-pair compliances, from the real geometry) on a body that only twists
// about the axis with compliance C (every pattern's displacement its lever times the twist: A = C·λλᵀ), the
// generator held (no stations), the circular spline rigid. With ψ the output's turn, the flanks carry
// f_i = max(0, λ_i·(ψ − C·T) − q_i)/c_i and T = Σ λ_i·f_i, piecewise linear in ψ − C·T between the flanks' closing
// angles q_i/λ_i: solved exactly by walking those breakpoints. The analysis (its active-set solve, its torque
// stepping, the twist it reports, the play between the limits at zero) must give the same twist at every step to
// round-off, and the flanks' forces too.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "contact/contact_body.hpp"
#include "contact/loaded_contact.hpp"
#include "tests/contact/size17_harmonic.hpp"

namespace sw {
namespace {

/// A body that only twists: compliance C (rad/N·m) about the axis; the generator held, with no stations.
class TwistingBody : public ContactBody {
public:
  explicit TwistingBody(double compliance_rad_per_Nm) : C_(compliance_rad_per_Nm) {}
  std::string solver() const override { return "twisting body"; }
  const BodyStations& stations() const override { return stations_; }
  BodyInfluence influence(const std::vector<FlankPattern>& patterns, int) const override {
    const Eigen::Index n = static_cast<Eigen::Index>(patterns.size());
    BodyInfluence out;
    out.lever.resize(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      const FlankPattern& p = patterns[static_cast<std::size_t>(i)];
      double moment = 0;  // of the pattern's load on the flexspline about the axis, at each of its stations
      for (const double s : p.stations_rad) {
        const Eigen::Vector2d at = p.contact_radius_m * Eigen::Vector2d(std::cos(s), std::sin(s));
        const Eigen::Vector2d dir = Eigen::Rotation2Dd(s - p.stations_rad[0]) * p.force_dir;
        moment += p.scale * (at.x() * dir.y() - at.y() * dir.x());
      }
      out.lever[i] = -moment;  // the lever: what the partner takes back (contact/contact_body.hpp)
    }
    out.A = C_ * out.lever * out.lever.transpose();
    out.check = [lever = out.lever](const Eigen::VectorXd& x) { return BodyCheck{0.0, lever.dot(x)}; };
    return out;
  }
  std::vector<NeutralCurveSamples> generator_curves_at(const std::vector<double>&) const override { return {}; }

private:
  double C_;
  BodyStations stations_;
};

/// ψ at flank torque T: the breakpoints walked in order.
double closed_form_twist(double T, double C, const Eigen::VectorXd& lambda, const Eigen::VectorXd& q,
                         const Eigen::VectorXd& c) {
  // The flanks closed by this sense of torque: λ_i with T's sign; their closing turns q_i/λ_i (ψ_t in T's sense).
  std::vector<Eigen::Index> side;
  for (Eigen::Index i = 0; i < lambda.size(); ++i)
    if (lambda[i] * T > 0) side.push_back(i);
  std::sort(side.begin(), side.end(), [&](Eigen::Index a, Eigen::Index b) {
    return q[a] / std::abs(lambda[a]) < q[b] / std::abs(lambda[b]);
  });
  // T(ψ_t) = Σ_active λ_i·(λ_i ψ_t − q_i)/c_i = S2·ψ_t − S1 on each interval.
  double S2 = 0, S1 = 0, psi = 0;
  for (std::size_t k = 0; k < side.size(); ++k) {
    const Eigen::Index i = side[k];
    S2 += lambda[i] * lambda[i] / c[i];
    S1 += lambda[i] * q[i] / c[i];
    psi = (T + S1) / S2;  // with the flanks up to k closed
    const double next = k + 1 < side.size() ? q[side[k + 1]] / lambda[side[k + 1]] : (T > 0 ? 1e9 : -1e9);
    if (T > 0 ? psi <= next : psi >= next) break;
  }
  return psi + C * T;
}

TEST(DriveClosedForm, TwistingBodyWithTeethInSeriesAndPlayToRoundOff) {
  const test::Size17Harmonic& k = test::size17_harmonic();
  const double C = 2e-5;  // rad/(N·m): of the order of the size-17 cup's C_τ
  const TwistingBody body(C);
  ContactOptions o = k.options;
  o.series.circular_spline = {};
  o.series.bearing_approach_m = {};
  o.contact.face_slices = 1;  // the centre section: a body that only twists has no rim to read the others from
  const ContactAnalysis a = analyse_contact(flexspline_model(k.c), body, k.readout, o);
  const ContactProblem& P = a.problem;
  const Eigen::Index nf = static_cast<Eigen::Index>(a.flanks.size());
  ASSERT_EQ(P.q.size(), nf);
  Eigen::VectorXd c(nf);
  const double n_teeth = a.half_turn_pairs ? 2.0 : 1.0;
  for (Eigen::Index i = 0; i < nf; ++i) c[i] = n_teeth * a.flanks[static_cast<std::size_t>(i)].compliance_m_per_N;
  ASSERT_GT(c.minCoeff(), 0.0);
  ASSERT_GT(P.q.minCoeff(), 0.0);  // the designed drive keeps play: every flank open at rest
  double worst = 0, worst_force = 0;
  for (const TorqueStep& s : a.steps) {
    if (s.torque_Nm == 0) continue;  // the limits at zero: the play's edges, below
    const double expected = closed_form_twist(s.torque_Nm, C, P.lambda, P.q, c);
    worst = std::max(worst, std::abs(s.twist_rad - expected) / std::abs(expected));
    // The flanks' forces from the closed form's ψ_t.
    const double psi_t = expected - C * s.torque_Nm;
    for (Eigen::Index i = 0; i < nf; ++i) {
      const double f = P.lambda[i] * s.torque_Nm > 0 ? std::max(0.0, (P.lambda[i] * psi_t - P.q[i]) / c[i]) : 0.0;
      worst_force = std::max(worst_force, std::abs(s.flank_force_N[static_cast<std::size_t>(i)] - f) /
                                              std::max(1.0, s.max_pair_force_N));
    }
  }
  // The play: the jump between the limits at zero (±1e-6 of rated torque either side of the dead band).
  const double limit = 1e-6 * a.rated_torque_Nm;
  const double play = closed_form_twist(limit, C, P.lambda, P.q, c) - closed_form_twist(-limit, C, P.lambda, P.q, c);
  std::printf("closed-form drive (size-17 flanks on a body that only twists): twist within %.1e, forces within %.1e "
              "of the largest; play %.9g vs %.9g arcmin\n", worst, worst_force, a.play_rad * 10800 / M_PI,
              play * 10800 / M_PI);
  EXPECT_LT(worst, 1e-12);
  EXPECT_LT(worst_force, 1e-12);
  EXPECT_NEAR(a.play_rad, play, 1e-12 * play);
  EXPECT_LT(a.torque_balance_error_rel, 1e-10);  // the flanks' share settles to 1e-13 of T, 1e-11 of rated at zero
}

}  // namespace
}  // namespace sw
