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

Baseline with_remembered_runs(Baseline b) {
  if (!b.dynamics_run) return b;
  using Key = std::tuple<double, double, double, double, double>;
  auto store = std::make_shared<std::map<Key, DynamicsRun>>();
  b.dynamics_run = [run = b.dynamics_run, store](const DynamicsVariation& v) {
    const Key key{v.stiffness_ratio, v.stiffness_phase_rad, v.damping_Ns_per_m, v.drag_coulomb_Nm,
                  v.drag_viscous_Nms_per_rad};
    auto it = store->find(key);
    if (it == store->end()) it = store->emplace(key, run(v)).first;
    return it->second;
  };
  return b;
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

Eigen::MatrixXd mesh_harmonics(const Experiment& e, int orders) {
  Eigen::MatrixXd m(e.n, 2 * orders);
  for (int k = 1; k <= orders; ++k) {
    m.col(2 * k - 2) = (k * e.mesh_phase_rad.array()).cos();
    m.col(2 * k - 1) = (k * e.mesh_phase_rad.array()).sin();
  }
  return m;
}

Eigen::MatrixXd mesh_lines(const Experiment& e) { return mesh_harmonics(e, 2); }

namespace {

/// The damping response at c (clamped to the table): Lagrange cubic through the four table runs around c (linear
/// with two). Interpolation error O(h^4) on the table's spacing: linear interpolation between the runs at 1682 and
/// 2000 N*s/m read a concealed 1700 2.4 % low on the frozen seed gear, more than its own scatter.
Eigen::VectorXd damping_response_at(const Experiment& e, double c_Ns_per_m) {
  const std::vector<double>& c = e.damping_table_Ns_per_m;
  const int m = static_cast<int>(c.size());
  const double at = std::clamp(c_Ns_per_m, c.front(), c.back());
  const int j = std::clamp(static_cast<int>(std::upper_bound(c.begin(), c.end(), at) - c.begin()) - 1, 0, m - 2);
  const int points = std::min(m, 4);
  const int k0 = std::clamp(j - 1, 0, m - points);
  Eigen::VectorXd r = Eigen::VectorXd::Zero(e.n);
  for (int i = k0; i < k0 + points; ++i) {
    double w = 1.0;
    for (int l = k0; l < k0 + points; ++l)
      if (l != i) w *= (at - c[l]) / (c[i] - c[l]);
    r += w * e.damping_response.col(i);
  }
  return r;
}

}  // namespace

Eigen::VectorXd damping_secant(const Experiment& e, double c_Ns_per_m) {
  const std::vector<double>& c = e.damping_table_Ns_per_m;
  if (c.size() < 2) return Eigen::VectorXd::Zero(e.n);
  const double c0 = e.model.damping_Ns_per_m;
  const double at = std::clamp(c_Ns_per_m, c.front(), c.back());
  const double h = 1e-3 * std::max(c0, c[1] - c[0]);
  if (std::abs(at - c0) < h) {  // the secant's limit at c0: the interpolant's slope there
    const double lo = std::max(c0 - h, c.front()), hi = std::min(c0 + h, c.back());
    return (damping_response_at(e, hi) - damping_response_at(e, lo)) / (hi - lo);
  }
  return (damping_response_at(e, at) - damping_response_at(e, c0)) / (at - c0);
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

Experiment make_experiment(const Recording& recording, const Baseline& base) {
  const Recording rec = recording.kind == Kind::Dynamics ? rows_from(recording, base.analysis_from_s) : recording;
  Experiment e;
  e.kind = rec.kind;
  e.n = static_cast<int>(rec.rows());
  e.model = base;
  if (e.n < kMinSamples)
    throw InputError(rec.path + ": rows = " + std::to_string(e.n) + "; reconcile needs at least " +
                     std::to_string(kMinSamples) + " samples (noise model, held-out block, signature tests)");
  if (const auto* t = rec.column("time_s")) {
    e.time = to_vec(*t);
    e.has_time = true;
  } else {
    e.time = Eigen::VectorXd::LinSpaced(e.n, 0.0, e.n - 1.0);
  }
  switch (rec.kind) {
    case Kind::Torsion: {
      if (!(base.compliance_rad_per_Nm > 0.0))
        throw InputError(rec.path + ": compliance_rad_per_Nm = " + std::to_string(base.compliance_rad_per_Nm) +
                         "; a torsion baseline needs C_tau > 0 (give --fem DIR/result.json or --compliance)");
      e.torque_Nm = to_vec(*rec.column("torque_Nm"));
      e.measured = to_vec(*rec.column("twist_rad"));
      if (base.twist_rad) {
        e.baseline.resize(e.n);
        for (int i = 0; i < e.n; ++i) e.baseline[i] = base.twist_rad(e.torque_Nm[i]);
      } else {
        e.baseline = base.compliance_rad_per_Nm * e.torque_Nm;
      }
      e.response_name = "twist_rad";
      e.response_unit = "rad";
      const double range = e.torque_Nm.maxCoeff() - e.torque_Nm.minCoeff();
      if (!(range > 0.0)) throw InputError(rec.path + ": torque_Nm is constant; a torsion test must vary the torque");
      if (const auto size = rec.meta_number("size")) e.drive_size = static_cast<int>(std::lround(*size));
      if (const auto rated = rec.meta_number("rated_torque_Nm")) {
        if (!(*rated > 0.0))
          throw InputError(rec.path + ": metadata rated_torque_Nm = " + std::to_string(*rated) + "; must be > 0");
        e.rated_torque_Nm = *rated;
      }
      const Branches br = find_branches(e.torque_Nm, 0.02 * range);
      e.direction = br.direction;
      e.since_reversal_Nm.resize(e.n);
      for (int i = 0; i < e.n; ++i) e.since_reversal_Nm[i] = std::abs(e.torque_Nm[i] - e.torque_Nm[br.branch_start[i]]);
      std::vector<double> amps;
      for (int r : br.reversals) amps.push_back(std::abs(e.torque_Nm[r]));
      if (amps.empty()) {
        e.torque_amplitude_Nm = e.torque_Nm.cwiseAbs().maxCoeff();
      } else {
        std::nth_element(amps.begin(), amps.begin() + amps.size() / 2, amps.end());
        e.torque_amplitude_Nm = amps[amps.size() / 2];
      }
      break;
    }
    case Kind::Transmission: {
      if (base.teeth_flexspline <= 0 || base.teeth_circular <= base.teeth_flexspline)
        throw InputError(rec.path + ": teeth z_f = " + std::to_string(base.teeth_flexspline) + ", z_c = " +
                         std::to_string(base.teeth_circular) +
                         "; the transmission baseline needs 0 < z_f < z_c (case [gear] or metadata teeth_*)");
      e.wg_angle_rad = to_vec(*rec.column("wg_angle_rad"));
      e.measured = to_vec(*rec.column("output_angle_rad"));
      const double ratio = double(base.teeth_circular - base.teeth_flexspline) / base.teeth_flexspline;
      e.baseline = -ratio * e.wg_angle_rad;
      e.output_angle_rad = e.baseline;
      e.response_name = "output_angle_rad";
      e.response_unit = "rad";
      break;
    }
    case Kind::Backlash: {
      if (!base.backlash_um)
        throw InputError(rec.path + ": kind = backlash; the basic kinematic backlash model is not available");
      e.wg_angle_rad = to_vec(*rec.column("wg_angle_deg")) * (M_PI / 180.0);
      e.torque_Nm = to_vec(*rec.column("torque_Nm"));
      e.measured = to_vec(*rec.column("backlash_um"));
      e.baseline.resize(e.n);
      for (int i = 0; i < e.n; ++i) e.baseline[i] = base.backlash_um(e.wg_angle_rad[i]);
      e.response_name = "backlash_um";
      e.response_unit = "um";
      break;
    }
    case Kind::Dynamics: {
      if (!base.dynamics_run)
        throw InputError(rec.path + ": kind = dynamics; the dynamics baseline (the case's [dynamics] model) is not "
                         "available");
      if (!e.has_time)
        throw InputError(rec.path + ": time_s missing; a dynamics recording needs time_s as its first column");
      e.measured = to_vec(*rec.column("mesh_force_N"));
      e.response_name = "mesh_force_N";
      e.response_unit = "N";
      const DynamicsRun b0 = base.dynamics_run(DynamicsVariation{});
      if (b0.time_s.size() < 2 || e.time.maxCoeff() > b0.time_s.back() * (1.0 + 1e-9) + 1e-12)
        throw InputError(rec.path + ": time_s reaches " + std::to_string(e.time.maxCoeff()) +
                         " s; the case's dynamics run covers only " +
                         std::to_string(b0.time_s.empty() ? 0.0 : b0.time_s.back()) +
                         " s (raise dynamics.duration_s)");
      e.baseline = resample(b0.time_s, b0.mesh_force_N, e.time);
      e.mesh_phase_rad = resample(b0.time_s, b0.mesh_phase_rad, e.time);
      // Wave-generator angle of the baseline (for plots in wave-generator orders).
      std::vector<double> wg_angle(b0.time_s.size(), 0.0);
      for (std::size_t i = 1; i < wg_angle.size(); ++i)
        wg_angle[i] = wg_angle[i - 1] + 0.5 * (b0.wg_speed_rpm[i] + b0.wg_speed_rpm[i - 1]) * (M_PI / 30.0) *
                                            (b0.time_s[i] - b0.time_s[i - 1]);
      e.wg_angle_rad = resample(b0.time_s, wg_angle, e.time);
      // Sensitivity basis from a few perturbed runs (the dynamics run is ~0.1 s).
      auto force = [&](const DynamicsVariation& v) { return resample(b0.time_s, base.dynamics_run(v).mesh_force_N, e.time); };
      e.sensitivity.resize(e.n, 5);
      // k(t) columns from a small one-sided step: the response bends with r (flanks lose and regain contact), and
      // a step of 0.1 folds that bend into the column (on moving pairs, a concealed r = 0.048 left 26 % of its signal
      // outside the columns of a 0.1 step, 7.7 % with 0.02; central differences at 0.05: 29 %).
      const double dk = 0.02;
      DynamicsVariation v;
      v.stiffness_ratio = dk;
      e.sensitivity.col(0) = (force(v) - e.baseline) / dk;
      v.stiffness_phase_rad = 0.5 * M_PI;
      e.sensitivity.col(1) = (force(v) - e.baseline) / dk;
      // Split into the part locked to the mesh (k(t) is periodic in the mesh phase, so is the steady response to it)
      // and the rest (the load step's ringing changed, contacts that open and close at other times), which may
      // answer r non-smoothly: r is read from the locked part alone (frozen seed gear: 51 % of an r = 0.05 response
      // lay outside the raw columns, and r read from them was half the truth).
      const Eigen::MatrixXd harmonics = mesh_harmonics(e, kMeshHarmonics);
      const auto harmonics_qr = harmonics.colPivHouseholderQr();
      e.stiffness_unlocked.resize(e.n, 2);
      for (int j = 0; j < 2; ++j) {
        const Eigen::VectorXd locked = harmonics * harmonics_qr.solve(Eigen::VectorXd(e.sensitivity.col(j)));
        e.stiffness_unlocked.col(j) = e.sensitivity.col(j) - locked;
        e.sensitivity.col(j) = locked;
      }
      const double c0 = base.damping_Ns_per_m;
      if (c0 > 0.0) {
        DynamicsVariation lo, hi;
        lo.damping_Ns_per_m = 0.5 * c0;
        hi.damping_Ns_per_m = 1.5 * c0;
        e.sensitivity.col(2) = (force(hi) - force(lo)) / c0;
      } else {
        DynamicsVariation hi;
        hi.damping_Ns_per_m = 1e3;
        e.sensitivity.col(2) = (force(hi) - e.baseline) / 1e3;
      }
      const double tc = std::max(0.05 * base.load_torque_Nm, 0.1);
      DynamicsVariation dc;
      dc.drag_coulomb_Nm = tc;
      e.sensitivity.col(3) = (force(dc) - e.baseline) / tc;
      const double bv = tc / std::max(base.output_speed_rad_s, 1e-6);
      DynamicsVariation dv;
      dv.drag_viscous_Nms_per_rad = bv;
      e.sensitivity.col(4) = (force(dv) - e.baseline) / bv;
      // Calibration of the nonlinear responses (the mesh responds to Δk and c far from linearly: flanks leave and
      // regain contact, the ringing after a load step decays at a rate set by c).
      const auto stiffness_qr = Eigen::MatrixXd(e.sensitivity.leftCols(2)).colPivHouseholderQr();
      e.calib_ratio = {0.0, 0.01, 0.03, 0.1, 0.3, 0.6, 0.9};
      e.calib_stiffness_beta = {0.0};
      for (std::size_t j = 1; j < e.calib_ratio.size(); ++j) {
        DynamicsVariation sv;
        sv.stiffness_ratio = e.calib_ratio[j];
        const Eigen::VectorXd b = stiffness_qr.solve(Eigen::VectorXd(force(sv) - e.baseline));
        e.calib_stiffness_beta.push_back(std::hypot(b[0], b[1]));
      }
      // The response to the damping coefficient on a geometric table (ratio 2^(1/4), c0/8 to 8 c0, and 0 when the
      // model has none): the fit reads c from it as a nonlinear parameter (damping_response_at).
      const double cref = c0 > 0.0 ? c0 : 1e3;
      if (c0 == 0.0) e.damping_table_Ns_per_m.push_back(0.0);
      for (int k = -kDampingTableSteps; k <= kDampingTableSteps; ++k)
        e.damping_table_Ns_per_m.push_back(cref * std::pow(2.0, k / 4.0));
      e.damping_response.resize(e.n, e.damping_table_Ns_per_m.size());
      for (std::size_t j = 0; j < e.damping_table_Ns_per_m.size(); ++j) {
        DynamicsVariation cv;
        cv.damping_Ns_per_m = e.damping_table_Ns_per_m[j];
        e.damping_response.col(j) = cv.damping_Ns_per_m == c0 ? Eigen::VectorXd::Zero(e.n)
                                                              : Eigen::VectorXd(force(cv) - e.baseline);
      }
      break;
    }
  }
  return e;
}

}  // namespace sw::reconcile
