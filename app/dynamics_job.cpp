#include "app/dynamics_job.hpp"

#include <algorithm>
#include <functional>
#include <numbers>
#include <optional>
#include <sstream>
#include <vector>

#include "app/contact_job.hpp"
#include "app/fem_job.hpp"
#include "common/error.hpp"
#include "common/progress.hpp"
#include "contact/harmonic_body.hpp"
#include "datasheet/limits.hpp"
#include "datasheet/losses.hpp"
#include "generator/bearing_friction.hpp"
#include "dynamics/kinematic_pairs.hpp"
#include "dynamics/moving_mesh_build.hpp"
#include "io/case.hpp"
#include "io/fem_output.hpp"
#include "kinematics/backlash.hpp"
#include "kinematics/neutral_curve.hpp"

namespace sw::app {
namespace {

/// What to do with a flank whose clearance at rest is negative (interference in the basic kinematic model):
/// "preload" keeps it (contact force at rest), "clip" sets the clearance to 0, "drop" removes the pair.
std::vector<ToothPair> treat_interference(std::vector<ToothPair> pairs, const std::string& policy) {
  if (policy == "preload") return pairs;
  std::vector<ToothPair> out;
  for (ToothPair t : pairs) {
    const bool interferes = t.clearance_drive_m < 0 || t.clearance_coast_m < 0;
    if (policy == "drop" && interferes) continue;
    t.clearance_drive_m = std::max(0.0, t.clearance_drive_m);
    t.clearance_coast_m = std::max(0.0, t.clearance_coast_m);
    out.push_back(t);
  }
  return out;
}

/// The frozen pairs of generator angle 0 and where their clearances come from.
std::vector<ToothPair> frozen_pairs(const Case& c, const DynamicsParams& p, const DynamicsModelOptions& o,
                                    std::string& source) {
  std::vector<ToothPair> pairs;
  if (o.clearances == "kinematics") {
    pairs = pairs_from_kinematics(flexspline_model(c));
    source = "kinematics (basic model, wave generator at 0, phi0 = 0), " + std::to_string(pairs.size()) + " engaged pairs";
  } else {
    pairs = approximate_tooth_pairs(*c.gear, radial_deformation_m(flexspline_model(c)), c.load.engagement_half_angle_rad,
                                    p.base_clearance_m);
    source = "approximate stand-in (w0(1 - cos 2phi) sin(alpha) within +-engagement_half_angle), " +
             std::to_string(pairs.size()) + " pairs";
  }
  int interfering = 0;
  for (const auto& tp : pairs) interfering += (tp.clearance_drive_m < 0 || tp.clearance_coast_m < 0) ? 1 : 0;
  if (interfering > 0) {
    progress("dynamics: " + std::to_string(interfering) + " pairs have negative clearance (interference) at rest: " +
             (o.interference == "preload" ? "carried as contact preload"
              : o.interference == "clip"  ? "clearance set to 0"
                                          : "pairs left out"));
    pairs = treat_interference(std::move(pairs), o.interference);
    source += ", interference: " + o.interference;
  }
  return pairs;
}

/// The flexspline as the fem job solved it (its files in the command's output set) and the loaded contact's body on it.
struct SolvedBody {
  FemJobResult fem;
  FemReadout readout;
  std::unique_ptr<ContactBody> body;
};

SolvedBody solve_body(const Case& c, OutputSet& out) {
  FemJobOptions o;
  o.write_vtk = false;
  SolvedBody s;
  s.fem = run_fem_job(c, out, o);
  s.readout = fem_readout(s.fem.solution);
  s.body = contact_body(c, s.fem, s.readout.generator_u);
  return s;
}

/// The generator's friction moment on the rim against the speed of the two relative to each other (the wave's turn
/// through the flexspline's material): the bearing's Palmgren M0 + M1 (generator/bearing_friction.hpp) with the
/// lubricant's viscosity at its temperature and the balls loaded as the loaded contact loads them at the run's load
/// torque (the step nearest that torque, at most rated), and the rate-independent moments the datasheet counts with
/// it (datasheet/losses.hpp): the outer ring slipping on the bore under the same stations' forces (a cam;
/// generator/ring_slip.hpp) and the flexspline's material damping under the generator's wave. On the body the rim's
/// coupling solved (`solved`), else on the harmonic solver's (seconds; its solution gives the wave's energies in both
/// cases when the solved body is TET10). The loads stay those of that torque through the run (the load's ramp and the
/// mesh's fluctuation do not change them): an idealisation, said in `source`. Empty, with the reason in `source`,
/// without a [lubricant] or without a bearing whose balls a cam or rollers load.
std::function<double(double)> generator_moment(const Case& c, double load_torque_Nm, const SeriesParts& series,
                                               const SolvedBody* solved, std::string& source) {
  if (!c.lubricant) {
    source = "frictionless: the case gives no [lubricant]";
    return {};
  }
  if (!c.wave_generator || !c.wave_generator->bearing || contact_model_gap(flexspline_model(c))) {
    source = "frictionless: the generator bearing's friction needs its balls (a [wave_generator] bearing) loaded by "
             "the loaded contact";
    return {};
  }
  progress("dynamics: the generator bearing's ball loads from the loaded contact at " +
           std::to_string(load_torque_Nm) + " N·m");
  const FlexsplineModel m = flexspline_model(c);
  std::shared_ptr<const FourierSolution> fourier = solved ? solved->fem.harmonic : nullptr;
  if (!fourier) {
    double section_s = 0;
    fourier = std::make_shared<const FourierSolution>(solve_fourier_model(c, 0.0, section_s));
  }
  std::optional<HarmonicBody> harmonic;
  if (!solved) harmonic.emplace(m, *fourier);
  const ContactBody& body = solved ? *solved->body : static_cast<const ContactBody&>(*harmonic);
  const FemReadout readout = solved ? solved->readout : fem_readout(fourier->figures);
  const ContactAnalysis contact =
      naming_file(c.path, [&] { return analyse_contact(m, body, readout, contact_options(c, series)); });
  if (!body.stations().unilateral || contact.steps.back().station_force_N.empty()) {
    source = "frictionless: the generator's stations are held (the force idealisation), no ball is loaded by contact";
    return {};
  }
  const GeneratorBearing bearing = *c.wave_generator->bearing;
  const std::size_t i = step_nearest(contact, std::abs(load_torque_Nm));
  const std::vector<double> balls = ball_loads_N(body.stations(), contact.steps[i].station_force_N, bearing.balls);
  const double nu = kinematic_viscosity_mm2_s(*c.lubricant, c.lubricant->temperature_C);
  const RingOnBore ring = ring_on_bore(c, body.stations());
  const double ring_Nm = ring_on_bore_moment_Nm(ring, contact.steps[i].station_force_N);
  const double damping_Nm =
      damping_moment_Nm(harmonic_strain_energy_J(fourier->section, c.material, fourier->generator),
                        c.material.loss_factor);
  std::ostringstream os;
  os << "Palmgren's M0 + M1 (f0 = 2, z = 0.0005, y = 0.55), the lubricant's " << nu << " mm²/s at "
     << c.lubricant->temperature_C << " °C, the balls loaded as at " << contact.steps[i].torque_Nm
     << " N·m in the loaded contact (held there through the run); with the outer ring slipping on the bore ("
     << ring_Nm * 1e3 << " mN·m, boundary μ " << ring.friction << ") and the flexspline's material damping ("
     << damping_Nm * 1e3 << " mN·m, loss factor " << c.material.loss_factor << "), both at any speed";
  source = os.str();
  const double constant_Nm = ring_Nm + damping_Nm;
  return [bearing, balls, nu, constant_Nm](double relative_speed_rad_s) {
    return palmgren_friction_moment(bearing, balls, relative_speed_rad_s * 30 / std::numbers::pi, nu).total_Nm +
           constant_Nm;
  };
}

/// The moving mesh of the case: a rigid rim on the case's generator curve (flank table every pitch/64), or, for
/// rim = "fem", the rim coupled through the body the fem job solved (`solved`); the tooth pairs from `series`.
std::shared_ptr<const MovingMesh> moving_mesh(const Case& c, const DynamicsParams& p, const SeriesParts& series,
                                              const SolvedBody* solved) {
  const ToothCompliance teeth = p.pair_stiffness == PairStiffness::Teeth ? series.tooth_pair_m_per_N : ToothCompliance{};
  if (!solved) {
    const double rm = rim_mean_radius(c.flexspline), w0 = radial_deformation_m(flexspline_model(c));
    const NeutralCurve curve =
        c.wave_generator ? generator_neutral_curve(rm, w0, *c.wave_generator) : cam_neutral_curve(rm, w0);
    return std::make_shared<MovingMesh>(rigid_rim_mesh(*c.gear, curve, teeth, 64));
  }
  const double rated = c.load.rated_torque_Nm.value_or(c.load.torque_Nm);
  // The constant law's pair is a compliance 1/k too (linear with the rim coupled: validate_moving); its least value
  // (the stiffest k of the variation) is what the contact problem adds at least on the flanks' diagonal.
  const double k_max = p.stiffness_N_per_m + std::abs(p.stiffness_variation_N_per_m);
  const ToothCompliance pairs = teeth ? teeth : ToothCompliance([k_max](double, double) { return 1.0 / k_max; });
  return std::make_shared<MovingMesh>(naming_file(c.path, [&] {  // the flank table every pitch/64: see test_moving
    return fem_coupled_mesh(flexspline_model(c), *solved->body, solved->readout, pairs, rated, p.compliance_phases,
                            std::max(1, 64 / p.compliance_phases));
  }));
}

}  // namespace

DynamicsJobModel dynamics_model(const Case& c, DynamicsParams p, const DynamicsModelOptions& o, OutputSet& out) {
  const bool moving = p.pair_motion == PairMotion::Moving;
  if (moving) validate_moving(p, c.path);
  if (!moving && c.contact.friction_coefficient > 0) {
    std::ostringstream os;
    os << c.path << ": contact.friction_coefficient = " << c.contact.friction_coefficient
       << "; the flanks' friction acts on moving pairs only: set dynamics.pairs = \"moving\" (or --pairs moving), "
          "or friction_coefficient = 0";
    throw InputError(os.str());
  }
  if (!o.fem_result.empty()) {
    p.flexspline_compliance_rad_per_Nm = read_fem_compliance(o.fem_result);
    progress("dynamics: flexspline rim and flange joined by 1/C_tau, C_tau = " +
             std::to_string(p.flexspline_compliance_rad_per_Nm) + " rad/(N m) from " + o.fem_result);
  }
  DynamicsJobModel r;
  std::vector<ToothPair> pairs = frozen_pairs(c, p, o, r.source);
  r.model = make_model(*c.gear, c.flexspline, c.flexspline.shape == FlexsplineShape::Cup, c.material, p,
                       std::move(pairs), c.path);
  // The tooth pairs' compliance (an FEM of its own, run once here) where the moving pairs or the bearing's loads use it.
  const bool teeth_used = (moving && p.pair_stiffness == PairStiffness::Teeth) || c.lubricant.has_value();
  const SeriesParts series = teeth_used ? series_parts(c) : SeriesParts{};
  std::optional<SolvedBody> solved;  // the rim coupled through the FEM: its body serves the bearing's loads too
  if (moving && p.rim == RimCoupling::Fem) {
    naming_file(c.path, [&] { check_contact_model(flexspline_model(c)); });
    solved = solve_body(c, out);
  }
  if (moving) {
    r.model.moving = moving_mesh(c, p, series, solved ? &*solved : nullptr);
    r.model.pairs.clear();
    r.source = r.model.moving->source;
  }
  r.model.friction_coefficient = c.contact.friction_coefficient;
  r.model.generator_moment_Nm =
      generator_moment(c, p.load_torque_Nm, series, solved ? &*solved : nullptr, r.bearing_source);
  return r;
}

}  // namespace sw::app
