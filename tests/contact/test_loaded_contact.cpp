// The loaded tooth contact on a coarse seed cup with a cam generator: the influence coefficients against a direct FEM
// solve, the torque balance of the flank forces and of the clamp's reaction, reversal symmetry of a symmetric gear.
#include <cmath>
#include <map>
#include <cstdio>

#include <Eigen/Core>

#include <gtest/gtest.h>

#include "common/error.hpp"
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
    s->c.mesh.corner_levels = 0;  // uniform: the tooth contact, not the clamp corner's convergence
    s->c.wave_generator->model = Cam{};
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
  if (tooth_compliance_m_per_N > 0) o.series.tooth_pair_m_per_N = [=](double, double) { return tooth_compliance_m_per_N; };
  return analyse_contact(flexspline_model(k.c), k.mesh, k.system, fem_readout(k.fem), o);
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

// A flank's load pattern and its half-turn partner's: a rigid tooth carrying 1 N along the flank's force at the contact
// point, the same turned by π at the partner (both radial components inward when the force pushes inward). Near each
// station the nodal loads have exactly the contact force's resultant: its force and its moment about the axis (to
// round-off), and the foot's moment (force × height above the rim's surface) is there: the pattern's moment about the
// foot is the force's, not the zero of a force applied at the surface. (The partner once carried the radial part
// outward; the foot's moment was once missing, the tangential force scaled up instead.)
TEST(LoadedContact, FlankPatternAndItsHalfTurnPartnerCarryTheContactForce) {
  const Coarse& k = coarse_seed_cam();
  const double pitch = 2 * M_PI / k.c.gear->teeth_flexspline, s = 0.3;
  const Eigen::Vector2d er(std::cos(s), std::sin(s)), et(-std::sin(s), std::cos(s));
  const Eigen::Vector2d dir = (-0.5 * er + 0.8660254037844386 * et).normalized();  // inward and along the pitch circle
  const double surface = rim_outer_radius(k.c.flexspline, k.c.gear), contact = surface + 0.3e-3;
  const Eigen::VectorXd f = FlankLoads(k.mesh, pitch).pattern({s, s + M_PI}, dir, contact);
  Eigen::Vector2d force[2] = {Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()};
  double mz[2] = {0, 0}, foot[2] = {0, 0};
  for (std::size_t n = 0; n < k.mesh.n_nodes(); ++n) {
    const Eigen::Vector2d x(k.mesh.nodes(n, 0), k.mesh.nodes(n, 1)), fn(f[3 * n], f[3 * n + 1]);
    if (fn.norm() == 0) continue;
    const int p = std::abs(std::remainder(std::atan2(x.y(), x.x()) - s, 2 * M_PI)) < 4 * pitch ? 0 : 1;
    const Eigen::Vector2d base = (p == 0 ? 1.0 : -1.0) * surface * er, r = x - base;
    force[p] += fn;
    mz[p] += x.x() * fn.y() - x.y() * fn.x();
    foot[p] += r.x() * fn.y() - r.y() * fn.x();
  }
  const double arm = contact * dir.dot(et), height = contact - surface;
  for (int p = 0; p < 2; ++p) {
    const Eigen::Vector2d F = p == 0 ? dir : Eigen::Vector2d(-dir);
    EXPECT_NEAR((force[p] - F).norm(), 0.0, 1e-12) << "station " << p;
    EXPECT_NEAR(mz[p], arm, 1e-14) << "station " << p;
    EXPECT_NEAR(foot[p], height * dir.dot(et), 1e-14) << "station " << p;  // (P − foot) × F, P = foot + height·e_r
  }
  EXPECT_LT(force[0].dot(er), 0.0);  // the radial part pushes inward at both
  EXPECT_LT(force[1].dot(-er), 0.0);
}

