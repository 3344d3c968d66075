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
#include "contact/ratcheting.hpp"
#include "kinematics/backlash.hpp"
#include "tests/contact/size17_harmonic.hpp"

namespace sw {
namespace {

/// What a closed-form body reads of each pattern: its lever (minus the moment about the axis of its load on the
/// flexspline, what the partner takes back: contact/contact_body.hpp) and its outward radial force, over its stations.
struct PatternResultants {
  Eigen::VectorXd lever, radial;
};
PatternResultants resultants(const std::vector<FlankPattern>& patterns) {
  const Eigen::Index n = static_cast<Eigen::Index>(patterns.size());
  PatternResultants r{Eigen::VectorXd::Zero(n), Eigen::VectorXd::Zero(n)};
  for (Eigen::Index i = 0; i < n; ++i) {
    const FlankPattern& p = patterns[static_cast<std::size_t>(i)];
    for (const double s : p.stations_rad) {
      const Eigen::Vector2d e(std::cos(s), std::sin(s)), at = p.contact_radius_m * e;
      const Eigen::Vector2d dir = Eigen::Rotation2Dd(s - p.stations_rad[0]) * p.force_dir;
      r.lever[i] -= p.scale * (at.x() * dir.y() - at.y() * dir.x());
      r.radial[i] += p.scale * dir.dot(e);
    }
  }
  return r;
}

/// A closed-form body with the generator held and no stations: its coefficients from the patterns' resultants.
class HeldBody : public ContactBody {
public:
  const BodyStations& stations() const override { return stations_; }
  BodyInfluence influence(const std::vector<FlankPattern>& patterns, int) const override {
    const PatternResultants r = resultants(patterns);
    BodyInfluence out;
    out.lever = r.lever;
    out.A = coefficients(r);
    out.check = [lever = out.lever](const Eigen::VectorXd& x) { return BodyCheck{0.0, lever.dot(x)}; };
    return out;
  }
  std::vector<NeutralCurveSamples> generator_curves_at(const std::vector<double>&) const override { return {}; }

private:
  virtual Eigen::MatrixXd coefficients(const PatternResultants& r) const = 0;
  BodyStations stations_;
};

/// A body that only twists: compliance C (rad/N·m) about the axis, A = C·λλᵀ.
class TwistingBody : public HeldBody {
public:
  explicit TwistingBody(double compliance_rad_per_Nm) : C_(compliance_rad_per_Nm) {}
  std::string solver() const override { return "twisting body"; }

private:
  Eigen::MatrixXd coefficients(const PatternResultants& r) const override { return C_ * r.lever * r.lever.transpose(); }
  double C_;
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
  // The flanks' share settles to 1e-13 of T, and at the limits at zero (±1e-6 of rated) to 1e-11 of rated: 1e-5 of
  // their own torque (the steps there read 0, so the worst over the analysis is theirs).
  for (const TorqueStep& s : a.steps)
    if (s.torque_Nm != 0) EXPECT_LT(s.balance_error_rel, 1e-12) << s.torque_Nm;
  EXPECT_LT(a.torque_balance_error_rel, 1e-5);
}

/// Rigid teeth on a ring that only shrinks, as a whole: its radial stiffness K against the patterns' total outward
/// radial force, every point moving in by the same u = −Σρ_j x_j / K (ρ_j a pattern's outward radial force per unit),
/// so A = ρρᵀ/K; no twist of its own.
class ShrinkingRingBody : public HeldBody {
public:
  explicit ShrinkingRingBody(double K_N_per_m) : K_(K_N_per_m) {}
  std::string solver() const override { return "shrinking ring"; }

private:
  Eigen::MatrixXd coefficients(const PatternResultants& r) const override {
    return r.radial * r.radial.transpose() / K_;
  }
  double K_;
};

// The ratcheting ramp with climbing contacts against rigid teeth on a ring that shrinks as a whole (the size-17
// drive's flanks and geometry; K = 1e7 N/m, the circular spline rigid, the teeth all but rigid: 1e-12 m/N). Every tooth
// parts by the same s; of the teeth still carrying, the flank that a rigid turn closes first at that parting takes
// the whole torque, at the climbed contact's lever ℓ(s) and normal n(s), which push the ring in by its radial share:
//     T(s) = K·s·|ℓ(s)| / (n(s)·e_r),
// the output holding T at the least parting where T(s) reaches it, and a tooth whose parting passes its overlap
// letting go. The reference walks T(s) on the exact geometry (closed_flank at each parting) with the same release
// search; the drive's ramp instead turns each flank's pattern with its contact and iterates the body's parting. 1 %:
// the drive keeps each load's point at rest (its direction turns), a second-order shift of its radial share.
TEST(DriveClosedForm, RatchetingWithClimbingContactsOnAShrinkingRing) {
  const test::Size17Harmonic& k = test::size17_harmonic();
  const double K = 1e7;
  const ShrinkingRingBody body(K);
  ContactOptions o = k.options;
  o.series.circular_spline = {};
  o.series.bearing_approach_m = {};
  o.series.tooth_pair_m_per_N = [](double, double) { return 1e-12; };
  o.contact.face_slices = 1;
  o.contact.friction_coefficient = 0;
  o.ratcheting_ceiling_Nm = 100 * o.rated_torque_Nm;
  const FlexsplineModel model = flexspline_model(k.c);
  const ContactAnalysis a = analyse_contact(model, body, k.readout, o);
  ASSERT_TRUE(a.ratcheting);
  const BacklashModel m = make_backlash_model(*model.gear, fem_neutral_curve(k.readout.neutral_curve));
  // The teeth as the ramp sees them: in the order of their first flank.
  std::vector<RatchetTooth> teeth;
  std::vector<std::size_t> tooth_of;
  for (const FlankContact& f : a.flanks) {
    std::size_t t = 0;
    while (t < teeth.size() && teeth[t].tooth != f.tooth) ++t;
    tooth_of.push_back(t);
    if (t == teeth.size()) teeth.push_back({f.tooth, f.phi_rad, pair_clearance(m, f.phi_rad, 0.0).depth_m, 0});
  }
  // Each flank a positive torque closes, on a grid of partings up to the deepest tooth's overlap: its closing turn,
  // lever and radial share on the exact geometry (linear between the grid's points).
  double s_max = 0;
  for (const RatchetTooth& t : teeth) s_max = std::max(s_max, t.overlap_at_rest_m);
  constexpr int kGrid = 400;
  struct Climb {
    std::size_t flank = 0;
    std::vector<double> turn, torque_per_parting;  // δ(s); K·|ℓ(s)|/(n(s)·e_r): T(s) = s·that
  };
  std::vector<Climb> climbs;
  for (std::size_t i = 0; i < a.flanks.size(); ++i) {
    const FlankContact& f = a.flanks[i];
    if (!(f.lever_m > 0) || !(teeth[tooth_of[i]].overlap_at_rest_m > 0)) continue;
    Climb c{i, {}, {}};
    for (int j = 0; j <= kGrid; ++j) {
      const ClosedFlank cf = closed_flank(m, f.phi_rad, 0.0, f.flank, s_max * j / kGrid);
      c.turn.push_back(cf.turn_rad);
      c.torque_per_parting.push_back(K * std::abs(cf.contact.lever_arm_m) /
                                     cf.contact.normal.dot(cf.contact.point_f.normalized()));
    }
    climbs.push_back(std::move(c));
  }
  const auto on_grid = [&](const std::vector<double>& v, double s) {
    const double x = std::clamp(s / s_max * kGrid, 0.0, kGrid - 1e-9);
    const int j = static_cast<int>(x);
    return v[j] + (x - j) * (v[j + 1] - v[j]);
  };
  const RatchetSolve reference = [&](double T, const std::vector<bool>& carry) -> std::optional<RatchetState> {
    // The flank that closes first at parting s among the carrying teeth's, T(s) and its tooth.
    const auto at = [&](double s) {
      std::pair<double, std::size_t> best{std::numeric_limits<double>::quiet_NaN(), 0};
      double first = std::numeric_limits<double>::infinity();
      for (const Climb& c : climbs) {
        const std::size_t t = tooth_of[c.flank];
        const double turn = on_grid(c.turn, s);
        if (!carry[t] || !(turn < first)) continue;
        first = turn;
        best = {s * on_grid(c.torque_per_parting, s), t};
      }
      return best;
    };
    const auto state = [&](double s, std::size_t loaded) {
      RatchetState st;
      st.overlap_m.resize(static_cast<Eigen::Index>(teeth.size()));
      for (std::size_t t = 0; t < teeth.size(); ++t)
        st.overlap_m[static_cast<Eigen::Index>(t)] = teeth[t].overlap_at_rest_m - s;
      st.loaded.assign(teeth.size(), false);
      st.loaded[loaded] = true;
      return st;
    };
    constexpr int kScan = 4000;
    double lo = 0;
    for (int j = 1; j <= kScan; ++j) {
      const double s = s_max * j / kScan;
      const auto [torque, tooth] = at(s);
      if (!std::isfinite(torque)) return std::nullopt;
      if (teeth[tooth].overlap_at_rest_m <= s) return state(s, tooth);  // its tips pass: it lets go
      if (torque >= T) {  // the least parting that holds T: bisected
        double hi = s;
        for (int k = 0; k < 60; ++k) {
          const double mid = 0.5 * (lo + hi);
          (at(mid).first >= T ? hi : lo) = mid;
        }
        return state(hi, at(hi).second);
      }
      lo = s;
    }
    return std::nullopt;
  };
  const Ratcheting expected = ratcheting_torque(teeth, reference, o.rated_torque_Nm, o.ratcheting_ceiling_Nm);
  const Ratcheting& r = *a.ratcheting;
  std::printf("shrinking ring, K = %.0e N/m: ratcheting %.2f N*m (reference %.2f), first release %.2f (%.2f); last "
              "tooth %d (%d), its normal turned %.2f deg, %s\n",
              K, r.torque_Nm, expected.torque_Nm, r.first_release_Nm, expected.first_release_Nm, r.last_tooth,
              expected.last_tooth, r.last_normal_turn_rad * 180 / M_PI, r.last_contact.c_str());
  ASSERT_TRUE(std::isfinite(expected.torque_Nm));
  EXPECT_NEAR(r.torque_Nm, expected.torque_Nm, 1e-2 * expected.torque_Nm);
  EXPECT_NEAR(r.first_release_Nm, expected.first_release_Nm, 1e-2 * expected.first_release_Nm);
  EXPECT_NE(r.last_normal_turn_rad, 0.0);  // the contact climbed
}

}  // namespace
}  // namespace sw
