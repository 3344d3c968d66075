// Flexspline load cases on a plain clamped tube: the wave generator's loads are self-equilibrated, reach the requested
// w0, leave no net rotation, the cam only pushes, and the torque case balances with the generator in place.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "fem/fatigue.hpp"
#include "fem/flexspline_analysis.hpp"
#include "fem/post.hpp"
#include "mesh/shapes.hpp"

namespace sw {
namespace {

constexpr double kPi = std::numbers::pi;

FlexsplineModel tube_with_generator(GeneratorModel model) {
  FlexsplineModel c;
  c.flexspline.shape = FlexsplineShape::Tube;
  c.flexspline.teeth = TeethModel::None;
  c.flexspline.inner_radius_m = 18.4e-3;
  // A long, 1 mm tube: a short clamped thin tube resists ovalisation by membrane action (the clamp forbids the
  // inextensional cos2θ mode), and concentrated generator forces then dent it locally instead of ovalising it.
  c.flexspline.wall_thickness_m = 1.0e-3;
  c.flexspline.length_m = 60e-3;
  c.flexspline.rim_width_m = 0.0;
  c.load.torque_Nm = 10.0;
  c.mesh.size_m = 2e-3;
  c.mesh.wall_layers = 1;
  WaveGeneratorParams w;
  w.model = model;
  w.radial_deformation_m = 0.2e-3;
  w.axial_position_m = 3e-3;
  w.band_width_m = 4e-3;
  c.wave_generator = w;
  return c;
}

TetMesh mesh_of(const FlexsplineModel& c) {
  const auto& f = c.flexspline;
  return mesh_tube(f.inner_radius_m, f.inner_radius_m + f.wall_thickness_m, f.length_m, c.mesh);
}

TEST(FourForceGenerator, LoadsAreSelfEquilibratedAndReachW0WithoutNetRotation) {
  const FlexsplineModel c = tube_with_generator(FourForce{});
  const TetMesh m = mesh_of(c);
  const FlexsplineSolution s = analyse_flexspline(c, m);
  // Four equal radial forces at ±β and π ± β: zero resultant and zero moment, to round-off of the patch integration
  // (the patches are symmetric only up to the unstructured mesh, so allow 1e-9 of one force).
  EXPECT_LT(s.checks.generator_net_force.norm(), 1e-9 * s.generator_force_N);
  EXPECT_LT(s.checks.generator_net_moment.norm(), 1e-9 * s.generator_force_N * 20e-3);
  // w0 at the major axis, read independently from the displacement field (0.1 %).
  const PointSampler sampler(m);
  const double r = neutral_radius(c.flexspline), z = c.flexspline.length_m;
  const Eigen::VectorXd& u = s.cases.front().u;
  ASSERT_EQ(s.cases.front().name, "generator");
  const double w_plus = sampler.displacement({r, 0, z}, u)[0], w_minus = -sampler.displacement({-r, 0, z}, u)[0];
  EXPECT_NEAR(0.5 * (w_plus + w_minus), 0.2e-3, 1e-3 * 0.2e-3);
  // Two-lobe shape: the minor axis moves in.
  EXPECT_LT(sampler.displacement({0, r, z}, u)[1], 0.0);
  // Symmetric loads give no rotation: compare with the torque case's rotation scale.
  EXPECT_LT(std::abs(s.checks.generator_rotation_rad), 1e-4 * std::abs(s.phi0_rad));
  // The torque sweep is linear: φ/T constant.
  for (const auto& [T, c_tau] : s.torque_sweep) EXPECT_NEAR(c_tau / s.compliance_rad_per_Nm, 1.0, 1e-9) << T;
  // Torque balance: clamp plus the band's radial support (which carries no moment about z, to round-off).
  EXPECT_NEAR(-s.checks.reaction_torque_Nm / s.checks.applied_torque_Nm, 1.0, 1e-8);
  // Hoop stress pattern of the seed paper: tension near the forces, compression at the minor axis.
  ASSERT_TRUE(s.neutral_curve.has_value());
  EXPECT_GT(s.hoop.max_tensile_Pa, 0.0);
  EXPECT_LT(s.hoop.max_compressive_Pa, 0.0);
  // A material point's history over one revolution is the field around its circle: at the bore in the generator's
  // plane it matches the hoop profile (cylindrical components rotated at the nodes, then interpolated; here
  // interpolated, then rotated at the point) within 1 % of the profile's amplitude.
  const auto h = revolution_history(s.hoop.inner_radius_m, s.hoop.profile_z_m, 0.0, 1.0, sampler,
                                    s.cases.front().stress);
  ASSERT_TRUE(h.has_value());
  double amplitude = 0;
  for (double v : s.hoop.inner_Pa) amplitude = std::max(amplitude, std::abs(v));
  for (int k = 0; k < 360; k += 5) EXPECT_NEAR(h->hoop_Pa[k], s.hoop.inner_Pa[k], 0.01 * amplitude) << k;
  ASSERT_TRUE(s.fatigue.has_value());
  EXPECT_GT(s.fatigue->rim.hoop.alternating_Pa, 0.0);
}

// Goodman per component: 1/(σa/Se + σm/Su), no credit for a compressive mean.
TEST(Fatigue, GoodmanSafetyFactorAndCycle) {
  const StressCycle c = stress_cycle({-100e6, 300e6, 50e6});
  EXPECT_DOUBLE_EQ(c.alternating_Pa, 200e6);
  EXPECT_DOUBLE_EQ(c.mean_Pa, 100e6);
  EXPECT_DOUBLE_EQ(goodman_safety_factor(c, 500e6, 1000e6), 2.0);
  EXPECT_DOUBLE_EQ(goodman_safety_factor({200e6, -100e6}, 500e6, 1000e6), 2.5);
}

// The cam as a body in unilateral contact: it pushes only, the zone it touches is centred on the major axis and does
// not reach the minor axis of a tube (which comes in by inextensibility, short of the cam), the bore reaches the cam at
// the major axis, and with torque the clamp's and the generator's reactions balance the applied torque (1e-8: an
// identity of the discrete equations, the generator's share included).
TEST(CamGenerator, PushesOnlyTouchesAroundTheMajorAxisAndBalancesTorque) {
  const FlexsplineModel c = tube_with_generator(Cam{});
  const TetMesh m = mesh_of(c);
  const FlexsplineSolution s = analyse_flexspline(c, m);
  ASSERT_TRUE(s.generator.has_value());
  const GeneratorReadout& g = *s.generator;
  EXPECT_TRUE(g.unilateral);
  EXPECT_GE(g.min_contact_force_N, 0.0);
  for (double f : g.force_comb_N) EXPECT_GE(f, 0.0);
  ASSERT_EQ(g.zones_wg_deg.size(), 2u);
  for (const auto& [from, to] : g.zones_wg_deg) {
    const double mid = std::remainder(0.5 * (from + to) + (from > to ? 180.0 : 0.0), 180.0);
    EXPECT_LT(std::abs(mid), 3.0) << from << " " << to;
    EXPECT_LT(std::abs(std::remainder(to - from, 360.0)), 170.0) << from << " " << to;
  }
  EXPECT_GT(g.total_radial_force_N, 0.0);
  // The bore at the major axis sits on the cam at the band's middle (within 1 % of w0: the station enforces the
  // band-averaged gap); the open end, 3 mm beyond the band, flares further out.
  const PointSampler sampler(m);
  const double zb = c.flexspline.length_m - c.wave_generator->axial_position_m, rb = c.flexspline.inner_radius_m + 1e-6;
  const Eigen::VectorXd& u = s.cases.front().u;
  EXPECT_NEAR(0.5 * (sampler.displacement({rb, 0, zb}, u)[0] - sampler.displacement({-rb, 0, zb}, u)[0]) / 0.2e-3,
              1.0, 0.01);
  EXPECT_LT(g.w_minor_m, 0.0);
  // A cam of two symmetric lobes does not twist the flexspline.
  EXPECT_LT(std::abs(s.checks.generator_rotation_rad), 1e-3 * std::abs(s.phi0_rad));
  EXPECT_NEAR(-s.checks.reaction_torque_Nm / s.checks.applied_torque_Nm, 1.0, 1e-8);
  EXPECT_NE(g.reaction_torque_Nm, 0.0);
}

// Rigid rollers at ±β from both ends of the major axis: all four touch with positive force when the generator acts
// alone (symmetric), the standoff that reaches w0 is found on the linear all-touching problem and the unilateral solve
// keeps it (1e-6), and with torque the reactions balance (1e-8); a roller's normal is radial, so it carries no torque.
TEST(RollerGenerator, FourRollersTouchReachW0AndBalanceTorque) {
  FlexsplineModel c = tube_with_generator(Rollers{});
  const TetMesh m = mesh_of(c);
  const FlexsplineSolution s = analyse_flexspline(c, m);
  ASSERT_TRUE(s.generator.has_value());
  const GeneratorReadout& g = *s.generator;
  EXPECT_EQ(g.model, "rollers");
  EXPECT_EQ(g.zones_wg_deg.size(), 4u);
  EXPECT_GT(g.min_contact_force_N, 0.0);
  EXPECT_NEAR(g.w_major_m / 0.2e-3, 1.0, 1e-6);
  for (double f : g.force_comb_N) EXPECT_GE(f, 0.0);
  EXPECT_NEAR(-s.checks.reaction_torque_Nm / s.checks.applied_torque_Nm, 1.0, 1e-8);
  EXPECT_LT(std::abs(g.reaction_torque_Nm), 1e-9 * std::abs(s.checks.applied_torque_Nm));
}

}  // namespace
}  // namespace sw
