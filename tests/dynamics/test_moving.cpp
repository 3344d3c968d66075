// Moving pairs: the teeth travel through the mesh. Quasi-static limit against the loaded contact (coarse seed cup with
// its cam), spectra of the gear's own excitation with constant k (lines at the mesh frequency and its harmonics; none
// with the pairs frozen), energy balance, the complementarity solver.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <numbers>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <gtest/gtest.h>

#include "contact/contact_problem.hpp"
#include "contact/loaded_contact.hpp"
#include "contact/tet10_body.hpp"
#include "dynamics/analysis.hpp"
#include "dynamics/kinematic_pairs.hpp"
#include "dynamics/moving_mesh_build.hpp"
#include "dynamics/simulate.hpp"
#include "fem/flexspline_analysis.hpp"
#include "fem/flexspline_system.hpp"
#include "gear/tooth_stiffness.hpp"
#include "io/case.hpp"
#include "kinematics/neutral_curve.hpp"
#include "mesh/flexspline.hpp"

namespace sw {
namespace {

constexpr double kPi = std::numbers::pi;

ToothCompliance teeth_of(const Case& c) { return tooth_pair_compliance_of(flexspline_model(c)).pair_m_per_N; }

DynamicsModel model_of(const Case& c, DynamicsParams p) {
  DynamicsModel m = make_model(*c.gear, c.flexspline, c.flexspline.shape == FlexsplineShape::Cup, c.material, p,
                               pairs_from_kinematics(flexspline_model(c)), c.path);
  return m;
}

TEST(MovingMeshLcp, SolvesTwoCoupledContactsOneOpen) {
  // A = [[2, 1], [1, 3]], b = [−4, 1]: x = (2, 0), w = (0, 3).
  Eigen::MatrixXd A(2, 2);
  A << 2, 1, 1, 3;
  Eigen::VectorXd b(2), x;
  b << -4, 1;
  std::vector<char> active{0, 1};  // a wrong warm start
  solve_lcp(A, b, x, active);
  EXPECT_NEAR(x[0], 2.0, 1e-14);
  EXPECT_EQ(x[1], 0.0);
  EXPECT_TRUE(active[0] && !active[1]);
}

/// One flank and no station at S phases over a unit pitch, with body compliance values[s] at phase s.
MovingMesh one_flank_mesh(const std::vector<double>& values) {
  MovingMesh m;
  m.teeth_flexspline = 1;
  m.pitch_rad = 1.0;
  for (std::size_t s = 0; s < values.size(); ++s) {
    MeshPhase P;
    P.shift_rad = static_cast<double>(s) / values.size();
    P.key = {0};
    P.side = {0};
    P.phi_rad = {0.0};
    P.next = {0};
    P.A_body = Eigen::MatrixXd::Constant(1, 1, values[s]);
    P.q_correction = Eigen::VectorXd::Zero(1);
    m.phases.push_back(P);
  }
  prepare_intervals(m);
  return m;
}

/// Interval s's compliance and its slope per unit a at a ∈ [0, 1].
std::pair<double, double> interval_at(const MeshPhase& P, double a) {
  const auto& C = P.A_cubic;
  return {C[0](0, 0) + a * (C[1](0, 0) + a * (C[2](0, 0) + a * C[3](0, 0))),
          C[1](0, 0) + a * (2 * C[2](0, 0) + 3 * a * C[3](0, 0))};
}

// The compliance between phases stays positive definite and C¹. Values 1, 0.01, 0.01, 1: the central slopes at the two
// low phases (−0.495 and +0.495 per interval) make the Hermite segment between them dip to 0.01 − 0.124 = −0.114 at
// its middle, a compliance below zero that no body has. Those two phases' row factor is halved until the segment
// passes the check (a diagonal slope scales with the factor squared: 1/16 after two halvings, 0.0023 at the middle);
// the neighbouring segments keep their other end's central slope, every join keeps value and slope. A family that
// stays positive keeps the plain Hermite segments (the central differences).
TEST(MovingMesh, BetweenPhasesTheCompliancesStayPositiveAndJoinSmoothly) {
  const MovingMesh m = one_flank_mesh({1.0, 0.01, 0.01, 1.0});
  EXPECT_EQ(m.reduced_phases, 2);
  const int S = 4;
  double least = 1.0, worst_value = 0.0, worst_slope = 0.0;
  for (int s = 0; s < S; ++s) {
    for (int k = 0; k <= 1000; ++k) least = std::min(least, interval_at(m.phases[s], k / 1000.0).first);
    const auto end = interval_at(m.phases[s], 1.0), start = interval_at(m.phases[(s + 1) % S], 0.0);
    worst_value = std::max(worst_value, std::abs(end.first - start.first));
    worst_slope = std::max(worst_slope, std::abs(end.second - start.second));
  }
  EXPECT_GT(least, 0.0);
  EXPECT_LT(worst_value, 1e-14);  // round-off of the cubic's sums (values of order 1)
  EXPECT_LT(worst_slope, 1e-14);
  EXPECT_NEAR(interval_at(m.phases[1], 0.5).first, 0.01 - 0.12375 / 16, 1e-15);
  EXPECT_NEAR(interval_at(m.phases[0], 0.0).second, -0.495, 1e-15);  // phase 0 keeps its central slope

  const MovingMesh smooth = one_flank_mesh({1.0, 0.8, 0.7, 0.9});
  EXPECT_EQ(smooth.reduced_phases, 0);
  EXPECT_NEAR(interval_at(smooth.phases[1], 0.0).second, (0.7 - 1.0) / 2, 1e-15);
  EXPECT_NEAR(interval_at(smooth.phases[3], 0.0).second, (1.0 - 0.7) / 2, 1e-15);
}

// When the failure's direction lies on rows whose slopes are already zero, the other rows' slopes give way. Two flanks,
// a constant 2 × 2 compliance [[1e-3, 0.0216], [0.0216, d]] with d = 1, 0.5, 0.5, 1 at the four phases: every phase is
// positive definite (det 3.3e-5 at d = 0.5), but d's Hermite segment between the two low phases dips to 0.4375 at its
// middle (central slopes ∓0.25 per interval), where det = 4.375e-4 − 4.6656e-4 < 0. The negative direction is about
// (1, −0.05): the first flank's row, whose slopes are zero (its entries are constant). Halving the second flank's
// slopes once (its diagonal's by 4) lifts the middle to 0.484 and passes. Before, this threw after zeroing row one.
TEST(MovingMesh, WhenTheFailingRowsAreFlatTheOtherRowsGiveWay) {
  MovingMesh m;
  m.teeth_flexspline = 1;
  m.pitch_rad = 1.0;
  const double d[] = {1.0, 0.5, 0.5, 1.0};
  for (int s = 0; s < 4; ++s) {
    MeshPhase P;
    P.shift_rad = s / 4.0;
    P.key = {0, 1};
    P.side = {0, 0};
    P.phi_rad = {0.0, 0.0};
    P.next = {0, 1};
    P.A_body.resize(2, 2);
    P.A_body << 1e-3, 0.0216, 0.0216, d[s];
    P.q_correction = Eigen::VectorXd::Zero(2);
    m.phases.push_back(P);
  }
  ASSERT_NO_THROW(prepare_intervals(m));
  EXPECT_EQ(m.reduced_phases, 2);
  double least = 1.0;
  for (int s = 0; s < 4; ++s)
    for (int k = 0; k <= 1000; ++k) {
      const double a = k / 1000.0;
      const auto& C = m.phases[s].A_cubic;
      const Eigen::Matrix2d A = C[0] + a * (C[1] + a * (C[2] + a * C[3]));
      least = std::min(least, A.determinant());
    }
  EXPECT_GT(least, 0.0);
  const auto& C = m.phases[1].A_cubic;
  EXPECT_NEAR((C[0] + 0.5 * (C[1] + 0.5 * (C[2] + 0.5 * C[3])))(1, 1), 0.5 - 0.0625 / 4, 1e-15);
}

struct CoarseSeed {
  Case c;
  TetMesh mesh;
  FlexsplineSystem system;
  FlexsplineSolution fem;
};

const CoarseSeed& coarse_seed() {
  static const CoarseSeed* k = [] {
    auto* s = new CoarseSeed;
    s->c = load_case("cases/seed_190_192.toml");
    s->c.mesh.size_m = 1.2e-3;
    s->c.mesh.wall_layers = 1;
    s->c.mesh.corner_levels = 0;  // uniform: the moving teeth, not the clamp corner's convergence
    s->mesh = mesh_flexspline(s->c.flexspline, s->c.gear, s->c.mesh);
    s->system = assemble_and_factorise(flexspline_model(s->c), s->mesh);
    s->fem = analyse_flexspline(flexspline_model(s->c), s->mesh, s->system);
    return s;
  }();
  return *k;
}

/// The coarse seed's mesh coupled through the rim as the tool builds it (8 phases, the flank table every pitch/64).
const MovingMesh& coarse_coupled() {
  static const MovingMesh* m = [] {
    const CoarseSeed& k = coarse_seed();
    const FemReadout readout = fem_readout(k.fem);
    const Tet10Body body(flexspline_model(k.c), k.mesh, k.system, readout.generator_u);
    return new MovingMesh(fem_coupled_mesh(flexspline_model(k.c), body, readout, teeth_of(k.c), 44.1, 8, 8));
  }();
  return *m;
}

// Across every boundary between two compliance phases, the flank problem is C¹ in σ: the gaps q, their rates ∂q/∂σ,
// the body compliance A and the quadratic form xᵀ(∂A/∂σ)x of the teeth's travel torque agree on both sides for the
// flanks present on both (σ_b ± 1e-9 of a phase). With linear segments, ∂q/∂σ (through the generator's gap
// correction) and ∂A/∂σ jumped at every boundary: the contact forces jumped with the damping, and the integrator cut
// its step at each. Tolerances: relative 1e-6 for values and rates, 1e-4 for the quadratic form (what ±1e-9 of a
// phase moves them by is far below; the linear segments' jumps were of order one).
TEST(MovingMesh, CompliancePhasesJoinWithContinuousGapsRatesAndCompliance) {
  MovingMesh m = coarse_coupled();
  const int S = static_cast<int>(m.phases.size());
  const double h = m.pitch_rad / S, eps = 1e-9 * h;
  double worst_q = 0, worst_dq = 0, worst_A = 0, worst_form = 0, form_scale = 0;
  for (int b = 1; b <= S; ++b) {
    const double sigma = 3 * m.pitch_rad + b * h;
    MeshInstant lo, hi;
    mesh_instant(m, sigma - eps, lo);
    mesh_instant(m, sigma + eps, hi);
    std::map<std::pair<int, int>, int> at_hi;
    for (int i = 0; i < hi.flanks(); ++i) at_hi[{hi.tooth[i], hi.side[i]}] = i;
    std::vector<int> il, ih;  // common flanks, then the stations
    for (int i = 0; i < lo.flanks(); ++i) {
      const auto it = at_hi.find({lo.tooth[i], lo.side[i]});
      if (it != at_hi.end()) il.push_back(i), ih.push_back(it->second);
    }
    const int common = static_cast<int>(il.size());
    ASSERT_GT(common, lo.flanks() / 2) << "boundary " << b;
    double q_scale = 0, dq_scale = 0;
    for (int c = 0; c < common; ++c) {
      q_scale = std::max(q_scale, std::abs(lo.q[il[c]]));
      dq_scale = std::max(dq_scale, std::abs(lo.dq[il[c]]));
    }
    for (int c = 0; c < common; ++c) {
      worst_q = std::max(worst_q, std::abs(lo.q[il[c]] - hi.q[ih[c]]) / q_scale);
      worst_dq = std::max(worst_dq, std::abs(lo.dq[il[c]] - hi.dq[ih[c]]) / dq_scale);
    }
    for (int j = 0; j < lo.stations; ++j) il.push_back(lo.flanks() + j), ih.push_back(hi.flanks() + j);
    double a_scale = 0, a_jump = 0;
    for (std::size_t c = 0; c < il.size(); ++c) {
      const double* cl = lo.column(il[c]);
      const double* ch = hi.column(ih[c]);
      for (std::size_t r = 0; r < il.size(); ++r) {
        a_scale = std::max(a_scale, std::abs(cl[il[r]]));
        a_jump = std::max(a_jump, std::abs(cl[il[r]] - ch[ih[r]]));
      }
    }
    worst_A = std::max(worst_A, a_jump / a_scale);
    // the quadratic form with 100 N on every common flank and station
    Eigen::VectorXd xl = Eigen::VectorXd::Zero(lo.unknowns()), xh = Eigen::VectorXd::Zero(hi.unknowns());
    for (std::size_t c = 0; c < il.size(); ++c) xl[il[c]] = xh[ih[c]] = 100.0;
    const double fl = body_travel_torque_Nm(lo, xl), fh = body_travel_torque_Nm(hi, xh);
    form_scale = std::max({form_scale, std::abs(fl), std::abs(fh)});
    worst_form = std::max(worst_form, std::abs(fl - fh));
    std::printf("boundary %d: %d common flanks of %d / %d; travel torque form %.6g / %.6g N·m\n", b, common,
                lo.flanks(), hi.flanks(), fl, fh);
  }
  worst_form /= form_scale;  // of the largest form at a boundary: where a phase's slope is reduced, the form is small
  std::printf("largest jumps across a phase boundary: q %.2e, dq/dsigma %.2e, A %.2e, x'(dA/dsigma)x %.2e\n", worst_q,
              worst_dq, worst_A, worst_form);
  // Between the phases the contact problem's matrix (the body's cubic, the tooth pairs in series) stays positive
  // definite, at 32 points per interval (the tool checks 15 per interval).
  int indefinite = 0;
  for (int k = 0; k < 32 * S; ++k) {
    MeshInstant in;
    mesh_instant(m, 3 * m.pitch_rad + (k + 0.5) * h / 32, in);
    in.series.head(in.flanks()) = in.compliance;
    Eigen::MatrixXd A(in.unknowns(), in.unknowns());
    for (int j = 0; j < in.unknowns(); ++j) A.col(j) = Eigen::Map<const Eigen::VectorXd>(in.column(j), in.unknowns());
    indefinite += A.llt().info() != Eigen::Success;
  }
  std::printf("%d phases with a reduced slope of %d; indefinite instants %d of %d\n", m.reduced_phases, S, indefinite,
              32 * S);
  EXPECT_EQ(indefinite, 0);
  EXPECT_LT(worst_q, 1e-6);
  EXPECT_LT(worst_dq, 1e-6);
  EXPECT_LT(worst_A, 1e-6);
  EXPECT_LT(worst_form, 1e-4);
}

// A slow run (60 rpm at the generator, default damping) against the loaded contact solved directly at the generator
// angles of the samples, at the same flank torque: per-tooth forces within 1 % of the largest, mesh deflection
// within 1 %. The samples' angles lie between the body's compliance phases, so the interpolation's error is in it.
// The flank table every pitch/64, as the tool builds it: near the major axis the circular spline's contact moves from
// its flank to its tip corner within a quarter pitch and the pair's compliance changes by 25 % there; at pitch/16 the
// linear interpolation of that kink alone costs 1.2 % of the largest force.
TEST(MovingMesh, SlowRunReproducesTheLoadedContactAtEveryGeneratorAngle) {
  const CoarseSeed& k = coarse_seed();
  const ToothCompliance teeth = teeth_of(k.c);
  DynamicsParams p;
  p.drive_speed_rpm = 60;
  p.drive_ramp_end_s = 0.002;
  p.load_torque_Nm = 44.1;
  p.load_ramp_start_s = 0.002;
  p.load_ramp_end_s = 0.006;
  p.duration_s = 0.016;
  p.output_step_s = 1e-4;
  p.steady_from_s = 0.008;
  p.damping_Ns_per_m = 100;  // small: its force c·q′·σ̇ stays below 1e-3 of the elastic one
  p.oversampling = 1;  // plain samples: the comparison is of the model, not of the output filter
  DynamicsModel m = model_of(k.c, p);
  m.moving = std::make_shared<MovingMesh>(coarse_coupled());
  const DynamicsSeries s = simulate(m);
  for (const auto& ph : m.moving->phases) {
    int missing = 0;
    for (int nx : ph.next) missing += nx < 0;
    std::printf("phase %.4f: %zu flanks, %d not in the next phase\n", ph.shift_rad, ph.key.size(), missing);
  }
  std::printf("energy balance %.3e (input %.4g J, dissipated %.4g J)\n", s.energy.error_rel(), s.energy.input_J, s.energy.dissipated_J);
  const int period = m.moving->key_period();
  {
    double jump = 0, at = 0;
    int tooth_j = -1;
    for (int t = 0; t < period; ++t)
      for (std::size_t j = 60; j < s.time_s.size(); ++j) {
        const double a0 = s.pair_force_N[t][j - 1], a1 = s.pair_force_N[t][j];
        if ((a0 == 0) != (a1 == 0) && std::max(std::abs(a0), std::abs(a1)) > jump) {
          jump = std::max(std::abs(a0), std::abs(a1));
          at = s.time_s[j];
          tooth_j = t;
        }
      }
    std::printf("largest force at a flank's entry or exit %.1f N (tooth %d, t = %.4f s)\n", jump, tooth_j, at);
    const std::size_t jj = std::lround(at / p.output_step_s);
    for (std::size_t j : {jj - 1, jj}) {
      const double sg = s.angle_rad[0][j] - s.angle_rad[2][j];
      const double phi = std::remainder(2 * kPi * tooth_j / 190 - sg, kPi);
      std::printf("  sample %zu: sigma %.5f (phase %.3f of a pitch), phi %.5f deg, force %.1f\n", j, sg,
                  std::fmod(sg, 2 * kPi / 190) / (2 * kPi / 190), phi * 180 / kPi, s.pair_force_N[tooth_j][j]);
    }
    const FlankTable& tb = m.moving->table;
    for (int side = 0; side < 2; ++side)
      for (int j = 1; j < tb.size(); ++j)
        if (std::isnan(tb.q_m[side][j]) != std::isnan(tb.q_m[side][j - 1]))
          std::printf("  table side %d validity edge at %.4f deg, q %.3e %.3e\n", side,
                      (tb.phi_start_rad + j * tb.step_rad) * 180 / kPi, tb.q_m[side][j - 1], tb.q_m[side][j]);
    // The gap is continuous where a tooth crosses the circular spline's tip circle: one exact closing turn on both
    // sides of it. With the free teeth's tip-corner distance as their gap it jumped there by 162 µm (per two teeth)
    // within one table step (3.7 µm apart, 5.3e-3 rad of turn to close), and a tooth entering the zone carried 130 N
    // that vanished in one sample. The steepest change left is a tooth rising into the zone (its gap falls from 45 to
    // 8 µm over 0.15°): a steep but continuous entry, whose force within one sample (printed above, ~70–100 N) is
    // not bounded here.
    // Gaps within reach: a few times what the twist at 44.1 N·m closes (0.9 mrad × 18 mm × two teeth per unknown).
    constexpr double kWithinReach_m = 100e-6;
    double steepest = 0, at_deg = 0;
    for (int side = 0; side < 2; ++side)
      for (int j = 1; j < tb.size(); ++j)
        if (std::min(tb.q_m[side][j], tb.q_m[side][j - 1]) < kWithinReach_m &&
            std::abs(tb.q_m[side][j] - tb.q_m[side][j - 1]) > steepest) {
          steepest = std::abs(tb.q_m[side][j] - tb.q_m[side][j - 1]);
          at_deg = (tb.phi_start_rad + j * tb.step_rad) * 180 / kPi;
        }
    std::printf("  largest change of a gap within reach over one table step (%.4f deg): %.2f um at %.3f deg\n",
                tb.step_rad * 180 / kPi, steepest * 1e6, at_deg);
    EXPECT_LT(steepest, 40e-6);
  }
  double worst_force = 0, worst_twist = 0;
  for (int j : {80, 103, 150}) {
    const double sigma = s.angle_rad[0][j] - s.angle_rad[2][j];
    ContactOptions o;
    o.rated_torque_Nm = 44.1;
    o.steps = 1;
    o.contact.generator_angle_rad = contact_wg_angle_rad(*k.c.gear, sigma);
    o.series.tooth_pair_m_per_N = teeth;
    const ContactAnalysis a = analyse_contact(flexspline_model(k.c), k.mesh, k.system, fem_readout(k.fem), o);
    const double flank_torque = s.mesh_torque_Nm[j] - s.travel_torque_Nm[j];  // Σ λ_i x_i
    const ContactSolution qs = solve_contact(a.problem, flank_torque);
    std::vector<double> tooth(period, 0.0);
    for (std::size_t i = 0; i < a.flanks.size(); ++i)
      tooth[a.flanks[i].tooth % period] += (a.flanks[i].flank == Flank::Ccw ? 1 : -1) * qs.force_N[i];
    double fmax = 0, err = 0;
    int worst_t = 0;
    for (int t = 0; t < period; ++t) {
      fmax = std::max(fmax, std::abs(tooth[t]));
      if (std::abs(tooth[t] - s.pair_force_N[t][j]) > err) worst_t = t;
      err = std::max(err, std::abs(tooth[t] - s.pair_force_N[t][j]));
    }
    std::printf("  worst tooth %d (phi %.3f deg): loaded contact %.2f N, moving %.2f N\n", worst_t,
                std::remainder(2 * kPi * worst_t / 190 - sigma, kPi) * 180 / kPi, tooth[worst_t], s.pair_force_N[worst_t][j]);
    const double twist_err = std::abs(s.deflection_rad[j] / qs.twist_rad - 1);
    std::printf("t = %.4f s, sigma %.5f rad (%.2f pitches): flank torque %.3f N·m, %d flanks in contact (loaded "
                "contact %d), largest force %.1f N; force error %.2e of it, deflection %.4e vs %.4e rad (%.2e)\n",
                s.time_s[j], sigma, sigma / (2 * kPi / 190), flank_torque, int(s.flanks_in_contact[j]),
                2 * int((qs.force_N.head(a.flanks.size()).array() > 0).count()), fmax, err / fmax, s.deflection_rad[j], qs.twist_rad, twist_err);
    worst_force = std::max(worst_force, err / fmax);
    worst_twist = std::max(worst_twist, twist_err);
  }
  EXPECT_LT(worst_force, 0.01);
  EXPECT_LT(worst_twist, 0.01);
}

// The paper's 26/28 gear on a rigid rim with the paper's constant k (8e7 N/m, c = 1e3 N·s/m), 1000 rpm, 100 N·m: the
// teeth's travel alone excites the mesh. z_f even: both zones in phase, so the total force's and the transmission
// error's strongest lines are at f_m = z_c·n_w/60 = 466.7 Hz (within one bin, 21.4 Hz) and stand > 20 dB above the
// median of the spectrum. With the pairs frozen the same run has no line above 1e-3 of it.
TEST(MovingMesh, ConstantStiffnessPutsTheStrongestLinesAtTheMeshFrequencyFrozenPairsDoNot) {
  Case c = load_case("cases/mbd_26_28.toml");
  DynamicsParams p = *c.dynamics;
  p.pair_stiffness = PairStiffness::Constant;
  DynamicsModel frozen = model_of(c, p);
  DynamicsModel moving = frozen;
  const NeutralCurve curve = generator_neutral_curve(rim_mean_radius(c.flexspline), radial_deformation_m(flexspline_model(c)),
                                                     *c.wave_generator);
  moving.moving = std::make_shared<MovingMesh>(rigid_rim_mesh(*c.gear, curve, {}, 16));
  const DynamicsSummary r = summarize(moving, simulate(moving));
  const DynamicsSummary f = summarize(frozen, simulate(frozen));
  const double fm = r.theory.mesh_frequency_Hz;
  ASSERT_NEAR(fm, 28 * 1000 / 60.0, 1e-9);
  ASSERT_FALSE(r.lines.empty());
  ASSERT_FALSE(r.te_lines.empty());
  std::printf("moving: force line %.2f Hz %.3g N (floor %.3g N, %.1f dB); TE line %.2f Hz %.3g urad (%.1f dB); "
              "deflection %.3f..%.3f mrad, largest force %.0f N; frozen: strongest %.3g N\n",
              r.lines[0].frequency_Hz, r.lines[0].amplitude_N, r.noise_floor_N,
              20 * std::log10(r.lines[0].amplitude_N / r.noise_floor_N), r.te_lines[0].frequency_Hz,
              r.te_lines[0].amplitude_N * 1e6, 20 * std::log10(r.te_lines[0].amplitude_N / r.te_noise_floor_rad),
              r.deflection_min_rad * 1e3, r.deflection_max_rad * 1e3, r.max_pair_force_N,
              f.lines.empty() ? 0.0 : f.lines[0].amplitude_N);
  EXPECT_NEAR(r.lines[0].frequency_Hz, fm, r.spectrum.resolution_Hz);
  EXPECT_NEAR(r.te_lines[0].frequency_Hz, fm, r.te_spectrum.resolution_Hz);
  EXPECT_GT(r.lines[0].amplitude_N, 10 * r.noise_floor_N);
  EXPECT_GT(r.te_lines[0].amplitude_N, 10 * r.te_noise_floor_rad);
  // the second transmission-error line is a harmonic of f_m
  ASSERT_GT(r.te_lines.size(), 1u);
  const double order = r.te_lines[1].frequency_Hz / fm;
  EXPECT_NEAR(order, std::round(order), r.te_spectrum.resolution_Hz / fm);
  EXPECT_TRUE(f.lines.empty() || f.lines[0].amplitude_N < 1e-3 * r.lines[0].amplitude_N);
  // The frozen run's spectrum at f_m itself (on a bin: the window spans whole mesh periods), with or without lines.
  const std::size_t fm_bin = std::lround(fm / f.spectrum.resolution_Hz);
  ASSERT_LT(fm_bin, f.spectrum.amplitude_N.size());
  EXPECT_LT(f.spectrum.amplitude_N[fm_bin], 1e-3 * r.lines[0].amplitude_N);
}

// An odd tooth count (the 26/28 case with z_f = 25, z_c = 27): the two zones are half a pitch apart, so the f_m
// component of the total force and of the transmission error cancels and the fundamental is 2·f_m; the three
// strongest lines sit at even mesh orders.
TEST(MovingMesh, OddToothCountPutsTheFundamentalAtTwiceTheMeshFrequency) {
  Case c = load_case("cases/mbd_26_28.toml");
  GearParams g = *c.gear;
  g.teeth_flexspline = 25;
  g.teeth_circular = 27;
  c.gear = g;
  DynamicsParams p = *c.dynamics;
  DynamicsModel m = model_of(c, p);
  const NeutralCurve curve = generator_neutral_curve(rim_mean_radius(c.flexspline), radial_deformation_m(flexspline_model(c)),
                                                     *c.wave_generator);
  m.moving = std::make_shared<MovingMesh>(rigid_rim_mesh(g, curve, {}, 16));
  const DynamicsSummary r = summarize(m, simulate(m));
  const double fm = r.theory.mesh_frequency_Hz;
  ASSERT_NEAR(fm, 27 * 1000 / 60.0, 1e-9);
  ASSERT_GE(r.lines.size(), 3u);
  ASSERT_GE(r.te_lines.size(), 3u);
  std::printf("z_f = 25: force lines %.2f, %.2f, %.2f Hz (f_m %.2f Hz), first %.3g N, %.1f dB above the floor\n",
              r.lines[0].frequency_Hz, r.lines[1].frequency_Hz, r.lines[2].frequency_Hz, fm, r.lines[0].amplitude_N,
              20 * std::log10(r.lines[0].amplitude_N / r.noise_floor_N));
  EXPECT_NEAR(r.lines[0].frequency_Hz, 2 * fm, r.spectrum.resolution_Hz);
  EXPECT_NEAR(r.te_lines[0].frequency_Hz, 2 * fm, r.te_spectrum.resolution_Hz);
  for (int i = 0; i < 3; ++i) {
    const double order = r.lines[i].frequency_Hz / fm, te_order = r.te_lines[i].frequency_Hz / fm;
    EXPECT_NEAR(order, 2 * std::round(order / 2), r.spectrum.resolution_Hz / fm) << i;
    EXPECT_NEAR(te_order, 2 * std::round(te_order / 2), r.te_spectrum.resolution_Hz / fm) << i;
  }
  EXPECT_GT(r.lines[0].amplitude_N, 10 * r.noise_floor_N);
}

// The seed gear's moving pairs on a rigid rim with the tooth-pair compliance, 1000 rpm, 100 N·m: the teeth's travel
// torque M_σ closes the energy balance (input = output + dissipated + kinetic + potential) and the torque balance
// (mean of Σλx + M_σ = load) over whole mesh periods.
TEST(MovingMesh, EnergyAndTorqueBalanceWithTravellingTeeth) {
  Case c = load_case("cases/seed_190_192.toml");
  DynamicsParams p = *c.dynamics;
  p.duration_s = 0.03;
  p.steady_from_s = 0.022;
  DynamicsModel m = model_of(c, p);
  const NeutralCurve curve = generator_neutral_curve(rim_mean_radius(c.flexspline), radial_deformation_m(flexspline_model(c)),
                                                     *c.wave_generator);
  m.moving = std::make_shared<MovingMesh>(rigid_rim_mesh(*c.gear, curve, teeth_of(c), 16));
  const DynamicsSeries s = simulate(m);
  const DynamicsSummary r = summarize(m, s);
  std::printf("energy %.2e, torque %.2e, speeds %.2e; deflection %.4f..%.4f mrad, largest force %.1f N, %g..%g flanks\n",
              r.energy_error_rel, r.torque_balance_error_rel, r.max_speed_error_rel, r.deflection_min_rad * 1e3,
              r.deflection_max_rad * 1e3, r.max_pair_force_N, r.flanks_in_contact_min, r.flanks_in_contact_max);
  EXPECT_LT(r.energy_error_rel, 5e-3);
  EXPECT_LT(r.torque_balance_error_rel, 1e-3);
  EXPECT_LT(r.max_speed_error_rel, 1e-4);
}

}  // namespace
}  // namespace sw
