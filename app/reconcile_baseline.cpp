#include "app/reconcile_baseline.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>

#include <nlohmann/json.hpp>

#include "app/commands.hpp"
#include "app/dynamics_job.hpp"
#include "common/constants.hpp"
#include "common/error.hpp"
#include "common/format.hpp"
#include "dynamics/model.hpp"
#include "dynamics/kinematic_pairs.hpp"
#include "dynamics/simulate.hpp"
#include "kinematics/backlash.hpp"
#include "kinematics/neutral_curve.hpp"
#include "io/atomic_file.hpp"
#include "io/contact_output.hpp"
#include "io/fem_output.hpp"

namespace sw::app {

using reconcile::Kind;

namespace {

/// The dynamics baseline's integrator tolerances at most (make_baseline): the code's defaults.
constexpr double kBaselineRelativeTolerance = 1e-8, kBaselineAbsoluteTolerance_rad = 1e-13;

double compliance_from_fem(const std::string& path) { return read_fem_compliance(path); }

/// Slope (rad per N*m) of the polyline's first or last segment with a torque step.
double end_slope(const TorqueTwist& c, bool top) {
  const auto& t = c.torque_Nm;
  std::size_t a = 0;
  if (top) {
    a = t.size() - 2;
    while (t[a] == t.back()) --a;
  } else {
    while (t[a + 1] == t.front()) ++a;
  }
  return (c.twist_rad[a + 1] - c.twist_rad[a]) / (t[a + 1] - t[a]);
}

/// A recording cycled to the loop's own +-rated torque (each end within kCurveEndTolerance of it) is held against the
/// loop's branches, loading while its torque rises and unloading while it falls; any other history against the middle
/// line (the branches of a frictional loop hold for its own cycle only), said in the notes.
void hold_against_loop(const TorqueLoop& loop, double rated_Nm, const std::vector<double>* torque,
                       reconcile::TorsionPrediction& p, std::vector<std::string>& notes) {
  const double loss = hysteresis_loss_rad(loop);
  const LoopWidth widest = widest_loop_width(loop);
  const std::string what = "the curve is a loop (friction in the teeth; hysteresis loss " +
                           six_digits(loss * kArcmin) + " arcmin at +-" + six_digits(rated_Nm) + " N*m, widest " +
                           six_digits(widest.width_rad * kArcmin) + " arcmin at " + six_digits(widest.torque_Nm) +
                           " N*m)";
  const double tol = kCurveEndTolerance * rated_Nm;
  auto cycled_to_rated = [&] {
    if (!torque || torque->empty()) return false;
    const auto [tmin, tmax] = std::minmax_element(torque->begin(), torque->end());
    return std::abs(*tmax - rated_Nm) <= tol && std::abs(*tmin + rated_Nm) <= tol;
  };
  if (!cycled_to_rated()) {
    notes.push_back(what + "; the recording is not cycled to +-" + six_digits(rated_Nm) +
                    " N*m, so it is held against the loop's middle line");
    return;
  }
  p.branch_twist_rad = [loop, tol](double T, double direction) {
    return twist_at(direction > 0 ? loop.loading : loop.unloading, T, tol);
  };
  p.loop_loss_rad = loss;
  notes.push_back(what + "; the recording is held against its loading branch while the torque rises and its "
                  "unloading branch while it falls");
}

/// The torsion baseline from the contact stage's torque-twist curve: its loop's middle line (or its branches, see
/// hold_against_loop), checked to cover the recording's torque range.
void contact_baseline(const BaselineSources& src, reconcile::Baseline& b, std::vector<std::string>& notes) {
  reconcile::TorsionPrediction p;
  const ContactCurve contact = src.contact_curve ? *src.contact_curve : read_contact_curve(src.contact_result);
  const TorqueTwist& curve = contact.middle_line;
  const double lo = curve.torque_Nm.front(), hi = curve.torque_Nm.back();
  const double tol = kCurveEndTolerance * contact.rated_torque_Nm;
  const std::vector<double>* torque = src.recording ? src.recording->column("torque_Nm") : nullptr;
  if (torque && !torque->empty()) {
    const auto [tmin, tmax] = std::minmax_element(torque->begin(), torque->end());
    if (*tmin < lo - tol || *tmax > hi + tol)
      throw InputError(src.recording->path + ": torque_Nm spans [" + six_digits(*tmin) + ", " + six_digits(*tmax) +
                       "] N*m but the torque-twist curve of " + src.contact_result + " covers [" + six_digits(lo) + ", " +
                       six_digits(hi) + "] N*m (rated " + six_digits(contact.rated_torque_Nm) +
                       " N*m); the curve is not extrapolated: record within it, or compare with --baseline fem");
    if (*tmin < lo || *tmax > hi)
      notes.push_back("the recording's torque [" + six_digits(*tmin) + ", " + six_digits(*tmax) + "] N*m passes the curve's ends [" +
                      six_digits(lo) + ", " + six_digits(hi) + "] N*m by less than " + six_digits(100 * kCurveEndTolerance) +
                      " % of rated torque; its end segments are extended there");
  }
  if (src.compliance || !src.fem_result.empty())
    notes.push_back("C_tau (--fem, --compliance) is not used: the torsion baseline is the contact curve");
  b.model = "contact";
  b.source = src.contact_result;
  p.twist_rad = [curve, tol](double T) { return twist_at(curve, T, tol); };
  p.compliance_rad_per_Nm = 0.5 * (end_slope(curve, false) + end_slope(curve, true));
  if (!(p.compliance_rad_per_Nm > 0.0))
    throw InputError(src.contact_result + ": torque_twist: the curve's end slopes give " +
                     six_digits(p.compliance_rad_per_Nm) + " rad/(N*m); twist must rise with torque");
  p.curve_t1_Nm = contact.catalog_t1_Nm;
  p.curve_t2_Nm = contact.catalog_t2_Nm;
  notes.push_back("torsion baseline: the drive's torque-twist curve of " + src.contact_result + " (middle line, " +
                  std::to_string(curve.torque_Nm.size()) + " points over [" + six_digits(lo) + ", " + six_digits(hi) +
                  "] N*m; end slope " + six_digits(p.compliance_rad_per_Nm) + " rad/(N*m))");
  if (contact.loop) hold_against_loop(*contact.loop, contact.rated_torque_Nm, torque, p, notes);
  b.prediction = p;
}

std::optional<int> meta_int(const reconcile::Recording* r, const std::string& key) {
  if (!r) return std::nullopt;
  const auto v = r->meta_number(key);
  if (!v) return std::nullopt;
  return static_cast<int>(std::lround(*v));
}

/// The pair model in words: frozen or moving pairs, the rim, the pair stiffness.
std::string pair_model_name(const DynamicsModel& m) {
  if (!m.moving) return "frozen tooth pairs";
  const std::string stiffness = m.params.pair_stiffness == PairStiffness::Teeth
                                    ? "tooth-pair compliance" : "constant pair stiffness k0";
  return std::string(m.moving->coupled() ? "moving tooth pairs coupled through the flexspline body (FEM)"
                                         : "moving tooth pairs on a rigid rim") + ", " + stiffness;
}

/// Moving pairs with the teeth's own compliance have no k0 for k(t) = k0 (1 + r sin(psi_mesh + phase)) to act on; the
/// same variation is each flank's compliance divided by 1 + r sin(psi_mesh + phase) at the flank's place. Tooth k sits
/// at phi_k = 2 pi k / z_f - sigma, so z_f phi_k = -z_f sigma (mod 2 pi) for every tooth, and the mesh phase is
/// psi_mesh = s z_f sigma (s the sense of the generator's travel relative to the flexspline): the table's factor at phi
/// is 1 + r sin(phase - s z_f phi), the same for all teeth at each instant, as k(t) is.
/// The table's node slopes of the compliance follow the quotient rule (c/g)' = c'/g - c g'/g^2, so the interpolant
/// stays the cubic Hermite of the modulated compliance.
MovingMesh with_stiffness_variation(const MovingMesh& mesh, double ratio, double phase_rad, double sense) {
  MovingMesh m = mesh;
  FlankTable& t = m.table;
  const double z = sense * m.teeth_flexspline;
  for (int side = 0; side < 2; ++side)
    for (int j = 0; j < t.size(); ++j) {
      const double phi = t.phi_start_rad + j * t.step_rad;
      const double g = 1.0 + ratio * std::sin(phase_rad - z * phi), dg = -z * ratio * std::cos(phase_rad - z * phi);
      double& c = t.compliance_m_per_N[side][j];
      double& dc = t.compliance_slope[side][j];
      dc = dc / g - c * dg / (g * g);
      c /= g;
    }
  return m;
}

/// The model of one variation: k(t), damping and output drag changed as the variation says.
DynamicsModel varied_model(const DynamicsModel& model, const SteadyState& ss, const reconcile::DynamicsVariation& v) {
  DynamicsModel m = model;
  const bool teeth = m.moving && m.params.pair_stiffness == PairStiffness::Teeth;
  if (teeth && v.stiffness_ratio != 0.0) {
    const int w = static_cast<int>(BodyId::WaveGenerator), f = static_cast<int>(BodyId::FlexsplineRim);
    const double sense = ss.speed_rad_s[w] - ss.speed_rad_s[f] >= 0.0 ? 1.0 : -1.0;
    m.moving = std::make_shared<MovingMesh>(
        with_stiffness_variation(*model.moving, v.stiffness_ratio, v.stiffness_phase_rad, sense));
  } else {
    m.params.stiffness_variation_N_per_m = v.stiffness_ratio * m.params.stiffness_N_per_m;
    m.params.stiffness_phase_deg = v.stiffness_phase_rad * 180.0 / M_PI;
  }
  if (v.damping_Ns_per_m >= 0.0) m.params.damping_Ns_per_m = v.damping_Ns_per_m;
  m.params.output_drag_coulomb_Nm += v.drag_coulomb_Nm;
  m.params.output_drag_viscous_Nms_per_rad += v.drag_viscous_Nms_per_rad;
  return m;
}

}  // namespace

TorsionBaseline parse_torsion_baseline(const std::string& text) {
  if (text == "fem") return TorsionBaseline::Fem;
  if (text == "contact") return TorsionBaseline::Contact;
  throw InputError("--baseline = '" + text + "'; expected fem (C_tau T of the flexspline body) or contact (the "
                   "drive's torque-twist curve from contact.json)");
}

reconcile::Baseline dynamics_baseline(const DynamicsModel& model) {
  reconcile::Baseline b;
  b.gear.teeth_flexspline = model.teeth_flexspline;
  b.gear.teeth_circular = model.teeth_circular;
  b.source = pair_model_name(model);
  const SteadyState ss = steady_state(model);
  reconcile::DynamicsPrediction p;
  p.damping_Ns_per_m = model.params.damping_Ns_per_m;
  p.mesh_frequency_Hz = ss.mesh_frequency_Hz;
  p.load_torque_Nm = model.params.load_torque_Nm;
  p.output_speed_rad_s = std::abs(ss.speed_rad_s[static_cast<int>(ss.output)]);
  if (model.moving) p.analysis_from_s = model.params.steady_from_s;
  p.dynamics_run = [model, ss](const reconcile::DynamicsVariation& v) {
    const DynamicsModel m = varied_model(model, ss, v);
    const DynamicsSeries s = simulate(m);
    reconcile::DynamicsRun r;
    r.time_s = s.time_s;
    const int wg = static_cast<int>(BodyId::WaveGenerator), out = static_cast<int>(ss.output);
    const int drv = static_cast<int>(ss.driven);
    const double rpm = 30.0 / M_PI;
    const double w_drive = std::abs(ss.speed_rad_s[drv]);
    const double rate = w_drive > 0 ? 2.0 * M_PI * ss.mesh_frequency_Hz / w_drive : 0.0;
    for (std::size_t i = 0; i < s.time_s.size(); ++i) {
      r.wg_speed_rpm.push_back(s.speed_rad_s[wg][i] * rpm);
      r.output_speed_rpm.push_back(s.speed_rad_s[out][i] * rpm);
      r.mesh_force_N.push_back(s.total_force_N[i]);
      r.mesh_phase_rad.push_back(rate * std::abs(s.angle_rad[drv][i]));
    }
    return r;
  };
  b.prediction = p;
  return b;
}

namespace {

/// The drive's gear: the case's when it has one (the recording's metadata checked against it), else the teeth the
/// recording's metadata gives.
reconcile::DriveGear drive_gear(const BaselineSources& src, std::vector<std::string>& notes) {
  reconcile::DriveGear g;
  const Case* c = src.case_file ? &*src.case_file : nullptr;
  const auto zf_meta = meta_int(src.recording, "teeth_flexspline");
  const auto zc_meta = meta_int(src.recording, "teeth_circular");
  if (c && c->gear) {
    g.teeth_flexspline = c->gear->teeth_flexspline;
    g.teeth_circular = c->gear->teeth_circular;
    g.pitch_radius_m = 0.5 * c->gear->module_m * c->gear->teeth_flexspline;
    if ((zf_meta && *zf_meta != g.teeth_flexspline) || (zc_meta && *zc_meta != g.teeth_circular))
      notes.push_back("the case (" + c->path + ") has teeth z_f = " + std::to_string(g.teeth_flexspline) +
                      ", z_c = " + std::to_string(g.teeth_circular) + " but the recording's metadata says z_f = " +
                      (zf_meta ? std::to_string(*zf_meta) : "?") + ", z_c = " + (zc_meta ? std::to_string(*zc_meta) : "?") +
                      "; the case is used");
  } else {
    if (zf_meta) g.teeth_flexspline = *zf_meta;
    if (zc_meta) g.teeth_circular = *zc_meta;
  }
  return g;
}

/// Torsion: C_tau T of the flexspline body (--compliance, or the FEM's result.json), or the contact curve.
void torsion_baseline(const BaselineSources& src, reconcile::Baseline& b, std::vector<std::string>& notes) {
  if (src.torsion == TorsionBaseline::Contact) return contact_baseline(src, b, notes);
  reconcile::TorsionPrediction p;
  b.model = "fem";
  if (src.compliance) {
    p.compliance_rad_per_Nm = *src.compliance;
    notes.push_back("C_tau = " + std::to_string(*src.compliance) + " rad/(N*m) from --compliance");
  } else if (!src.fem_result.empty()) {
    p.compliance_rad_per_Nm = compliance_from_fem(src.fem_result);
    b.source = src.fem_result;
    notes.push_back("C_tau from " + src.fem_result);
  } else {
    throw InputError("--fem: missing; a torsion baseline needs C_tau: give --fem DIR/result.json (from "
                     "`strainwave fem CASE.toml`) or --compliance RAD_PER_NM");
  }
  b.prediction = p;
}

std::string case_name(const Case* c) { return c ? c->path : std::string("case"); }

/// Transmission: the ideal ratio of the drive's teeth.
void transmission_baseline(const Case* c, reconcile::Baseline& b) {
  if (b.gear.teeth_flexspline <= 0 || b.gear.teeth_circular <= 0)
    throw InputError(case_name(c) + ": [gear] teeth missing; the transmission baseline needs z_f and z_c (case [gear] "
                     "or the recording's teeth_flexspline/teeth_circular metadata)");
  b.prediction = reconcile::TransmissionPrediction{};
}

/// Backlash: the basic kinematic model (phi0 = 0) of the case's gear on its neutral curve.
void backlash_baseline(const Case* c, reconcile::Baseline& b, std::vector<std::string>& notes) {
  if (!c || !c->gear)
    throw InputError(case_name(c) +
                     ": [gear] missing; the backlash baseline (basic kinematic model) needs the gear and flexspline");
  const double rm = rim_mean_radius(c->flexspline);
  const NeutralCurve curve = c->wave_generator
                                 ? generator_neutral_curve(rm, radial_deformation_m(flexspline_model(*c)), *c->wave_generator)
                                 : cam_neutral_curve(rm, radial_deformation_m(flexspline_model(*c)));
  const BacklashModel model = make_backlash_model(*c->gear, curve);
  reconcile::BacklashPrediction p;
  p.backlash_um = [model](double wg_angle_rad) { return 1e6 * min_backlash_m(model, wg_angle_rad, 0.0); };
  b.prediction = p;
  notes.push_back("backlash baseline: basic kinematic model (phi0 = 0) of " + c->path);
}

/// The case's [dynamics] parameters as the baseline runs them: constant mesh stiffness, and integrated tightly.
DynamicsParams baseline_dynamics_params(const Case& c, std::vector<std::string>& notes) {
  DynamicsParams q = c.dynamics ? *c.dynamics : DynamicsParams{};
  if (q.stiffness_variation_N_per_m != 0.0)
    notes.push_back("the case has dynamics.stiffness_variation_N_per_m = " +
                    std::to_string(q.stiffness_variation_N_per_m) + "; the baseline uses constant mesh stiffness");
  q.stiffness_variation_N_per_m = 0.0;
  // The experiment reads every effect from differences between runs, so the integrator's own error must sit far
  // below them: a case's display tolerance does not. At the seed case's 1e-6 / 1e-9 rad, changing any parameter by
  // 1e-8 moved its meshing force by 0.25 N RMS (another step sequence), against 4e-5 N at 1e-8 / 1e-13; a
  // concealed effect at the noise level is about 7 N.
  if (q.relative_tolerance > kBaselineRelativeTolerance || q.absolute_tolerance_rad > kBaselineAbsoluteTolerance_rad) {
    q.relative_tolerance = std::min(q.relative_tolerance, kBaselineRelativeTolerance);
    q.absolute_tolerance_rad = std::min(q.absolute_tolerance_rad, kBaselineAbsoluteTolerance_rad);
    notes.push_back("the baseline integrates at relative_tolerance " + six_digits(q.relative_tolerance) +
                    ", absolute_tolerance_rad " + six_digits(q.absolute_tolerance_rad) +
                    " (tighter than the case's): its effects are differences between runs");
  }
  return q;
}

/// Dynamics: the model `strainwave dynamics` builds from the case, its runs remembered.
void dynamics_baseline_of(const Case* c, const BaselineSources& src, reconcile::Baseline& b,
                          std::vector<std::string>& notes) {
  if (!c || !c->gear)
    throw InputError(case_name(c) + ": [gear] missing; the dynamics baseline needs the case's gear and [dynamics] table");
  const DynamicsParams q = baseline_dynamics_params(*c, notes);
  DynamicsModelOptions o;
  o.fem_result = src.fem_result;
  const std::filesystem::path fem_dir = default_out_dir(*c);
  if (q.pair_motion == PairMotion::Moving && q.rim == RimCoupling::Fem)
    notes.push_back("rim = \"fem\": the flexspline body's compliance from the FEM solved first, its result in " +
                    fem_dir.string() + " (each of the ~40 runs of the experiment then integrates the coupled mesh)");
  OutputSet fem_outputs(fem_dir);  // rim = "fem": the FEM's files, brought in before the experiment runs
  const DynamicsJobModel job = dynamics_model(*c, q, o, fem_outputs);
  fem_outputs.commit();
  const reconcile::Baseline d = dynamics_baseline(job.model);
  const auto& p = std::get<reconcile::DynamicsPrediction>(d.prediction);
  b.source = c->path + ": " + d.source;
  b.prediction = reconcile::with_remembered_runs(p);  // synth and the experiment share runs
  if (p.analysis_from_s > 0.0)
    notes.push_back("moving tooth pairs: the recording is compared from dynamics.steady_from_s = " +
                    six_digits(p.analysis_from_s) + " s on (in the run-up and at load steps the teeth separate and "
                    "strike again, and the meshing force answers the model's parameters by the impacts' timing)");
  notes.push_back("dynamics baseline: the [dynamics] model of " + c->path + " (" + to_string(q.configuration) + ", " +
                  d.source + ", constant mesh stiffness; " + job.source + "); f_m = " +
                  std::to_string(p.mesh_frequency_Hz) + " Hz");
}

}  // namespace

reconcile::Baseline make_baseline(Kind kind, const BaselineSources& src, std::vector<std::string>& notes) {
  reconcile::Baseline b;
  const Case* c = src.case_file ? &*src.case_file : nullptr;
  b.gear = drive_gear(src, notes);
  switch (kind) {
    case Kind::Torsion: torsion_baseline(src, b, notes); break;
    case Kind::Transmission: transmission_baseline(c, b); break;
    case Kind::Backlash: backlash_baseline(c, b, notes); break;
    case Kind::Dynamics: dynamics_baseline_of(c, src, b, notes); break;
  }
  return b;
}

}  // namespace sw::app