// The mesh zones' edges are watched at every step: the observers read the rim's radial motion at the edge teeth's
// tips (their read-out is in the superposition check above) and the teeth sit where the engagement changes. Under
// torque the rim moves outward at the zones' edges (on the coarse seed cup the first free tooth, 3.3 µm short of the
// circular spline's tip circle at rest, comes about 5 µm into it), so the free teeth near an edge take part; with them
// the edges hold: no loaded engaged tooth loses its overlap and no tooth left out comes into mesh.
TEST(LoadedContact, MeshZoneEdgesAreWatchedAndHold) {
  const ContactAnalysis a = analyse(0.0);
  ASSERT_FALSE(a.edges.empty());
  int engaged = 0, free = 0, free_coming_in = 0;
  for (const EdgeTooth& e : a.edges) {
    std::printf("edge tooth %d at %.1f deg, %s: radial overlap at rest %.2f um, over the steps %.2f .. %.2f um\n",
                e.tooth, e.phi_rad * 180 / M_PI, e.engaged ? "engaged" : "free", e.overlap_at_rest_m * 1e6,
                e.overlap_min_m * 1e6, e.overlap_max_m * 1e6);
    (e.engaged ? engaged : free)++;
    EXPECT_EQ(e.engaged, e.overlap_at_rest_m > 0);
    // The observer reads the rim moving under load at every edge tooth (at least 0.1 µm between −rated and +rated:
    // a dead observer reads nothing).
    EXPECT_GT(e.overlap_max_m - e.overlap_min_m, 0.1e-6) << e.tooth;
    if (!e.engaged) free_coming_in += e.overlap_max_m > 0;
  }
  EXPECT_GT(engaged, 0);
  EXPECT_GT(free, 0);
  EXPECT_GT(free_coming_in, 0);  // the rim moves outward at the zones' edges: a free tooth comes into the tip circle
  EXPECT_TRUE(a.zone_edges_hold);
  // The edge teeth's share of +rated torque, recomputed from the flank forces: the teeth within two pitches of a change
  // of engagement (a tooth off the watched list is more than three pitches from any change, so it engages as its
  // watched neighbour does), their flanks' moments over the torque. Without them the drive can only be softer.
  std::map<int, bool> engaged_at;
  for (const EdgeTooth& e : a.edges) engaged_at[e.tooth] = e.engaged;
  const int zf = coarse_seed_cam().c.gear->teeth_flexspline;
  auto near_edge = [&](int k) {
    if (!engaged_at.count(k)) return false;
    for (int d = -2; d <= 2; ++d)
      if (const auto it = engaged_at.find((k + d + zf) % zf); it != engaged_at.end() && it->second != engaged_at[k]) return true;
    return false;
  };
  double edge_moment = 0;
  for (std::size_t i = 0; i < a.flanks.size(); ++i)
    if (near_edge(a.flanks[i].tooth)) edge_moment += a.problem.lambda[static_cast<Eigen::Index>(i)] * a.steps.back().flank_force_N[i];
  std::printf("edge teeth carry %.2f %% of +rated torque; twist at rated %.5e rad, without them %.5e rad\n",
              100 * a.edge_teeth_torque_share, a.curve.twist_rad.back(), a.twist_at_rated_without_edge_teeth_rad);
  EXPECT_NEAR(a.edge_teeth_torque_share, edge_moment / a.rated_torque_Nm, 1e-12);
  EXPECT_GE(a.edge_teeth_torque_share, 0.0);
  EXPECT_LE(a.edge_teeth_torque_share, 1.0);
  EXPECT_GE(a.twist_at_rated_without_edge_teeth_rad, a.curve.twist_rad.back() * (1 - 1e-12));
  int beyond = 0, beyond_loaded = 0;
  for (std::size_t i = 0; i < a.flanks.size(); ++i)
    if (a.flanks[i].beyond_tip_circle) {
      ++beyond;
      beyond_loaded += a.steps.back().flank_force_N[i] > 0 || a.steps.front().flank_force_N[i] > 0;
    }
  std::printf("%d flanks beyond the tip circle at rest take part, %d of them loaded at ±rated\n", beyond, beyond_loaded);
  EXPECT_GT(beyond, 0);
}

// The gear and the cam are symmetric about the major axis (tooth 0 on it): −T mirrors +T. The mesh is not symmetric,
// so the two directions agree to the discretisation's level, not to round-off.
TEST(LoadedContact, ReversalSymmetry) {
  const ContactAnalysis a = analyse(0.0);
  const double plus = a.curve.twist_rad.back(), minus = -a.curve.twist_rad.front();
  EXPECT_NEAR(plus / minus, 1.0, 0.03);
  EXPECT_LE(std::abs(a.steps.back().pairs_in_contact - a.steps.front().pairs_in_contact), 2);  // one marginal pair
}

