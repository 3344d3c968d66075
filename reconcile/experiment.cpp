#include "reconcile/experiment.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <tuple>

#include "common/error.hpp"

namespace sw::reconcile {

Branches find_branches(const Eigen::VectorXd& x, double threshold) {
  const int n = static_cast<int>(x.size());
  Branches b;
  b.direction = Eigen::VectorXd::Zero(n);
  b.branch_start.assign(n, 0);
  if (n == 0) return b;
  // Initial direction: the first move larger than the threshold.
  int dir = 1;
  for (int i = 1; i < n; ++i) {
    if (std::abs(x[i] - x[0]) > threshold) {
      dir = x[i] > x[0] ? 1 : -1;
      break;
    }
  }
  int extreme = 0;
  std::vector<int> turning{0};
  std::vector<int> dirs{dir};
  for (int i = 1; i < n; ++i) {
    if ((dir > 0 && x[i] > x[extreme]) || (dir < 0 && x[i] < x[extreme])) extreme = i;
    if ((dir > 0 && x[extreme] - x[i] > threshold) || (dir < 0 && x[i] - x[extreme] > threshold)) {
      turning.push_back(extreme);
      dir = -dir;
      dirs.push_back(dir);
      extreme = i;
    }
  }
  for (std::size_t s = 0; s < turning.size(); ++s) {
    const int from = s == 0 ? 0 : turning[s] + 1;
    const int to = s + 1 < turning.size() ? turning[s + 1] : n - 1;
    for (int i = from; i <= to; ++i) {
      b.direction[i] = dirs[s];
      b.branch_start[i] = turning[s];
    }
  }
  b.reversals.assign(turning.begin() + 1, turning.end());
  return b;
}

namespace {
Eigen::VectorXd to_vec(const std::vector<double>& v) { return Eigen::Map<const Eigen::VectorXd>(v.data(), v.size()); }
}  // namespace

Kind Baseline::kind() const {
  return std::visit([](const auto& p) { return p.kind; }, prediction);
}

Kind Experiment::kind() const {
  return std::visit([](const auto& d) { return d.kind; }, data);
}

DynamicsPrediction with_remembered_runs(DynamicsPrediction d) {
  if (!d.dynamics_run) return d;
  using Key = std::tuple<double, double, double, double, double>;
  auto store = std::make_shared<std::map<Key, DynamicsRun>>();
  d.dynamics_run = [run = d.dynamics_run, store](const DynamicsVariation& v) {
    const Key key{v.stiffness_ratio, v.stiffness_phase_rad, v.damping_Ns_per_m, v.drag_coulomb_Nm,
                  v.drag_viscous_Nms_per_rad};
    auto it = store->find(key);
    if (it == store->end()) it = store->emplace(key, run(v)).first;
    return it->second;
  };
  return d;
}

namespace {

std::string model_name(const TorsionPrediction& p) { return p.twist_rad ? "curve" : "fem"; }
std::string model_name(const TransmissionPrediction&) { return "ideal_ratio"; }
std::string model_name(const BacklashPrediction&) { return "kinematic"; }
std::string model_name(const DynamicsPrediction&) { return "dynamics_model"; }

}  // namespace

std::string default_model_name(const Prediction& prediction) {
  return std::visit([](const auto& p) { return model_name(p); }, prediction);
}

Eigen::VectorXd resample(const std::vector<double>& t, const std::vector<double>& y, const Eigen::VectorXd& at) {
  Eigen::VectorXd out(at.size());
  const std::size_t m = t.size();
  if (m == 0) return Eigen::VectorXd::Zero(at.size());
  std::size_t j = 0;
  for (Eigen::Index i = 0; i < at.size(); ++i) {
    const double x = at[i];
    while (j + 2 < m && t[j + 1] < x) ++j;
    if (m == 1 || x <= t[0]) { out[i] = y[0]; continue; }
    if (x >= t[m - 1]) { out[i] = y[m - 1]; continue; }
    while (j + 1 < m && t[j + 1] < x) ++j;
    const double w = (x - t[j]) / std::max(t[j + 1] - t[j], 1e-300);
    out[i] = (1.0 - w) * y[j] + w * y[j + 1];
  }
  return out;
}

Eigen::MatrixXd mesh_harmonics(const DynamicsExperiment& d, int orders) {
  Eigen::MatrixXd m(d.mesh_phase_rad.size(), 2 * orders);
  for (int k = 1; k <= orders; ++k) {
    m.col(2 * k - 2) = (k * d.mesh_phase_rad.array()).cos();
    m.col(2 * k - 1) = (k * d.mesh_phase_rad.array()).sin();
  }
  return m;
}

Eigen::MatrixXd mesh_lines(const DynamicsExperiment& d) { return mesh_harmonics(d, 2); }

namespace {

/// The damping response at c (clamped to the table): Lagrange cubic through the four table runs around c (linear
/// with two). Interpolation error O(h^4) on the table's spacing: linear interpolation between the runs at 1682 and
/// 2000 N*s/m read a concealed 1700 2.4 % low on the frozen seed gear, more than its own scatter.
Eigen::VectorXd damping_response_at(const DynamicsExperiment& d, double c_Ns_per_m) {
  const std::vector<double>& c = d.damping_table_Ns_per_m;
  const int m = static_cast<int>(c.size());
  const double at = std::clamp(c_Ns_per_m, c.front(), c.back());
  const int j = std::clamp(static_cast<int>(std::upper_bound(c.begin(), c.end(), at) - c.begin()) - 1, 0, m - 2);
  const int points = std::min(m, 4);
  const int k0 = std::clamp(j - 1, 0, m - points);
  Eigen::VectorXd r = Eigen::VectorXd::Zero(d.mesh_phase_rad.size());
  for (int i = k0; i < k0 + points; ++i) {
    double w = 1.0;
    for (int l = k0; l < k0 + points; ++l)
      if (l != i) w *= (at - c[l]) / (c[i] - c[l]);
    r += w * d.damping_response.col(i);
  }
  return r;
}

}  // namespace

Eigen::VectorXd damping_secant(const DynamicsExperiment& d, double c_Ns_per_m) {
  const std::vector<double>& c = d.damping_table_Ns_per_m;
  if (c.size() < 2) return Eigen::VectorXd::Zero(d.mesh_phase_rad.size());
  const double c0 = d.model.damping_Ns_per_m;
  const double at = std::clamp(c_Ns_per_m, c.front(), c.back());
  const double h = 1e-3 * std::max(c0, c[1] - c[0]);
  if (std::abs(at - c0) < h) {  // the secant's limit at c0: the interpolant's slope there
    const double lo = std::max(c0 - h, c.front()), hi = std::min(c0 + h, c.back());
    return (damping_response_at(d, hi) - damping_response_at(d, lo)) / (hi - lo);
  }
  return (damping_response_at(d, at) - damping_response_at(d, c0)) / (at - c0);
}

double invert_calibration(const std::vector<double>& x, const std::vector<double>& y, double x_ref, double value) {
  const int m = static_cast<int>(x.size());
  if (m < 2) return x_ref;
  std::vector<int> order(m - 1);
  for (int i = 0; i < m - 1; ++i) order[i] = i;
  auto dist = [&](int i) {
    const double mid = 0.5 * (x[i] + x[i + 1]);
    return std::abs(std::log(std::max(mid, 1e-300)) - std::log(std::max(x_ref, 1e-300)));
  };
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return dist(a) < dist(b); });
  for (int i : order) {
    const double lo = std::min(y[i], y[i + 1]), hi = std::max(y[i], y[i + 1]);
    if (value >= lo && value <= hi && hi > lo) return x[i] + (value - y[i]) / (y[i + 1] - y[i]) * (x[i + 1] - x[i]);
  }
  // Beyond the curve: extend the end segment on the side of the value.
  const bool rising = y[m - 1] > y[0];
  const bool above = rising ? value > std::max(y[0], y[m - 1]) : value < std::min(y[0], y[m - 1]);
  const int i = above ? m - 2 : 0;
  const double slope = (y[i + 1] - y[i]) / (x[i + 1] - x[i]);
  return slope != 0.0 ? x[i] + (value - y[i]) / slope : x[i];
}

