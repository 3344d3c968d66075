#include "reconcile/catalog.hpp"

#include <algorithm>
#include <cmath>

#include "reconcile/fit.hpp"

namespace sw::reconcile {

Eigen::VectorXd soft_start_column(const Eigen::VectorXd& torque_Nm, double t1_Nm) {
  return torque_Nm.cwiseMax(-t1_Nm).cwiseMin(t1_Nm);
}

double segment_law_twist(double T, double k1, double k2, double k3, double t1, double t2) {
  const double a = std::abs(T);
  const double phi = std::min(a, t1) / k1 + std::clamp(a - t1, 0.0, t2 - t1) / k2 + std::max(a - t2, 0.0) / k3;
  return T < 0 ? -phi : phi;
}

Eigen::VectorXd hysteresis_column(const Experiment& e, double transition_Nm) {
  Eigen::VectorXd c(e.n);
  for (int i = 0; i < e.n; ++i)
    c[i] = -e.direction[i] * (0.5 - std::exp(-e.since_reversal_Nm[i] / transition_Nm));
  return c;
}

double hysteresis_loss_rad(double h_rad, double transition_Nm, double amplitude_Nm) {
  return h_rad * (1.0 - 2.0 * std::exp(-amplitude_Nm / transition_Nm));
}

Eigen::VectorXd lost_motion_column(const Eigen::VectorXd& torque_Nm, double transition_Nm) {
  return 0.5 * (torque_Nm / transition_Nm).array().tanh();
}

namespace {

using Vec = Eigen::VectorXd;
using Mat = Eigen::MatrixXd;

Mat col(const Vec& v) { return v; }
Mat none(const Experiment& e) { return Mat(e.n, 0); }
std::pair<Vec, Vec> no_bounds(const Experiment&) { return {Vec(0), Vec(0)}; }
std::pair<Vec, Vec> bounds1(double lo, double hi) { return {Vec::Constant(1, lo), Vec::Constant(1, hi)}; }

Mat harmonic(const Vec& angle, int order) {
  Mat m(angle.size(), 2);
  m.col(0) = (order * angle.array()).cos();
  m.col(1) = (order * angle.array()).sin();
  return m;
}

NamedValues harmonic_headline(const FitResult& f, int term, const std::string& unit) {
  const Vec& b = f.terms[term].beta;
  return {{"order", double(f.terms[term].spec->order)},
          {"amplitude_" + unit, std::hypot(b[0], b[1])},
          {"phase_rad", std::atan2(-b[1], b[0])}};
}

double added_series_compliance(const FitResult& f) {
  const int s = f.find("series_compliance");
  return s >= 0 ? f.terms[s].beta[0] : 0.0;
}

/// Normalised time in [-1, 1] and Legendre polynomials of it (drift basis).
Mat legendre(const Experiment& e, int from, int to) {
  const double t0 = e.time.minCoeff(), t1 = e.time.maxCoeff();
  const Vec x = ((e.time.array() - t0) / std::max(t1 - t0, 1e-300) * 2.0 - 1.0).matrix();
  Mat m(e.n, to - from + 1);
  for (int p = from; p <= to; ++p) {
    Vec v;
    switch (p) {
      case 1: v = x; break;
      case 2: v = (1.5 * x.array().square() - 0.5).matrix(); break;
      case 3: v = (2.5 * x.array().cube() - 1.5 * x.array()).matrix(); break;
      default: v = (4.375 * x.array().pow(4) - 3.75 * x.array().square() + 0.375).matrix(); break;
    }
    m.col(p - from) = v;
  }
  return m;
}

std::vector<EffectSpec> torsion_effects() {
  std::vector<EffectSpec> v;
  {
    EffectSpec s;
    s.name = "series_compliance";
    s.physics = "compliance in series with the flexspline body (tooth bending and contact, wave-generator bearing): "
                "the whole drive twists more per newton-metre than the flexspline alone";
    s.bounds = no_bounds;
    s.columns = [](const Experiment& e, const Vec&) { return col(e.torque_Nm); };
    s.headline = [](const Experiment&, const FitResult& f, int t) {
      return NamedValues{{"compliance_rad_per_Nm", f.terms[t].beta[0]}};
    };
    v.push_back(s);
  }
  for (int breakpoints : {1, 2}) {
    // The catalog's segment law: one breakpoint (K1 up to T1, then K2) or two (K1, K2, K3). K of the last segment
    // is 1 / (C_tau + the series compliance effect): the law is of the whole drive, the catalog's form.
    EffectSpec s;
    s.name = "stiffness_nonlinearity";
    s.order = breakpoints;
    s.exclusive_variants = true;
    s.n_linear = breakpoints;
    s.physics = breakpoints == 1
                    ? "soft start of the torque-twist curve (progressive tooth engagement): below T1 the drive is "
                      "softer (catalog segment law with two slopes, K1 up to T1, then K2)"
                    : "stiffness that grows with torque as more teeth engage: the catalog's three-segment law (K1 up "
                      "to T1, K2 up to T2, K3 beyond)";
    s.nonlinear_names = breakpoints == 1 ? std::vector<std::string>{"T1_Nm"} : std::vector<std::string>{"T1_Nm", "T2_Nm"};
    s.bounds = [breakpoints](const Experiment& e) {
      const double a = e.torque_amplitude_Nm;
      // Below 0.08 A a breakpoint is a jump at zero torque: play's signature, not a soft start.
      if (breakpoints == 1) return bounds1(0.08 * a, 0.7 * a);
      // The two breakpoints enter symmetrically (the headline sorts them), so they share one range. Above 0.8 A the
      // last segment is too short to tell K3 from series compliance.
      return std::make_pair(Vec(Vec::Constant(2, 0.08 * a)), Vec(Vec::Constant(2, 0.8 * a)));
    };
    s.columns = [](const Experiment& e, const Vec& th) {
      Mat m(e.n, th.size());
      for (int j = 0; j < th.size(); ++j) m.col(j) = soft_start_column(e.torque_Nm, th[j]);
      return m;
    };
    s.headline = [breakpoints](const Experiment& e, const FitResult& f, int t) {
      const double c_last = e.model.compliance_rad_per_Nm + added_series_compliance(f);
      const Vec& b = f.terms[t].beta;
      const Vec& th = f.terms[t].theta;
      if (breakpoints == 1)
        return NamedValues{{"K1_Nm_per_rad", 1.0 / (c_last + b[0])}, {"T1_Nm", th[0]}, {"K2_Nm_per_rad", 1.0 / c_last}};
      // The two breakpoints enter symmetrically: T1 is the lower one.
      const int lo = th[0] <= th[1] ? 0 : 1, hi = 1 - lo;
      const double c2 = c_last + b[hi];
      return NamedValues{{"K1_Nm_per_rad", 1.0 / (c2 + b[lo])}, {"T1_Nm", th[lo]}, {"K2_Nm_per_rad", 1.0 / c2},
                         {"T2_Nm", th[hi]}, {"K3_Nm_per_rad", 1.0 / c_last}};
    };
    v.push_back(s);
  }
  for (int elements : {1, 2}) {
    // Friction as one exponential (Dahl-type) branch transition, or two in parallel (a two-element slip model) when
    // the branches bend in a way one transition cannot follow (Bouc-Wen-like friction, several contact zones).
    EffectSpec s;
    s.name = "hysteresis";
    s.order = elements;
    s.exclusive_variants = true;
    s.n_linear = elements;
    s.physics = "friction in the tooth contacts: the loading branch lies below the unloading branch and the drive "
                "needs some torque after each reversal before it moves the other way";
    s.nonlinear_names = elements == 1 ? std::vector<std::string>{"transition_Nm"}
                                      : std::vector<std::string>{"transition_Nm", "transition2_Nm"};
    s.bounds = [elements](const Experiment& e) {
      return std::make_pair(Vec(Vec::Constant(elements, 0.005 * e.torque_amplitude_Nm)),
                            Vec(Vec::Constant(elements, 0.25 * e.torque_amplitude_Nm)));
    };
    s.columns = [](const Experiment& e, const Vec& th) {
      Mat m(e.n, th.size());
      for (int j = 0; j < th.size(); ++j) m.col(j) = hysteresis_column(e, th[j]);
      return m;
    };
    s.headline = [elements](const Experiment& e, const FitResult& f, int t) {
      const Vec& b = f.terms[t].beta;
      const Vec& th = f.terms[t].theta;
      double loss = 0.0;
      for (int j = 0; j < th.size(); ++j) loss += hysteresis_loss_rad(b[j], th[j], e.torque_amplitude_Nm);
      NamedValues v{{"loss_rad", loss}, {"loss_arcmin", loss * kArcminPerRad}};
      if (elements == 1) {
        v.emplace_back("transition_Nm", th[0]);
      } else {
        const int lo = th[0] <= th[1] ? 0 : 1;
        v.emplace_back("transition_Nm", th[lo]);
        v.emplace_back("transition2_Nm", th[1 - lo]);
      }
      return v;
    };
    v.push_back(s);
  }
  {
    EffectSpec s;
    s.name = "lost_motion";
    s.physics = "play between the teeth (or in the output coupling): the twist jumps while the torque crosses zero";
    s.nonlinear_names = {"transition_Nm"};
    s.bounds = [](const Experiment& e) {
      return bounds1(0.001 * e.torque_amplitude_Nm, 0.05 * e.torque_amplitude_Nm);
    };
    s.columns = [](const Experiment& e, const Vec& th) { return col(lost_motion_column(e.torque_Nm, th[0])); };
    s.headline = [](const Experiment&, const FitResult& f, int t) {
      return NamedValues{{"width_rad", f.terms[t].beta[0]}, {"width_arcmin", f.terms[t].beta[0] * kArcminPerRad},
                         {"transition_Nm", f.terms[t].theta[0]}};
    };
    v.push_back(s);
  }
  for (auto& s : v) s.kind = Kind::Torsion;
  return v;
}

std::vector<EffectSpec> transmission_effects() {
  std::vector<EffectSpec> v;
  for (int k = 1; k <= kMaxHarmonicOrder; ++k) {
    EffectSpec s;
    s.name = "wg_harmonic";
    s.order = k;
    s.physics = k == 1 ? "kinematic error locked to the wave generator, once per revolution: eccentricity"
                       : "kinematic error locked to the wave generator, order " + std::to_string(k) +
                             (k == 2 ? ": ovality of the generator or the circular spline" : "");
    s.n_linear = 2;
    s.multiplicity = kMaxHarmonicOrder;
    s.bounds = no_bounds;
    s.columns = [k](const Experiment& e, const Vec&) { return harmonic(e.wg_angle_rad, k); };
    s.headline = [](const Experiment&, const FitResult& f, int t) { return harmonic_headline(f, t, "rad"); };
    v.push_back(s);
  }
  for (int k = 1; k <= kMaxHarmonicOrder; ++k) {
    EffectSpec s;
    s.name = "output_harmonic";
    s.order = k;
    s.physics = "error locked to the flexspline/output, order " + std::to_string(k) +
                " per output revolution (runout, accumulated pitch error)";
    s.n_linear = 2;
    s.multiplicity = kMaxHarmonicOrder;
    s.bounds = no_bounds;
    s.columns = [k](const Experiment& e, const Vec&) { return harmonic(e.output_angle_rad, k); };
    s.headline = [](const Experiment&, const FitResult& f, int t) { return harmonic_headline(f, t, "rad"); };
    v.push_back(s);
  }
  for (auto& s : v) s.kind = Kind::Transmission;
  return v;
}

std::vector<EffectSpec> backlash_effects() {
  std::vector<EffectSpec> v;
  {
    EffectSpec s;
    s.name = "load_torsion";
    s.physics = "the flexspline's torsional rotation under load (phi0 = C_tau * T) closes the clearance on the "
                "loaded flanks; the basic kinematic model assumes phi0 = 0";
    s.bounds = no_bounds;
    s.columns = [](const Experiment& e, const Vec&) {
      return col(-e.model.pitch_radius_m * 1e6 * e.torque_Nm);  // um per (rad/Nm)
    };
    s.headline = [](const Experiment&, const FitResult& f, int t) {
      return NamedValues{{"compliance_rad_per_Nm", f.terms[t].beta[0]}};
    };
    v.push_back(s);
  }
  for (int k = 1; k <= kMaxHarmonicOrder; ++k) {
    EffectSpec s;
    s.name = "wg_harmonic";
    s.order = k;
    s.physics = "clearance modulated with the wave-generator angle, order " + std::to_string(k) +
                (k == 1 ? " (eccentric assembly)" : k == 2 ? " (ovality of generator or circular spline)" : "");
    s.n_linear = 2;
    s.multiplicity = kMaxHarmonicOrder;
    s.bounds = no_bounds;
    s.columns = [k](const Experiment& e, const Vec&) { return harmonic(e.wg_angle_rad, k); };
    s.headline = [](const Experiment&, const FitResult& f, int t) { return harmonic_headline(f, t, "um"); };
    v.push_back(s);
  }
  {
    EffectSpec s;
    s.name = "uniform_clearance";
    s.physics = "a clearance change everywhere (tooth thickness, centre distance, thermal growth)";
    s.bounds = no_bounds;
    s.columns = [](const Experiment& e, const Vec&) { return col(Vec::Ones(e.n)); };
    s.headline = [](const Experiment&, const FitResult& f, int t) {
      return NamedValues{{"offset_um", f.terms[t].beta[0]}};
    };
    v.push_back(s);
  }
  for (auto& s : v) s.kind = Kind::Backlash;
  return v;
}

std::vector<EffectSpec> dynamics_effects() {
  std::vector<EffectSpec> v;
  {
    EffectSpec s;
    s.name = "mesh_stiffness_variation";
    s.physics = "mesh stiffness that varies as teeth engage and disengage: k(t) = k0 (1 + r sin(2 pi f_m t + phi)), "
                "a line at the mesh frequency f_m = z_f |n_f - n_w| / 60 in the meshing force";
    // The responses to r sin(psi) and r cos(psi) (the sensitivity columns at phase 0 and pi/2; k(t) is linear in
    // r cos(phi) and r sin(phi)), whole waveforms: on moving pairs the mesh has its own f_m content, so the
    // variation's response is not a pair of lines and its f_m line depends on phi. r from the coefficients' magnitude
    // through the calibration curve of runs at a few r (the response is far from linear in r on frozen pairs).
    // The columns' parts not locked to the mesh come with coefficients of their own (they carry the response's
    // transient part, not r).
    s.n_linear = 4;
    s.bounds = no_bounds;
    s.columns = [](const Experiment& e, const Vec&) {
      Mat m(e.n, 4);
      m << e.sensitivity.leftCols(2), e.stiffness_unlocked;
      return m;
    };
    s.headline = [](const Experiment& e, const FitResult& f, int t) {
      const Vec& b = f.terms[t].beta;
      const Vec contribution = e.sensitivity.leftCols(2) * b.head(2);
      const Vec line = mesh_lines(e).colPivHouseholderQr().solve(contribution);
      return NamedValues{{"amplitude_ratio", invert_calibration(e.calib_ratio, e.calib_stiffness_beta, 0.01,
                                                                std::hypot(b[0], b[1]))},
                         {"frequency_Hz", e.model.mesh_frequency_Hz},
                         {"line_amplitude_N", std::hypot(line[0], line[1])},
                         {"phase_rad", std::atan2(b[1], b[0])}};
    };
    v.push_back(s);
  }
  {
    EffectSpec s;
    s.name = "damping";
    s.physics = "contact damping other than the model's: the meshing-force fluctuations (the ringing after the run-up "
                "and load steps; with moving pairs also each tooth's entry into the mesh) are damped at another rate";
    // The column is the model's own response to a change of c from c0 to theta, per unit change (the secant of the
    // response, from the table of runs), and its coefficient is the change: added = beta, c = c0 + beta. The damping
    // sets the decay rate of the ringing after a step, so a large change alters the response's shape and theta finds
    // the shape (beta = theta - c0 when the model is right); a small one only scales it, and then beta alone is
    // determined, whatever theta. The one linear column at c0 mapped through a calibration curve that stood here
    // before left 45 % of a c = 2 c0 response unexplained and read c 25 % low (frozen seed gear).
    s.nonlinear_names = {"secant_to_Ns_per_m"};
    s.bounds = [](const Experiment& e) {
      const auto& c = e.damping_table_Ns_per_m;
      return c.empty() ? bounds1(0.0, 1.0) : bounds1(c.front(), c.back());
    };
    s.columns = [](const Experiment& e, const Vec& th) { return Mat(damping_secant(e, th[0])); };
    s.headline = [](const Experiment& e, const FitResult& f, int t) {
      const double c0 = e.model.damping_Ns_per_m, added = f.terms[t].beta[0];
      return NamedValues{{"coefficient_Ns_per_m", c0 + added}, {"added_Ns_per_m", added}};
    };
    v.push_back(s);
  }
  {
    EffectSpec s;
    s.name = "drag_torque";
    s.physics = "friction drag in bearings and teeth (Coulomb + viscous) on the output: the mesh carries more torque "
                "than the load, by an amount that grows with speed";
    s.n_linear = 2;
    s.bounds = no_bounds;
    s.columns = [](const Experiment& e, const Vec&) { return Mat(e.sensitivity.rightCols(2)); };
    s.headline = [](const Experiment& e, const FitResult& f, int t) {
      const Vec& b = f.terms[t].beta;
      return NamedValues{{"coulomb_Nm", b[0]},
                         {"viscous_Nms_per_rad", b[1]},
                         {"torque_at_speed_Nm", b[0] + b[1] * e.model.output_speed_rad_s}};
    };
    v.push_back(s);
  }
  for (auto& s : v) s.kind = Kind::Dynamics;
  return v;
}

std::vector<SignatureSpec> dynamics_signatures() {
  std::vector<SignatureSpec> v;
  auto time = [](const Experiment& e) { return e.time; };
  {
    SignatureSpec s;
    s.name = "mesh_frequency_lines";
    s.domain = "frequency";
    s.what = "a line at the mesh frequency f_m and its second harmonic in the meshing-force spectrum";
    s.basis = [](const Experiment& e) { return mesh_lines(e); };
    s.condition = none;
    s.triggers = {"mesh_stiffness_variation"};
    s.where = time;
    s.where_unit = "s";
    v.push_back(s);
  }
  {
    SignatureSpec s;
    s.name = "fluctuation_decay";
    s.domain = "time";
    s.what = "the meshing-force fluctuations after the run-up and load steps decay at another rate or amplitude";
    s.basis = [](const Experiment& e) { return Mat(e.sensitivity.col(2)); };
    s.condition = none;
    s.triggers = {"damping"};
    s.where = time;
    s.where_unit = "s";
    v.push_back(s);
  }
  {
    SignatureSpec s;
    s.name = "speed_dependent_offset";
    s.domain = "time (speed)";
    s.what = "a meshing-force offset that grows with speed (the mesh carries a drag torque besides the load)";
    s.basis = [](const Experiment& e) { return Mat(e.sensitivity.rightCols(2)); };
    s.condition = none;
    s.triggers = {"drag_torque"};
    s.where = time;
    s.where_unit = "s";
    v.push_back(s);
  }
  return v;
}

std::vector<SignatureSpec> torsion_signatures() {
  std::vector<SignatureSpec> v;
  auto torque = [](const Experiment& e) { return e.torque_Nm; };
  auto linear = [](const Experiment& e) { return col(e.torque_Nm); };
  {
    SignatureSpec s;
    s.name = "torque_linear";
    s.domain = "torque";
    s.what = "residual proportional to torque (the drive is softer or stiffer than the baseline)";
    s.basis = linear;
    s.condition = none;
    s.triggers = {"series_compliance", "stiffness_nonlinearity#1", "stiffness_nonlinearity#2"};
    s.where = torque;
    s.where_unit = "N*m";
    v.push_back(s);
  }
  {
    SignatureSpec s;
    s.name = "torque_shape";
    s.domain = "torque";
    s.what = "residual bends with torque beyond a straight line (soft start or play)";
    s.basis = [](const Experiment& e) {
      Mat m(e.n, 3);
      const double a = e.torque_amplitude_Nm;
      m.col(0) = soft_start_column(e.torque_Nm, 0.15 * a);
      m.col(1) = soft_start_column(e.torque_Nm, 0.3 * a);
      m.col(2) = soft_start_column(e.torque_Nm, 0.5 * a);
      return m;
    };
    s.condition = linear;
    s.triggers = {"stiffness_nonlinearity#1", "stiffness_nonlinearity#2", "lost_motion"};
    s.where = torque;
    s.where_unit = "N*m";
    v.push_back(s);
  }
  {
    SignatureSpec s;
    s.name = "loading_unloading";
    s.domain = "torque branch";
    s.what = "loading and unloading branches apart at equal torque";
    s.basis = [](const Experiment& e) {
      Mat m(e.n, 2);
      m.col(0) = e.direction;
      m.col(1) = hysteresis_column(e, 0.1 * e.torque_amplitude_Nm);
      return m;
    };
    s.condition = linear;
    s.triggers = {"hysteresis#1", "hysteresis#2"};
    s.where = torque;
    s.where_unit = "N*m";
    v.push_back(s);
  }
  {
    SignatureSpec s;
    s.name = "zero_crossing";
    s.domain = "torque zero crossing";
    s.what = "twist jumps while the torque crosses zero";
    s.basis = [](const Experiment& e) { return col(lost_motion_column(e.torque_Nm, 0.01 * e.torque_amplitude_Nm)); };
    s.condition = linear;
    s.triggers = {"lost_motion", "stiffness_nonlinearity#1", "stiffness_nonlinearity#2"};
    s.where = torque;
    s.where_unit = "N*m";
    v.push_back(s);
  }
  {
    SignatureSpec s;
    s.name = "time_drift";
    s.domain = "time";
    s.what = "slow drift of the residual in time (temperature, creep, sensor drift): no catalog effect";
    s.basis = [](const Experiment& e) { return legendre(e, 1, 2); };
    s.condition = none;
    s.where = [](const Experiment& e) { return e.time; };
    s.where_unit = "s";
    v.push_back(s);
  }
  return v;
}

std::vector<SignatureSpec> angle_order_signatures(const std::string& prefix, const std::string& domain,
                                                  const std::string& effect, bool output) {
  std::vector<SignatureSpec> v;
  for (int k = 1; k <= kMaxHarmonicOrder; ++k) {
    SignatureSpec s;
    s.name = prefix + "_order_" + std::to_string(k);
    s.domain = domain;
    s.what = "order " + std::to_string(k) + " line in the residual's " + domain + " spectrum";
    s.basis = [k, output](const Experiment& e) { return harmonic(output ? e.output_angle_rad : e.wg_angle_rad, k); };
    s.condition = none;
    s.triggers = {effect + "#" + std::to_string(k)};
    s.where = [output](const Experiment& e) {
      return Vec(((output ? e.output_angle_rad : e.wg_angle_rad) * (180.0 / M_PI)).array());
    };
    s.where_unit = "deg";
    s.periodic = true;
    v.push_back(s);
  }
  return v;
}

std::vector<SignatureSpec> transmission_signatures() {
  auto v = angle_order_signatures("wg", "wave-generator angle", "wg_harmonic", false);
  auto o = angle_order_signatures("output", "output angle", "output_harmonic", true);
  v.insert(v.end(), o.begin(), o.end());
  SignatureSpec s;
  s.name = "time_drift";
  s.domain = "time";
  s.what = "slow drift of the transmission error in time beyond a constant ratio error: no catalog effect";
  s.basis = [](const Experiment& e) { return legendre(e, 2, 3); };
  s.condition = none;
  s.where = [](const Experiment& e) { return e.time; };
  s.where_unit = "s";
  v.push_back(s);
  return v;
}

std::vector<SignatureSpec> backlash_signatures() {
  auto v = angle_order_signatures("wg", "wave-generator angle", "wg_harmonic", false);
  {
    SignatureSpec s;
    s.name = "torque_dependence";
    s.domain = "torque";
    s.what = "backlash changes with the applied torque";
    s.basis = [](const Experiment& e) { return col(e.torque_Nm); };
    s.condition = [](const Experiment& e) { return col(Vec::Ones(e.n)); };
    s.triggers = {"load_torsion"};
    s.where = [](const Experiment& e) { return e.torque_Nm; };
    s.where_unit = "N*m";
    v.push_back(s);
  }
  {
    SignatureSpec s;
    s.name = "mean_offset";
    s.domain = "all positions";
    s.what = "backlash offset from the basic model at every position";
    s.basis = [](const Experiment& e) { return col(Vec::Ones(e.n)); };
    s.condition = none;
    s.triggers = {"uniform_clearance", "load_torsion"};
    s.where = [](const Experiment& e) { return Vec(e.wg_angle_rad * (180.0 / M_PI)); };
    s.where_unit = "deg";
    s.periodic = true;
    v.push_back(s);
  }
  return v;
}

}  // namespace

const std::vector<EffectSpec>& effect_catalog(Kind kind) {
  static const std::vector<EffectSpec> torsion = torsion_effects();
  static const std::vector<EffectSpec> transmission = transmission_effects();
  static const std::vector<EffectSpec> backlash = backlash_effects();
  static const std::vector<EffectSpec> dynamics = dynamics_effects();
  static const std::vector<EffectSpec> empty;
  switch (kind) {
    case Kind::Torsion: return torsion;
    case Kind::Transmission: return transmission;
    case Kind::Backlash: return backlash;
    case Kind::Dynamics: return dynamics;
    default: return empty;
  }
}

const std::vector<SignatureSpec>& signature_catalog(Kind kind) {
  static const std::vector<SignatureSpec> torsion = torsion_signatures();
  static const std::vector<SignatureSpec> transmission = transmission_signatures();
  static const std::vector<SignatureSpec> backlash = backlash_signatures();
  static const std::vector<SignatureSpec> dynamics = dynamics_signatures();
  static const std::vector<SignatureSpec> empty;
  switch (kind) {
    case Kind::Torsion: return torsion;
    case Kind::Transmission: return transmission;
    case Kind::Backlash: return backlash;
    case Kind::Dynamics: return dynamics;
    default: return empty;
  }
}

Eigen::MatrixXd nuisance_columns(const Experiment& e) {
  switch (e.kind) {
    case Kind::Torsion: return Eigen::MatrixXd::Ones(e.n, 1);
    case Kind::Transmission: {
      Eigen::MatrixXd m(e.n, 2);
      m.col(0).setOnes();
      m.col(1) = e.wg_angle_rad;
      return m;
    }
    default: return Eigen::MatrixXd(e.n, 0);
  }
}

}  // namespace sw::reconcile

