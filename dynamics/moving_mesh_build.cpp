#include "dynamics/moving_mesh_build.hpp"

#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <numbers>
#include <string>
#include <utility>

#include <Eigen/Geometry>

#include "common/constants.hpp"
#include "common/error.hpp"
#include "common/progress.hpp"
#include "contact/loaded_contact.hpp"
#include "kinematics/backlash.hpp"

namespace sw {
namespace {

/// The backlash module's view of one flank: gap |ℓ|·δ at zero deflection, signed lever ℓ, contact radius on the
/// flexspline tooth and on the circular spline's, the flanks' sliding and the profile direction's arm; false where it
/// cannot close. The selection is the loaded contact's (contact/loaded_contact.hpp candidate_flank): within two pitches
/// of a zone's edge a free tooth takes part, with its exact closing turn as its gap like every other tooth.
struct FlankGeometry {
  const BacklashModel& model;
  const NeutralCurve& curve;
  double pitch_rad;  // 0: engaged teeth only
  double cached_phi = std::numeric_limits<double>::quiet_NaN();
  PairClearance pc;
  bool near_edge = false;
  bool operator()(double phi, int side, FlankSample& sample) {
    if (phi != cached_phi) {
      pc = pair_clearance(model, phi, 0.0);
      cached_phi = phi;
      near_edge = false;
      if (!pc.engaged && pitch_rad > 0)
        for (const int d : {-2, -1, 1, 2}) near_edge = near_edge || pair_clearance(model, phi + d * pitch_rad, 0.0).engaged;
    }
    const std::optional<FlankContact> f = candidate_flank(model, curve, pc, phi, side == 0 ? Flank::Ccw : Flank::Cw, near_edge);
    if (!f) return false;
    const FlankVelocity v = flank_velocity(model, side == 0 ? pc.ccw : pc.cw, phi);
    sample.q_m = std::abs(f->lever_m) * f->closing_angle_rad;
    sample.lever_m = f->lever_m;
    sample.contact_radius_f_m = f->contact_radius_m;
    sample.contact_radius_c_m = f->contact_radius_c_m;
    sample.sliding_m_per_rad = v.sliding_m_per_rad;
    sample.tangent_arm_m = v.tangent_arm_m;
    return true;
  }
};

/// `edge_teeth`: the free teeth next to the zone's edges take part. Only where the rim moves radially under load (the
/// FEM-coupled mesh): on a rigid rim a free tooth's tip stays inside the circular spline's tip circle, so a turn of the
/// rim slides it past and it never touches.
FlankTable table_on(const GearParams& g, const NeutralCurve& curve, const ToothCompliance& teeth, double step,
                    bool edge_teeth) {
  const BacklashModel model = make_backlash_model(g, curve);
  const int per = g.teeth_flexspline % 2 == 0 ? 2 : 1;
  const double half = kPi / per;
  const int n = static_cast<int>(std::ceil(half / step)) + 1;  // grid j·step, j = −n … n: phases fall on it
  FlankGeometry geo{model, curve, edge_teeth ? 2 * kPi / g.teeth_flexspline : 0.0};
  return make_flank_table(-n * step, n * step, step, per, std::ref(geo), teeth);
}

}  // namespace

FlankVelocity flank_velocity(const BacklashModel& model, const FlankClearance& fc, double phi) {
  const ToothPlacement at = place_tooth(model.curve, phi, 0.0);
  const Eigen::Vector2d local = Eigen::Rotation2Dd(-at.angle_rad) * (fc.point_f - at.offset_m);
  const auto material_point = [&](double phi_rad) {
    const ToothPlacement t = place_tooth(model.curve, phi_rad, 0.0);
    return Eigen::Vector2d(Eigen::Rotation2Dd(t.angle_rad) * local + t.offset_m);
  };
  // Central difference in φ: its truncation (h²·p‴ ~ 1e-14 m/rad) and rounding (ε·|p|/h ~ 1e-11 m/rad) are far
  // below the sliding's millimetres per radian.
  constexpr double h = 1e-6;
  const Eigen::Vector2d dp_dphi = (material_point(phi + h) - material_point(phi - h)) / (2 * h);
  const double turn = static_cast<double>(model.gear.teeth_flexspline) / model.gear.teeth_circular;
  const Eigen::Vector2d z_cross_pc(-fc.point_c.y(), fc.point_c.x());
  const Eigen::Vector2d v = -dp_dphi + turn * z_cross_pc;
  const Eigen::Vector2d& n = fc.normal;
  const Eigen::Vector2d t(-n.y(), n.x());
  return {n.dot(v), t.dot(v), n.dot(fc.point_f)};
}

double contact_wg_angle_rad(const GearParams& g, double sigma) {
  return sigma * g.teeth_flexspline / g.teeth_circular;
}

MovingMesh rigid_rim_mesh(const GearParams& g, const NeutralCurve& curve, const ToothCompliance& teeth,
                          int samples_per_pitch) {
  MovingMesh m;
  m.teeth_flexspline = g.teeth_flexspline;
  m.teeth_per_unknown = g.teeth_flexspline % 2 == 0 ? 2 : 1;
  m.pitch_rad = 2 * kPi / g.teeth_flexspline;
  m.table = table_on(g, curve, teeth, m.pitch_rad / samples_per_pitch, false);
  m.source = "moving pairs on a rigid rim (backlash module's clearances every pitch/" +
             std::to_string(samples_per_pitch) + ")";
  return m;
}

MovingMesh fem_coupled_mesh(const FlexsplineModel& c, const ContactBody& body, const FemReadout& fem,
                            const ToothCompliance& teeth, double rated_torque_Nm, int phases, int table_per_phase,
                            double reach_factor) {
  check_contact_model(c);
  if (phases < 1 || table_per_phase < 1) throw InputError("dynamics: phases and table samples must be >= 1");
  const GearParams& g = *c.gear;
  MovingMesh m;
  m.teeth_flexspline = g.teeth_flexspline;
  m.teeth_per_unknown = g.teeth_flexspline % 2 == 0 ? 2 : 1;
  m.pitch_rad = 2 * kPi / g.teeth_flexspline;
  const NeutralCurveSamples& nc = fem.neutral_curve;
  const NeutralCurve curve = fit_neutral_curve(nc.radius_m, nc.phi_rad, nc.w_wg_m, nc.v_wg_m, nc.mu_wg_rad, "FEM");
  m.table = table_on(g, curve, teeth, m.pitch_rad / (phases * table_per_phase), true);
  const int period = m.key_period();
  for (int s = 0; s < phases; ++s) {
    MeshPhase ph;
    ph.shift_rad = s * m.pitch_rad / phases;
    ContactOptions o;
    o.rated_torque_Nm = rated_torque_Nm;
    o.steps = 1;
    o.contact.generator_angle_rad = contact_wg_angle_rad(g, ph.shift_rad);
    o.reach_factor = reach_factor;  // body only: the teeth come from the table, the generator bearing is not modelled
    progress("dynamics: loaded-contact problem at generator phase " + std::to_string(s + 1) + "/" +
             std::to_string(phases));
    const ContactAnalysis a = analyse_contact(c, body, fem, o);
    const auto nf = static_cast<Eigen::Index>(a.flanks.size());
    ph.A_body = a.problem.A;
    ph.q_correction.resize(nf);
    for (Eigen::Index i = 0; i < nf; ++i) {
      const FlankContact& f = a.flanks[i];
      ph.key.push_back(f.tooth % period);
      ph.side.push_back(f.flank == Flank::Ccw ? 0 : 1);
      ph.phi_rad.push_back(f.phi_rad);
      // The table's gap at this very grid angle; the difference is the generator's own state (A·p0).
      const int j = static_cast<int>(std::lround((f.phi_rad - m.table.phi_start_rad) / m.table.step_rad));
      const double q_table = m.table.q_m[ph.side.back()].at(j);
      if (std::isnan(q_table) || std::abs(m.table.phi_start_rad + j * m.table.step_rad - f.phi_rad) > 1e-9 * m.pitch_rad)
        throw InputError("dynamics: flank of tooth " + std::to_string(f.tooth) + " off the clearance table's grid");
      ph.q_correction[i] = a.problem.q[i] - q_table;
    }
    if (s == 0) m.station_q = a.problem.q.tail(a.problem.q.size() - nf);
    else if (a.problem.q.size() - nf != m.station_q.size())
      throw InputError("dynamics: the generator's stations differ between phases");
    m.phases.push_back(std::move(ph));
  }
  // Each flank's index in the next phase; past the last phase, tooth k is where tooth k − 1 was at the first.
  for (int s = 0; s < phases; ++s) {
    const MeshPhase& nxt = m.phases[(s + 1) % phases];
    std::map<std::pair<int, int>, int> where;
    for (std::size_t i = 0; i < nxt.key.size(); ++i) where[{nxt.key[i], nxt.side[i]}] = static_cast<int>(i);
    MeshPhase& ph = m.phases[s];
    for (std::size_t i = 0; i < ph.key.size(); ++i) {
      const int key = s + 1 < phases ? ph.key[i] : (ph.key[i] - 1 + period) % period;
      const auto it = where.find({key, ph.side[i]});
      ph.next.push_back(it == where.end() ? -1 : it->second);
    }
  }
  prepare_intervals(m);
  m.source = "moving pairs coupled through the rim (loaded-contact body compliance at " + std::to_string(phases) +
             " phases per pitch, interpolated; clearances on the FEM's neutral curve every pitch/" +
             std::to_string(phases * table_per_phase) +
             (m.reduced_phases ? "; the compliance's slope reduced at " + std::to_string(m.reduced_phases) + " of " +
                                     std::to_string(phases) + " phases, to keep it positive definite"
                            : std::string()) +
             ")";
  return m;
}

}  // namespace sw
