// The 3-D reference of the flexspline's teeth: the loaded contact on a body whose teeth are solids on the cup
// (flexspline.teeth = "explicit", TET10), each flank's force acting on the tooth's own flank, against the fast model
// (the bare rim, the tooth in series from the plane-strain slabs) on the same designed drive.
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>

#include <Eigen/Geometry>

#include <gtest/gtest.h>

#include "app/contact_job.hpp"
#include "common/error.hpp"
#include "contact/loaded_contact.hpp"
#include "contact/tet10_body.hpp"
#include "contact/torque_twist.hpp"
#include "design/proportions.hpp"
#include "fem/flexspline_analysis.hpp"
#include "fem/flexspline_system.hpp"
#include "fem/loads.hpp"
#include "fem/post.hpp"
#include "gear/tooth_profile.hpp"
#include "io/case.hpp"
#include "mesh/flexspline.hpp"

namespace sw {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kArcmin = 10800 / kPi;

/// Size 14 at ratio 30 as `design` writes it (60 teeth, the fewest of any design: the explicit mesh stays small), on
/// a coarse uniform mesh; teeth as given.
Case designed(TeethModel teeth) {
  Case c = parse_case(design_case_toml(design_cup(14, 30)), "size14_ratio30.toml");
  c.flexspline.teeth = teeth;
  c.solver.method = SolverMethod::Tet10;
  c.mesh.size_m = 1.0e-3;
  c.mesh.wall_layers = 1;
  c.mesh.corner_levels = 0;  // uniform: the teeth, not the clamp corner's convergence
  return c;
}

struct Solved {
  Case c;
  TetMesh mesh;
  FlexsplineSystem system;
  FlexsplineSolution fem;
};

const Solved& solved(TeethModel teeth) {
  static std::map<TeethModel, Solved*> cache;
  Solved*& s = cache[teeth];
  if (!s) {
    s = new Solved;
    s->c = designed(teeth);
    s->mesh = mesh_flexspline(s->c.flexspline, s->c.gear, s->c.mesh);
    s->system = assemble_and_factorise(flexspline_model(s->c), s->mesh);
    s->fem = analyse_flexspline(flexspline_model(s->c), s->mesh, s->system);
  }
  return *s;
}

// A flank's pattern on an explicit tooth: its resultant is the contact force exactly and its moment about the axis
// that of the force at its place on the deformed rim (the contact's lever), at the station and, turned by π, at the
// half-turn partner; the force itself sits on the loaded tooth's flank, within the hat's reach of the contact point.
TEST(ExplicitTeeth, FlankLoadOnTheToothCarriesTheContactForceAndItsMoment) {
  const Solved& k = solved(TeethModel::Explicit);
  const GearParams& g = *k.c.gear;
  const double pitch = 2 * kPi / g.teeth_flexspline, spread = tooth_mesh_size(g, k.c.mesh).across_m;
  const GearRadii radii = gear_radii(g);
  // Tooth 5's ccw flank at mid height, pushed into the flank and inward; the deformed place of the point is moved
  // out and turned, as the generator moves it (0.5 mm and 0.01 rad).
  const int tooth = 5;
  const double a = tooth * pitch, r = 0.5 * (radii.form_f + radii.tip_f);
  const double half = 0.5 * flexspline_tooth_thickness(g, r) / r;
  const Eigen::Vector2d local = r * Eigen::Vector2d(std::cos(half), std::sin(half));
  const Eigen::Vector2d dir = Eigen::Rotation2Dd(a) * Eigen::Vector2d(-0.34, -0.94).normalized();
  const Eigen::Vector2d p = Eigen::Rotation2Dd(a) * local;
  const Eigen::Vector2d P = Eigen::Rotation2Dd(0.01) * (p + 0.5e-3 * p.normalized());
  const double s = std::atan2(P.y(), P.x());
  const ExplicitToothLoads loads(k.mesh, pitch, spread);
  const Eigen::VectorXd f = loads.pattern({s, s + kPi}, dir, P.norm(), a, local);
  Eigen::Vector2d force[2] = {Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()};
  double moment[2] = {0, 0};
  Eigen::Vector2d centre[2] = {Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()};
  double along[2] = {0, 0};
  for (std::size_t n = 0; n < k.mesh.n_nodes(); ++n) {
    const Eigen::Vector2d x(k.mesh.nodes(n, 0), k.mesh.nodes(n, 1)), fn(f[3 * n], f[3 * n + 1]);
    if (fn.norm() == 0) continue;
    const int q = std::abs(std::remainder(std::atan2(x.y(), x.x()) - a, 2 * kPi)) < kPi / 2 ? 0 : 1;
    force[q] += fn;
    moment[q] += x.x() * fn.y() - x.y() * fn.x();
    const double w = fn.dot(q == 0 ? dir : Eigen::Vector2d(-dir));  // the part along the force: the flank's load
    if (w > 0) centre[q] += w * x, along[q] += w;
  }
  for (int q = 0; q < 2; ++q) {
    const Eigen::Vector2d F = q == 0 ? dir : Eigen::Vector2d(-dir), at = q == 0 ? P : Eigen::Vector2d(-P);
    EXPECT_NEAR((force[q] - F).norm(), 0.0, 1e-12) << "station " << q;
    EXPECT_NEAR(moment[q], at.x() * F.y() - at.y() * F.x(), 1e-14) << "station " << q;
    // The pure moment's hats are small beside the flank's load, which sits at the contact point (within half the
    // hat: the hat is symmetric along the profile, the flank's curvature and the faces' cut move its centre).
    const Eigen::Vector2d on = q == 0 ? p : Eigen::Vector2d(-p);
    EXPECT_LT((centre[q] / along[q] - on).norm(), 0.5 * spread) << "station " << q;
  }
  EXPECT_THROW(loads.pattern({s}, dir, P.norm(), std::nan(""), local), InputError);
}

ContactAnalysis contact_of(TeethModel teeth) {
  const Solved& k = solved(teeth);
  ContactOptions o;
  o.rated_torque_Nm = *k.c.load.rated_torque_Nm;
  o.steps = 10;
  o.series = app::series_parts(k.c);
  return analyse_contact(flexspline_model(k.c), k.mesh, k.system, fem_readout(k.fem), o);
}

/// Twist at torque T on the loading branch, from the dead band's edge (the zero-torque limit on that side), rad.
double twist_from_edge(const ContactAnalysis& a, double T) {
  return twist_at(a.curve, T) - twist_limits(a.curve, 0.0).second;
}

// The drive on explicit teeth balances as the fast model does (the flank forces' moments against the torque, the
// clamp's reaction in a direct solve, the influence coefficients against that solve), and its twist beyond the dead
// band agrees with the fast model's: the ring model's teeth in series leave no compliance of the flexspline's teeth
// out. Tolerance 12 %: on this coarse mesh (1 mm, one layer, no corner grading) the explicit teeth are 5-8 % stiffer
// (printed); on finer meshes the two converge toward each other, within 3 % at 0.5 mm (contact/README.md, the 3-D
// reference), so a difference beyond 12 % here is a defect of either model, not the mesh.
TEST(ExplicitTeeth, DriveOnExplicitTeethBalancesAndAgreesWithTheFastModel) {
  const ContactAnalysis e = contact_of(TeethModel::Explicit), n = contact_of(TeethModel::None);
  EXPECT_LT(e.superposition_error_rel, 1e-8);
  EXPECT_LT(e.torque_balance_error_rel, 1e-6);
  // The clamp's reaction in a direct solve: the flanks' torque less the locked generator's share, which is counted
  // from the generator preload's moment at rest; zero by symmetry, but a mesh of explicit teeth is not symmetric
  // about the axes as a revolved one is, and its round-off moves the balance by a few 1e-6.
  std::printf("clamp reaction / rated torque: explicit teeth %.9f, fast model %.9f\n",
              e.fem_reaction_torque_Nm / e.rated_torque_Nm, n.fem_reaction_torque_Nm / n.rated_torque_Nm);
  EXPECT_NEAR(e.fem_reaction_torque_Nm / e.rated_torque_Nm, 1.0, 1e-5);
  const double T1 = 0.2 * e.rated_torque_Nm, TR = e.rated_torque_Nm;
  for (const double T : {T1, 0.5 * TR, TR}) {
    const double te = twist_from_edge(e, T), tn = twist_from_edge(n, T);
    std::printf("size 14 ratio 30, coarse: twist at %.2f N·m from the dead band's edge: explicit teeth %.3f, fast model "
                "%.3f arcmin (%+.1f %%); play %.3f / %.3f arcmin\n", T, te * kArcmin, tn * kArcmin, 100 * (te / tn - 1),
                e.play_rad * kArcmin, n.play_rad * kArcmin);
    EXPECT_NEAR(te / tn, 1.0, 0.12) << "at " << T << " N·m";
  }
}

}  // namespace
}  // namespace sw