namespace sw::reconcile {

const CatalogDrive* catalog_stiffness(int size) {
  const CatalogDrive* d = catalog_drive(size);
  return d && d->has_stiffness() ? d : nullptr;
}

CatalogFigures catalog_figures(const Experiment& e, const FitResult& f) {
  CatalogFigures c;
  if (e.kind != Kind::Torsion) return c;
  c.valid = true;
  c.reference = catalog_stiffness(e.drive_size);
  if (e.rated_torque_Nm > 0.0) {
    c.rated_torque_Nm = e.rated_torque_Nm;
    c.rated_from = "metadata rated_torque_Nm";
  } else if (c.reference) {
    c.rated_torque_Nm = c.reference->rated_torque_Nm;
    c.rated_from = "catalog size " + std::to_string(c.reference->size);
  } else {
    c.rated_torque_Nm = e.torque_amplitude_Nm;
    c.rated_from = "the recording's torque amplitude (no rated torque in the metadata)";
  }
  const double R = c.rated_torque_Nm;
  const double c_series = added_series_compliance(f);
  const double c_last = e.model.compliance_rad_per_Nm + c_series;
  c.k1 = c.k2 = c.k3 = 1.0 / c_last;
  // The middle line of the loop after cycling to +-R: everything but the branch-dependent part of hysteresis. A
  // curve baseline (the contact stage's) is its own middle line.
  std::function<double(double)> mid = [c_last](double T) { return c_last * T; };
  if (e.model.twist_rad)
    mid = [curve = e.model.twist_rad, c_series](double T) { return curve(T) + c_series * T; };
  bool stiffness_effect = false;
  for (std::size_t i = 0; i < f.terms.size(); ++i) {
    const Term& t = f.terms[i];
    const std::string& name = t.spec->name;
    if (name == "stiffness_nonlinearity") {
      stiffness_effect = true;
      const NamedValues h = t.spec->headline(e, f, static_cast<int>(i));
      c.segments = t.spec->order + 1;
      c.k1 = h[0].second;
      c.t1 = h[1].second;
      c.k2 = h[2].second;
      if (c.segments == 3) c.t2 = h[3].second;
      mid = [mid, b = t.beta, th = t.theta](double T) {
        double v = mid(T);
        for (int j = 0; j < th.size(); ++j) v += b[j] * std::clamp(T, -th[j], th[j]);
        return v;
      };
    } else if (name == "hysteresis") {
      for (int j = 0; j < t.theta.size(); ++j) {
        const double h = t.beta[j], th = t.theta[j];
        c.hysteresis_loss_arcmin += hysteresis_loss_rad(h, th, R) * kArcminPerRad;
        mid = [mid, h, th, R](double T) {
          return mid(T) + 0.5 * h * (std::exp(-(T + R) / th) - std::exp(-(R - T) / th));
        };
      }
    } else if (name == "lost_motion") {
      const double w = t.beta[0], ts = t.theta[0];
      c.play_arcmin = w * kArcminPerRad;
      mid = [mid, w, ts](double T) { return mid(T) + 0.5 * w * std::tanh(T / ts); };
    }
  }
  c.catalog_lost_motion_arcmin = (mid(0.04 * R) - mid(-0.04 * R)) * kArcminPerRad;
  const double t1 = e.model.curve_t1_Nm, t2 = e.model.curve_t2_Nm, top = e.torque_amplitude_Nm;
  if (e.model.twist_rad && !stiffness_effect && t1 > 0.0 && t2 > t1 && top > t2) {
    // The curve's own three segments (with the series compliance, if named) as segment secants, as catalogs read
    // them: K1 over 0..T1, K2 over T1..T2, K3 over T2 to the top of the recorded range. Friction and play are not
    // stiffness: they stay out, as they stay out of the stiffness effect's slopes.
    auto twist = [&](double T) { return 0.5 * (e.model.twist_rad(T) - e.model.twist_rad(-T)) + c_series * T; };
    c.segments = 3;
    c.t1 = t1;
    c.t2 = t2;
    c.k1 = t1 / twist(t1);
    c.k2 = (t2 - t1) / (twist(t2) - twist(t1));
    c.k3 = (top - t2) / (twist(top) - twist(t2));
  }
  return c;
}

}  // namespace sw::reconcile
