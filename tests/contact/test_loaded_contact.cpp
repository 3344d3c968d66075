// The loaded tooth contact on a coarse seed cup with a cam generator: the influence coefficients against a direct FEM
// solve, the torque balance of the flank forces and of the clamp's reaction, reversal symmetry of a symmetric gear.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "contact/loaded_contact.hpp"
#include "fem/flexspline_analysis.hpp"
#include "fem/flexspline_system.hpp"
#include "io/case.hpp"
#include "mesh/flexspline.hpp"

namespace sw {
namespace {

struct Coarse {
  Case c;
  TetMesh mesh;
  FlexsplineSystem system;
  FlexsplineSolution fem;
};

const Coarse& coarse_seed_cam() {
  static const Coarse* k = [] {
    auto* s = new Coarse;
    s->c = load_case("cases/seed_190_192.toml");
    s->c.mesh.size_m = 1.2e-3;
    s->c.mesh.wall_layers = 1;
    s->c.wave_generator->model = WaveGeneratorModel::Cam;
    s->mesh = mesh_flexspline(s->c.flexspline, s->c.gear, s->c.mesh);
    s->system = assemble_and_factorise(flexspline_model(s->c), s->mesh);
    s->fem = analyse_flexspline(flexspline_model(s->c), s->mesh, s->system);
    return s;
  }();
  return *k;
}

ContactAnalysis analyse(double tooth_compliance_m_per_N, double reach_factor = 3.0) {
  const Coarse& k = coarse_seed_cam();
  ContactOptions o;
  o.reach_factor = reach_factor;
  o.rated_torque_Nm = 44.1;
  o.steps = 8;
  if (tooth_compliance_m_per_N > 0) o.series.tooth_pair_m_per_N = [=](double) { return tooth_compliance_m_per_N; };
  return analyse_contact(k.c, k.mesh, k.system, k.fem, o);
}

TEST(LoadedContact, InfluenceCoefficientsMatchDirectSolveAndTorqueBalances) {
  const ContactAnalysis a = analyse(0.0);
  std::printf("coarse seed cup, cam: %zu flanks, %d contacts; twist at 44.1 N·m %.4e rad, %d flanks in contact, "
              "lost motion %.3f arcmin, play %.3f arcmin, overlap at rest %.2f um\n", a.flanks.size(), a.unknowns,
              a.curve.twist_rad.back(), a.steps.back().pairs_in_contact, a.lost_motion_rad * 10800 / M_PI,
              a.play_rad * 10800 / M_PI, a.overlap_at_rest_m * 1e6);
  EXPECT_LT(a.superposition_error_rel, 1e-8);
  EXPECT_LT(a.torque_balance_error_rel, 1e-6);
  // The clamp's reaction to the contact forces (direct FEM solve, internal forces) carries the torque.
  EXPECT_NEAR(a.fem_reaction_torque_Nm / a.rated_torque_Nm, 1.0, 1e-6);
  // More than one pair shares the torque at rated, and the twist exceeds the body's φ₀ alone.
  EXPECT_GT(a.steps.back().pairs_in_contact, 2);
  EXPECT_GT(a.curve.twist_rad.back(), coarse_seed_cam().fem.phi0_rad);
  // Monotone curve.
  for (std::size_t i = 1; i < a.curve.twist_rad.size(); ++i) EXPECT_GE(a.curve.twist_rad[i], a.curve.twist_rad[i - 1]);
}

// The gear and the cam are symmetric about the major axis (tooth 0 on it): −T mirrors +T. The mesh is not symmetric,
// so the two directions agree to the discretisation's level, not to round-off.
TEST(LoadedContact, ReversalSymmetry) {
  const ContactAnalysis a = analyse(0.0);
  const double plus = a.curve.twist_rad.back(), minus = -a.curve.twist_rad.front();
  EXPECT_NEAR(plus / minus, 1.0, 0.03);
  EXPECT_LE(std::abs(a.steps.back().pairs_in_contact - a.steps.front().pairs_in_contact), 2);  // one marginal pair
}

// Tooth compliance in series: the twist grows, the split names the teeth, and the fractions sum to one.
TEST(LoadedContact, SeriesToothComplianceAddsTwist) {
  const ContactAnalysis rigid = analyse(0.0), soft = analyse(2e-8);
  EXPECT_GT(soft.curve.twist_rad.back(), rigid.curve.twist_rad.back());
  EXPECT_GT(soft.split.teeth, 0.05);
  const auto& s = soft.split;
  EXPECT_NEAR(s.engagement + s.body + s.teeth + s.generator + s.circular_spline, 1.0, 1e-12);
  // Softer teeth share the load among more pairs.
  EXPECT_GE(soft.steps.back().pairs_in_contact, rigid.steps.back().pairs_in_contact);
}

// Flanks left out must not change the answer: starting from a reach too short for the twist (it is doubled until every
// flank that closes is in) gives the same curve as a generous one.
TEST(LoadedContact, FlanksLeftOutNeverClose) {
  const ContactAnalysis narrow = analyse(2e-8, 0.25), wide = analyse(2e-8, 12.0);
  EXPECT_LT(narrow.flanks.size(), wide.flanks.size());
  ASSERT_EQ(narrow.curve.twist_rad.size(), wide.curve.twist_rad.size());
  for (std::size_t i = 0; i < wide.curve.twist_rad.size(); ++i)
    EXPECT_NEAR(narrow.curve.twist_rad[i], wide.curve.twist_rad[i], 1e-9 * std::abs(wide.curve.twist_rad.back()));
}

}  // namespace
}  // namespace sw