// Tooth compliance in series: the twist grows, and the split names the teeth. The split is the tangent line at rated
// torque by energy: its parts other than engagement add up to the tangent compliance of the contact problem at the
// flanks' torque times that torque over the twist. Checked against the problem's own tangent by a difference of
// 1e-6 of the torque on the same contact set (the problem is linear there: the difference is exact to round-off, 1e-9).
// This case has no bearing and no circular-spline torsion: the problem solved is the one the analysis keeps.
TEST(LoadedContact, SeriesToothComplianceAddsTwist) {
  const ContactAnalysis rigid = analyse(0.0), soft = analyse(2e-8);
  EXPECT_GT(soft.curve.twist_rad.back(), rigid.curve.twist_rad.back());
  EXPECT_GT(soft.split.teeth, 0.05);
  const auto& s = soft.split;
  const ContactProblem& P = soft.problem;
  const std::vector<double>& f = soft.steps.back().flank_force_N;
  double T_flanks = 0;  // the flanks' torque at +rated (the stations' λ are 0 in the problem)
  for (std::size_t i = 0; i < f.size(); ++i) T_flanks += P.lambda[static_cast<Eigen::Index>(i)] * f[i];
  const ContactSolution at = solve_contact(P, T_flanks), below = solve_contact(P, T_flanks * (1 - 1e-6));
  ASSERT_EQ(at.in_contact(), below.in_contact());
  EXPECT_NEAR(at.twist_rad, soft.curve.twist_rad.back(), 1e-9 * at.twist_rad);
  const double tangent = (at.twist_rad - below.twist_rad) / (1e-6 * T_flanks);
  EXPECT_EQ(s.generator, 0.0);
  EXPECT_EQ(s.circular_spline, 0.0);
  EXPECT_NEAR(s.body + s.teeth, tangent * T_flanks / at.twist_rad, 1e-6);
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

// The cup's coning, which the slices read from the FEM: the rim as the generator leaves it at the face's ends is near
// the centre section's curve scaled by z/z_centre (the generatrix turning as a straight line about the diaphragm).
// Within 5 %: the coarse seed cup is 3.2 % and 3.7 % under the law at the diaphragm's end (its wide face, 0.74 of the
// centre's z, reaches where the diaphragm holds the generatrix), size 17 at its own mesh 0.3 % and 0.8 %.
TEST(LoadedContact, FaceSlicesFollowTheCupsConing) {
  const Coarse& k = coarse_seed_cam();
  const FlexsplineModel model = flexspline_model(k.c);
  const NeutralCurveSamples& mid = *k.fem.neutral_curve;
  const double face = k.c.flexspline.rim_width_m;
  for (double end : {-0.5, 0.5}) {
    const double z = mid.z_m + end * face;
    const NeutralCurveSamples at = neutral_curves_at(model, k.mesh, k.fem.cases.front().u, {z}).front();
    const double law = z / mid.z_m;
    std::printf("coning at z = %.2f mm: w(0) %.2f um (law %.2f), v(45) %.2f um (law %.2f)\n", z * 1e3,
                at.w_wg_m[0] * 1e6, law * mid.w_wg_m[0] * 1e6, at.v_wg_m[45] * 1e6, law * mid.v_wg_m[45] * 1e6);
    EXPECT_NEAR(at.w_wg_m[0] / (law * mid.w_wg_m[0]), 1.0, 0.05);
    EXPECT_NEAR(at.v_wg_m[45] / (law * mid.v_wg_m[45]), 1.0, 0.05);
  }
  // The sliced contact: every section takes part, the face's ends and its centre (the trapezoid rule: the ends stand
  // for a quarter of the face each, their teeth 4× as compliant as the whole face's, the centre for half, 2×); the
  // middle section is the one-slice contact's centre (its first flank closes at its turn, exactly) and the ends are
  // the face's ends as reported at rest (on this gear set both overlap at rest: the open end deeper in mesh, the
  // diaphragm's side off the zone's path at its edges); the influence coefficients, the balance and the clamp's
  // reaction hold as for one slice.
  ContactOptions o;
  o.rated_torque_Nm = 44.1;
  o.steps = 4;
  o.contact.face_slices = 3;
  o.series.tooth_pair_m_per_N = [](double, double) { return 1e-8; };
  const ContactAnalysis a = analyse_contact(flexspline_model(k.c), k.mesh, k.system, fem_readout(k.fem), o);
  double first[3] = {1, 1, 1};
  for (const FlankContact& f : a.flanks) {
    first[f.slice] = std::min(first[f.slice], f.closing_angle_rad);
    EXPECT_DOUBLE_EQ(f.compliance_m_per_N, f.slice == 1 ? 2e-8 : 4e-8);
  }
  const ContactAnalysis one = analyse(1e-8);
  std::printf("first closing per slice (diaphragm side to open end): %.3f %.3f %.3f arcmin; twist at rated %.4e rad "
              "(one slice: %.4e)\n", first[0] * 10800 / M_PI, first[1] * 10800 / M_PI, first[2] * 10800 / M_PI,
              a.curve.twist_rad.back(), one.curve.twist_rad.back());
  EXPECT_NEAR(first[1], one.min_closing_rad, 1e-12);
  // The face's sections at rest (reported whatever the slices): the centre is the one-slice contact's, the deflection
  // at the major axis grows from the diaphragm's end to the open end, an overlap exactly where a flank closes at a
  // negative turn.
  ASSERT_EQ(one.face_sections.size(), 3u);
  EXPECT_NEAR(one.face_sections[1].first_closing_rad, one.min_closing_rad, 1e-12);
  EXPECT_NEAR(one.face_sections[1].w_major_m / mid.w_wg_m[0], 1.0, 1e-3);
  EXPECT_LT(one.face_sections[0].w_major_m, one.face_sections[1].w_major_m);
  EXPECT_LT(one.face_sections[1].w_major_m, one.face_sections[2].w_major_m);
  for (const FaceSection& f : one.face_sections) EXPECT_EQ(f.overlap_m > 0, f.first_closing_rad < 0);
  EXPECT_LT(first[0], first[1] - 1e-4);  // 0.3 arcmin apart at least
  EXPECT_LT(first[2], first[1] - 1e-4);
  ASSERT_EQ(a.face_sections.size(), 3u);
  EXPECT_NEAR(first[0], a.face_sections[0].first_closing_rad, 1e-12);
  EXPECT_NEAR(first[2], a.face_sections[2].first_closing_rad, 1e-12);
  EXPECT_LT(a.superposition_error_rel, 1e-8);
  EXPECT_LT(a.torque_balance_error_rel, 1e-6);
  EXPECT_NEAR(a.fem_reaction_torque_Nm / a.rated_torque_Nm, 1.0, 1e-6);
  // A result read back (no load cases' fields) cannot give the slices' curves: refused with one line.
  FemReadout read_back = fem_readout(k.fem);
  read_back.generator_u = nullptr;  // as `contact --fem` reads it back from result.json
  EXPECT_THROW(analyse_contact(flexspline_model(k.c), k.mesh, k.system, read_back, o), InputError);

  // A solid tooth across the face (the pair all flexspline tooth here): coupled by the springs' own shape
  // diag(1/w_j) it is today's sections to round-off; by a shape that shares half of each band's load evenly with the
  // whole face (G = diag(1/w)/2 + 1/2: the same energy under a uniform load) each flank is half as compliant on its
  // own plus the face's share, and the drive stiffer.
  ContactOptions c = o;
  c.series.flexspline_tooth_m_per_N = [](double) { return 1e-8; };
  const Eigen::Vector3d w(0.25, 0.5, 0.25);
  const Eigen::MatrixXd springs = w.cwiseInverse().asDiagonal();
  c.series.face_shape = [&](int n) { EXPECT_EQ(n, 3); return springs; };
  const ContactAnalysis same = analyse_contact(flexspline_model(k.c), k.mesh, k.system, fem_readout(k.fem), c);
  EXPECT_NEAR(same.curve.twist_rad.back() / a.curve.twist_rad.back(), 1.0, 1e-12);
  const Eigen::MatrixXd shared = 0.5 * springs + 0.5 * Eigen::MatrixXd::Ones(3, 3);
  c.series.face_shape = [&](int) { return shared; };
  const ContactAnalysis solid = analyse_contact(flexspline_model(k.c), k.mesh, k.system, fem_readout(k.fem), c);
  for (const FlankContact& f : solid.flanks) EXPECT_NEAR(f.compliance_m_per_N, 1e-8 * shared(f.slice, f.slice), 1e-20);
  std::printf("twist at rated: sections side by side %.4e rad, one solid tooth sharing half %.4e\n",
              a.curve.twist_rad.back(), solid.curve.twist_rad.back());
  EXPECT_LT(solid.curve.twist_rad.back(), a.curve.twist_rad.back());
  EXPECT_LT(solid.torque_balance_error_rel, 1e-6);
  c.series.face_shape = [](int) { return Eigen::MatrixXd::Identity(2, 2); };
  EXPECT_THROW(analyse_contact(flexspline_model(k.c), k.mesh, k.system, fem_readout(k.fem), c), std::invalid_argument);
}

}  // namespace
}  // namespace sw