Recording rows_from(const Recording& rec, double from_s) {
  const std::vector<double>* t = rec.column("time_s");
  if (!t || from_s <= 0.0) return rec;
  Recording out = rec;
  for (auto& v : out.values) v.clear();
  out.lines.clear();
  for (std::size_t i = 0; i < rec.rows(); ++i) {
    if ((*t)[i] < from_s) continue;
    for (std::size_t c = 0; c < rec.values.size(); ++c) out.values[c].push_back(rec.values[c][i]);
    out.lines.push_back(rec.lines[i]);
  }
  if (static_cast<int>(out.rows()) < kMinSamples)
    throw InputError(rec.path + ": " + std::to_string(out.rows()) + " rows from time_s = " + std::to_string(from_s) +
                     " s (the model's steady window, which is what reconcile compares); it needs at least " +
                     std::to_string(kMinSamples) + ": record longer steady running");
  return out;
}

namespace {

/// The twist (rad) a torsion prediction gives at each row: its loop's branch the torque is on, its curve, or C_tau T.
Eigen::VectorXd torsion_response(const TorsionPrediction& p, const TorsionExperiment& t) {
  if (!p.twist_rad && !p.branch_twist_rad) return p.compliance_rad_per_Nm * t.torque_Nm;
  Eigen::VectorXd twist(t.torque_Nm.size());
  for (int i = 0; i < t.torque_Nm.size(); ++i)
    twist[i] = p.branch_twist_rad ? p.branch_twist_rad(t.torque_Nm[i], t.direction[i]) : p.twist_rad(t.torque_Nm[i]);
  return twist;
}

/// The backlash (um) a backlash prediction gives at each wave-generator angle.
Eigen::VectorXd backlash_response(const BacklashPrediction& p, const Eigen::VectorXd& wg_angle_rad) {
  Eigen::VectorXd backlash(wg_angle_rad.size());
  for (int i = 0; i < wg_angle_rad.size(); ++i) backlash[i] = p.backlash_um(wg_angle_rad[i]);
  return backlash;
}

/// What every kind shares: the rows (at least kMinSamples), their time, the baseline's name and source.
Experiment experiment_frame(const Recording& rec, const Baseline& base) {
  Experiment e;
  e.n = static_cast<int>(rec.rows());
  e.baseline_model = base.model.empty() ? default_model_name(base.prediction) : base.model;
  e.baseline_source = base.source;
  if (e.n < kMinSamples)
    throw InputError(rec.path + ": rows = " + std::to_string(e.n) + "; reconcile needs at least " +
                     std::to_string(kMinSamples) + " samples (noise model, held-out block, signature tests)");
  if (const auto* t = rec.column("time_s")) {
    e.time = to_vec(*t);
    e.has_time = true;
  } else {
    e.time = Eigen::VectorXd::LinSpaced(e.n, 0.0, e.n - 1.0);
  }
  return e;
}

/// The torque's branches: direction, torque since the last reversal, and the amplitude (median |T| at reversals).
void add_branches(TorsionExperiment& t, double range_Nm) {
  const int n = static_cast<int>(t.torque_Nm.size());
  const Branches br = find_branches(t.torque_Nm, 0.02 * range_Nm);
  t.direction = br.direction;
  t.since_reversal_Nm.resize(n);
  for (int i = 0; i < n; ++i) t.since_reversal_Nm[i] = std::abs(t.torque_Nm[i] - t.torque_Nm[br.branch_start[i]]);
  std::vector<double> amps;
  for (int r : br.reversals) amps.push_back(std::abs(t.torque_Nm[r]));
  if (amps.empty()) {
    t.torque_amplitude_Nm = t.torque_Nm.cwiseAbs().maxCoeff();
  } else {
    std::nth_element(amps.begin(), amps.begin() + amps.size() / 2, amps.end());
    t.torque_amplitude_Nm = amps[amps.size() / 2];
  }
}

/// The drive's catalog size and rated torque from the recording's metadata (0 when absent).
void add_drive_metadata(TorsionExperiment& t, const Recording& rec) {
  if (const auto size = rec.meta_number("size")) t.drive_size = static_cast<int>(std::lround(*size));
  if (const auto rated = rec.meta_number("rated_torque_Nm")) {
    if (!(*rated > 0.0))
      throw InputError(rec.path + ": metadata rated_torque_Nm = " + std::to_string(*rated) + "; must be > 0");
    t.rated_torque_Nm = *rated;
  }
}

Experiment experiment_of(const Recording& rec, const Baseline& base, const TorsionPrediction& p) {
  Experiment e = experiment_frame(rec, base);
  if (!(p.compliance_rad_per_Nm > 0.0))
    throw InputError(rec.path + ": compliance_rad_per_Nm = " + std::to_string(p.compliance_rad_per_Nm) +
                     "; a torsion baseline needs C_tau > 0 (give --fem DIR/result.json or --compliance)");
  TorsionExperiment t;
  t.model = p;
  t.torque_Nm = to_vec(*rec.column("torque_Nm"));
  e.measured = to_vec(*rec.column("twist_rad"));
  const double range = t.torque_Nm.maxCoeff() - t.torque_Nm.minCoeff();
  if (!(range > 0.0)) throw InputError(rec.path + ": torque_Nm is constant; a torsion test must vary the torque");
  add_drive_metadata(t, rec);
  add_branches(t, range);
  e.baseline = torsion_response(p, t);
  e.response_name = "twist_rad";
  e.response_unit = "rad";
  e.data = std::move(t);
  return e;
}

Experiment experiment_of(const Recording& rec, const Baseline& base, const TransmissionPrediction&) {
  Experiment e = experiment_frame(rec, base);
  const DriveGear& g = base.gear;
  if (g.teeth_flexspline <= 0 || g.teeth_circular <= g.teeth_flexspline)
    throw InputError(rec.path + ": teeth z_f = " + std::to_string(g.teeth_flexspline) + ", z_c = " +
                     std::to_string(g.teeth_circular) +
                     "; the transmission baseline needs 0 < z_f < z_c (case [gear] or metadata teeth_*)");
  TransmissionExperiment t;
  t.wg_angle_rad = to_vec(*rec.column("wg_angle_rad"));
  e.measured = to_vec(*rec.column("output_angle_rad"));
  const double ratio = double(g.teeth_circular - g.teeth_flexspline) / g.teeth_flexspline;
  e.baseline = -ratio * t.wg_angle_rad;
  t.output_angle_rad = e.baseline;
  e.response_name = "output_angle_rad";
  e.response_unit = "rad";
  e.data = std::move(t);
  return e;
}

Experiment experiment_of(const Recording& rec, const Baseline& base, const BacklashPrediction& p) {
  Experiment e = experiment_frame(rec, base);
  if (!p.backlash_um)
    throw InputError(rec.path + ": kind = backlash; the basic kinematic backlash model is not available");
  BacklashExperiment b;
  b.model = p;
  b.pitch_radius_m = base.gear.pitch_radius_m;
  b.wg_angle_rad = to_vec(*rec.column("wg_angle_deg")) * (M_PI / 180.0);
  b.torque_Nm = to_vec(*rec.column("torque_Nm"));
  e.measured = to_vec(*rec.column("backlash_um"));
  e.baseline = backlash_response(p, b.wg_angle_rad);
  e.response_name = "backlash_um";
  e.response_unit = "um";
  e.data = std::move(b);
  return e;
}

/// The baseline run of the dynamics model, checked to cover the recording's time.
DynamicsRun baseline_run(const Recording& rec, const DynamicsPrediction& p, const Eigen::VectorXd& time) {
  const DynamicsRun b0 = p.dynamics_run(DynamicsVariation{});
  if (b0.time_s.size() < 2 || time.maxCoeff() > b0.time_s.back() * (1.0 + 1e-9) + 1e-12)
    throw InputError(rec.path + ": time_s reaches " + std::to_string(time.maxCoeff()) +
                     " s; the case's dynamics run covers only " +
                     std::to_string(b0.time_s.empty() ? 0.0 : b0.time_s.back()) + " s (raise dynamics.duration_s)");
  return b0;
}

/// Wave-generator angle of a run (the integral of its speed), for plots in wave-generator orders.
std::vector<double> wg_angle_of(const DynamicsRun& run) {
  std::vector<double> wg_angle(run.time_s.size(), 0.0);
  for (std::size_t i = 1; i < wg_angle.size(); ++i)
    wg_angle[i] = wg_angle[i - 1] + 0.5 * (run.wg_speed_rpm[i] + run.wg_speed_rpm[i - 1]) * (M_PI / 30.0) *
                                        (run.time_s[i] - run.time_s[i - 1]);
  return wg_angle;
}

/// The meshing force of the model with a variation, on the recording's time.
using ForceOf = std::function<Eigen::VectorXd(const DynamicsVariation&)>;

/// The k(t) sensitivity columns from a small one-sided step, split into the part locked to the mesh and the rest.
void add_stiffness_sensitivity(DynamicsExperiment& d, const ForceOf& force, const Eigen::VectorXd& baseline) {
  // The response bends with r (flanks lose and regain contact), and a step of 0.1 folds that bend into the column (on
  // moving pairs, a concealed r = 0.048 left 26 % of its signal outside the columns of a 0.1 step, 7.7 % with 0.02;
  // central differences at 0.05: 29 %).
  const double dk = 0.02;
  DynamicsVariation v;
  v.stiffness_ratio = dk;
  d.sensitivity.col(0) = (force(v) - baseline) / dk;
  v.stiffness_phase_rad = 0.5 * M_PI;
  d.sensitivity.col(1) = (force(v) - baseline) / dk;
  // Split into the part locked to the mesh (k(t) is periodic in the mesh phase, so is the steady response to it)
  // and the rest (the load step's ringing changed, contacts that open and close at other times), which may
  // answer r non-smoothly: r is read from the locked part alone (frozen seed gear: 51 % of an r = 0.05 response
  // lay outside the raw columns, and r read from them was half the truth).
  const Eigen::MatrixXd harmonics = mesh_harmonics(d, kMeshHarmonics);
  const auto harmonics_qr = harmonics.colPivHouseholderQr();
  d.stiffness_unlocked.resize(baseline.size(), 2);
  for (int j = 0; j < 2; ++j) {
    const Eigen::VectorXd locked = harmonics * harmonics_qr.solve(Eigen::VectorXd(d.sensitivity.col(j)));
    d.stiffness_unlocked.col(j) = d.sensitivity.col(j) - locked;
    d.sensitivity.col(j) = locked;
  }
}

/// The damping and drag sensitivity columns (2, 3, 4).
void add_damping_and_drag_sensitivity(DynamicsExperiment& d, const ForceOf& force, const Eigen::VectorXd& baseline) {
  const DynamicsPrediction& p = d.model;
  const double c0 = p.damping_Ns_per_m;
  if (c0 > 0.0) {
    DynamicsVariation lo, hi;
    lo.damping_Ns_per_m = 0.5 * c0;
    hi.damping_Ns_per_m = 1.5 * c0;
    d.sensitivity.col(2) = (force(hi) - force(lo)) / c0;
  } else {
    DynamicsVariation hi;
    hi.damping_Ns_per_m = 1e3;
    d.sensitivity.col(2) = (force(hi) - baseline) / 1e3;
  }
  const double tc = std::max(0.05 * p.load_torque_Nm, 0.1);
  DynamicsVariation dc;
  dc.drag_coulomb_Nm = tc;
  d.sensitivity.col(3) = (force(dc) - baseline) / tc;
  const double bv = tc / std::max(p.output_speed_rad_s, 1e-6);
  DynamicsVariation dv;
  dv.drag_viscous_Nms_per_rad = bv;
  d.sensitivity.col(4) = (force(dv) - baseline) / bv;
}

/// Calibration of the nonlinear responses (the mesh responds to Δk and c far from linearly: flanks leave and regain
/// contact, the ringing after a load step decays at a rate set by c): the k(t) curve and the damping table.
void add_calibration(DynamicsExperiment& d, const ForceOf& force, const Eigen::VectorXd& baseline) {
  const auto stiffness_qr = Eigen::MatrixXd(d.sensitivity.leftCols(2)).colPivHouseholderQr();
  d.calib_ratio = {0.0, 0.01, 0.03, 0.1, 0.3, 0.6, 0.9};
  d.calib_stiffness_beta = {0.0};
  for (std::size_t j = 1; j < d.calib_ratio.size(); ++j) {
    DynamicsVariation sv;
    sv.stiffness_ratio = d.calib_ratio[j];
    const Eigen::VectorXd b = stiffness_qr.solve(Eigen::VectorXd(force(sv) - baseline));
    d.calib_stiffness_beta.push_back(std::hypot(b[0], b[1]));
  }
  // The response to the damping coefficient on a geometric table (ratio 2^(1/4), c0/8 to 8 c0, and 0 when the
  // model has none): the fit reads c from it as a nonlinear parameter (damping_response_at).
  const double c0 = d.model.damping_Ns_per_m;
  const double cref = c0 > 0.0 ? c0 : 1e3;
  if (c0 == 0.0) d.damping_table_Ns_per_m.push_back(0.0);
  for (int k = -kDampingTableSteps; k <= kDampingTableSteps; ++k)
    d.damping_table_Ns_per_m.push_back(cref * std::pow(2.0, k / 4.0));
  d.damping_response.resize(baseline.size(), d.damping_table_Ns_per_m.size());
  for (std::size_t j = 0; j < d.damping_table_Ns_per_m.size(); ++j) {
    DynamicsVariation cv;
    cv.damping_Ns_per_m = d.damping_table_Ns_per_m[j];
    d.damping_response.col(j) = cv.damping_Ns_per_m == c0 ? Eigen::VectorXd::Zero(baseline.size())
                                                          : Eigen::VectorXd(force(cv) - baseline);
  }
}

Experiment experiment_of(const Recording& recording, const Baseline& base, const DynamicsPrediction& p) {
  const Recording rec = rows_from(recording, p.analysis_from_s);
  Experiment e = experiment_frame(rec, base);
  if (!p.dynamics_run)
    throw InputError(rec.path + ": kind = dynamics; the dynamics baseline (the case's [dynamics] model) is not "
                     "available");
  if (!e.has_time)
    throw InputError(rec.path + ": time_s missing; a dynamics recording needs time_s as its first column");
  e.measured = to_vec(*rec.column("mesh_force_N"));
  e.response_name = "mesh_force_N";
  e.response_unit = "N";
  const DynamicsRun b0 = baseline_run(rec, p, e.time);
  DynamicsExperiment d;
  d.model = p;
  e.baseline = resample(b0.time_s, b0.mesh_force_N, e.time);
  d.mesh_phase_rad = resample(b0.time_s, b0.mesh_phase_rad, e.time);
  d.wg_angle_rad = resample(b0.time_s, wg_angle_of(b0), e.time);
  // Sensitivity basis from a few perturbed runs (the dynamics run is ~0.1 s).
  const ForceOf force = [&](const DynamicsVariation& v) {
    return resample(b0.time_s, p.dynamics_run(v).mesh_force_N, e.time);
  };
  d.sensitivity.resize(e.n, 5);
  add_stiffness_sensitivity(d, force, e.baseline);
  add_damping_and_drag_sensitivity(d, force, e.baseline);
  add_calibration(d, force, e.baseline);
  e.data = std::move(d);
  return e;
}

}  // namespace

Eigen::VectorXd predicted_response(const Experiment& e, const Prediction& prediction) {
  if (const auto* p = std::get_if<TorsionPrediction>(&prediction); p && e.kind() == Kind::Torsion)
    return torsion_response(*p, as<TorsionExperiment>(e));
  if (const auto* p = std::get_if<BacklashPrediction>(&prediction); p && p->backlash_um && e.kind() == Kind::Backlash)
    return backlash_response(*p, as<BacklashExperiment>(e).wg_angle_rad);
  throw InputError("a re-run of the model gives a " + default_model_name(prediction) + " prediction; a " +
                   kind_name(e.kind()) + " experiment reads only a torsion or backlash response of its own kind");
}

Experiment make_experiment(const Recording& recording, const Baseline& base) {
  if (recording.kind != base.kind())
    throw InputError(recording.path + ": kind = " + kind_name(recording.kind) + "; the baseline is of kind " +
                     kind_name(base.kind()));
  return std::visit([&](const auto& p) { return experiment_of(recording, base, p); }, base.prediction);
}


}  // namespace sw::reconcile
