#include "reconcile/laws.hpp"

#include <algorithm>
#include <cmath>

#include "common/error.hpp"

namespace sw::reconcile {

Eigen::MatrixXd harmonic_columns(const Eigen::VectorXd& angle_rad, int order) {
  Eigen::MatrixXd m(angle_rad.size(), 2);
  m.col(0) = (order * angle_rad.array()).cos();
  m.col(1) = (order * angle_rad.array()).sin();
  return m;
}

Eigen::VectorXd soft_start_column(const Eigen::VectorXd& torque_Nm, double t1_Nm) {
  return torque_Nm.cwiseMax(-t1_Nm).cwiseMin(t1_Nm);
}

double segment_law_twist(double T, double k1, double k2, double k3, double t1, double t2) {
  const double a = std::abs(T);
  const double phi = std::min(a, t1) / k1 + std::clamp(a - t1, 0.0, t2 - t1) / k2 + std::max(a - t2, 0.0) / k3;
  return T < 0 ? -phi : phi;
}

double rounded_segment_law_twist(double T, double k1, double k2, double k3, double t1, double t2, double width) {
  auto logcosh = [](double u) { return std::abs(u) + std::log1p(std::exp(-2.0 * std::abs(u))) - std::log(2.0); };
  auto step_integral = [&](double x, double tb) {
    if (!std::isfinite(tb)) return x;
    const double d = width * tb;
    return 0.5 * (x - d * logcosh((x - tb) / d) + d * logcosh(-tb / d));
  };
  const double x = std::abs(T);
  const double v = x / k3 + (1.0 / k2 - 1.0 / k3) * step_integral(x, t2) + (1.0 / k1 - 1.0 / k2) * step_integral(x, t1);
  return T < 0 ? -v : v;
}

Eigen::VectorXd hysteresis_column(const TorsionExperiment& t, double transition_Nm) {
  const int n = static_cast<int>(t.torque_Nm.size());
  Eigen::VectorXd c(n);
  for (int i = 0; i < n; ++i) c[i] = -t.direction[i] * (0.5 - std::exp(-t.since_reversal_Nm[i] / transition_Nm));
  return c;
}

Eigen::MatrixXd gap_profile_columns(const TorsionExperiment& t, int intervals) {
  const int n = static_cast<int>(t.torque_Nm.size());
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(n, intervals);
  for (int i = 0; i < n; ++i) {
    const double x = std::min(1.0, std::abs(t.torque_Nm[i]) / t.torque_amplitude_Nm) * intervals;
    const int k = std::min(static_cast<int>(x), intervals - 1);
    const double f = x - k;  // between knot k (weight 1 - f) and knot k + 1 (weight f; the last knot's gap is 0)
    m(i, k) = -0.5 * t.direction[i] * (1.0 - f);
    if (k + 1 < intervals) m(i, k + 1) = -0.5 * t.direction[i] * f;
  }
  return m;
}

double hysteresis_loss_rad(double h_rad, double transition_Nm, double amplitude_Nm) {
  return h_rad * (1.0 - 2.0 * std::exp(-amplitude_Nm / transition_Nm));
}

double hysteresis_middle_twist(double h, double th, double R, double T) {
  return 0.5 * h * (std::exp(-(T + R) / th) - std::exp(-(R - T) / th));
}

Eigen::VectorXd bouc_wen_column(const Eigen::VectorXd& torque_Nm, double th, double nexp) {
  const int n = static_cast<int>(torque_Nm.size());
  Eigen::VectorXd z(n);
  double zi = 0.0;
  for (int pass = 0; pass < 2; ++pass)
    for (int i = 0; i < n; ++i) {
      const double dT = (torque_Nm[i] - torque_Nm[i == 0 ? n - 1 : i - 1]) / 50.0;
      for (int k = 0; k < 50; ++k) {
        const double sg = dT * zi > 0 ? 1.0 : dT * zi < 0 ? -1.0 : 0.0;
        zi += dT / th * (1.0 - 0.5 * (sg + 1.0) * std::pow(std::abs(zi), nexp));
      }
      z[i] = zi;
    }
  const Eigen::VectorXd col = -0.5 * z;
  // Branch gap at zero torque, from the zero crossings (linear interpolation) after the first cycle.
  double up = 0, down = 0;
  int nu = 0, nd = 0;
  for (int i = n / 4; i + 1 < n; ++i) {
    const double a0 = torque_Nm[i], a1 = torque_Nm[i + 1];
    if ((a0 < 0) == (a1 < 0) || a0 == a1) continue;
    const double f = a0 / (a0 - a1), v = col[i] + f * (col[i + 1] - col[i]);
    if (a1 > a0) { up += v; ++nu; } else { down += v; ++nd; }
  }
  if (nu == 0 || nd == 0) throw InputError("synth effect friction_bouc_wen: the torque must cross zero both ways");
  return col / (down / nd - up / nu);
}

double lost_motion_twist(double torque_Nm, double transition_Nm) { return 0.5 * std::tanh(torque_Nm / transition_Nm); }

Eigen::VectorXd lost_motion_column(const Eigen::VectorXd& torque_Nm, double transition_Nm) {
  return 0.5 * (torque_Nm / transition_Nm).array().tanh();
}

Eigen::MatrixXd legendre_columns(const Eigen::VectorXd& time, int from, int to) {
  const double t0 = time.minCoeff(), t1 = time.maxCoeff();
  const Eigen::VectorXd x = ((time.array() - t0) / std::max(t1 - t0, 1e-300) * 2.0 - 1.0).matrix();
  Eigen::MatrixXd m(time.size(), to - from + 1);
  for (int p = from; p <= to; ++p) {
    Eigen::VectorXd v;
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

}  // namespace sw::reconcile
