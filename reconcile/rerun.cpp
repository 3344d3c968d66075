#include "reconcile/rerun.hpp"

#include <algorithm>
#include <cmath>

#include "common/error.hpp"

namespace sw::reconcile {

using Vec = Eigen::VectorXd;
using Mat = Eigen::MatrixXd;

namespace {

/// One iterate: the values, the model's response there, the linear part's coefficients and the whitened residual sum
/// of squares over the fitted rows.
struct Iterate {
  Vec values, response, linear_beta;
  double rss = INFINITY;
};

int fitted_rows(const RerunProblem& p) { return p.rows > 0 ? p.rows : p.e.n; }

/// The model at v with the linear part fitted by GLS over the rows.
Iterate at(const RerunProblem& p, const Vec& v, int& runs) {
  Iterate it;
  it.values = v;
  ++runs;
  it.response = p.response(v);
  const int rows = fitted_rows(p);
  const Vec z = whiten(p.ar, Vec((p.e.measured - it.response).head(rows)));
  if (p.linear.cols() == 0) {
    it.linear_beta = Vec(0);
    it.rss = z.squaredNorm();
    return it;
  }
  const LsResult ls = least_squares(whiten(p.ar, Mat(p.linear.topRows(rows))), z);
  it.linear_beta = ls.beta;
  it.rss = ls.rss;
  return it;
}

/// The values moved into the bounds: the model is never run outside them (a key may not even be valid there: a
/// negative tip rounding or damping).
Vec within_bounds(const RerunProblem& p, Vec v) { return v.cwiseMax(p.lo).cwiseMin(p.hi); }

/// d response / d value of each parameter at the iterate (n x k): central differences of +-step, one-sided (from the
/// iterate's own run) where a bound cuts one side off, or forward ones throughout when the problem asks.
Mat jacobian(const RerunProblem& p, const Iterate& it, int& runs) {
  Mat J(p.e.n, it.values.size());
  for (int i = 0; i < it.values.size(); ++i) {
    const double h = p.step(it.values, i), v = it.values[i];
    auto run = [&](double x) {
      Vec w = it.values;
      w[i] = x;
      ++runs;
      return Vec(p.response(w));
    };
    if (p.forward || v - h < p.lo[i]) J.col(i) = (run(v + h) - it.response) / h;
    else if (v + h > p.hi[i]) J.col(i) = (it.response - run(v - h)) / h;
    else J.col(i) = (run(v + h) - run(v - h)) / (2.0 * h);
  }
  return J;
}

/// A trial iterate; one where the model cannot be run is no improvement.
Iterate trial_at(const RerunProblem& p, const Vec& v, int& runs) {
  try {
    return at(p, v, runs);
  } catch (const InputError&) {
    Iterate failed;
    failed.values = v;
    return failed;
  }
}

}  // namespace

std::pair<Mat, Vec> projected_system(const RerunProblem& p, const Vec& response, const Mat& J) {
  const int rows = fitted_rows(p);
  const Mat Jw = whiten(p.ar, Mat(J.topRows(rows)));
  const Vec zw = whiten(p.ar, Vec((p.e.measured - response).head(rows)));
  if (p.linear.cols() == 0) return {Jw, zw};
  const Mat Lw = whiten(p.ar, Mat(p.linear.topRows(rows)));
  const auto qr = Lw.colPivHouseholderQr();
  const Mat Jp = Jw - Lw * qr.solve(Jw);
  const Vec zp = zw - Lw * qr.solve(zw);
  return {Jp, zp};
}

RerunFit refit_on_reruns(const RerunProblem& p, const Vec& start) {
  RerunFit out;
  Iterate cur = at(p, within_bounds(p, start), out.runs);
  out.start_response = cur.response;
  Mat J = jacobian(p, cur, out.runs);
  const int dof = std::max(1, static_cast<int>(fitted_rows(p) - p.linear.cols() - start.size()));
  double lambda = 1e-3;
  for (out.iterations = 0; out.iterations < p.max_iterations; ++out.iterations) {
    const auto [Jp, zp] = projected_system(p, cur.response, J);
    const Mat JtJ = Jp.transpose() * Jp;
    const Vec g = Jp.transpose() * zp;
    // A move is no move where it is below the stated fraction of every difference step and below a tenth of every
    // value's standard error (Wald's, at this iterate): the values have converged to well inside their intervals.
    const Vec sigma = (cur.rss / dof * Eigen::CompleteOrthogonalDecomposition<Mat>(JtJ).pseudoInverse().diagonal())
                          .cwiseMax(0.0)
                          .cwiseSqrt();
    const auto negligible = [&](const Vec& from, const Vec& to) {
      for (int i = 0; i < from.size(); ++i)
        if (std::abs(to[i] - from[i]) >= std::min(p.converged * p.step(from, i), 0.1 * sigma[i])) return false;
      return true;
    };
    bool improved = false, converged = false;
    for (int tries = 0; tries < 6 && !improved; ++tries, lambda *= 10.0) {
      Mat A = JtJ;
      A.diagonal() += lambda * JtJ.diagonal().cwiseMax(1e-300);
      Vec step = A.ldlt().solve(g);
      double scale = 1.0;
      for (int i = 0; i < step.size(); ++i)
        scale = std::min(scale, p.max_step_in_steps * p.step(cur.values, i) / std::max(std::abs(step[i]), 1e-300));
      step *= scale;
      // The move as run: projected into the bounds (a drag's part held at zero by its bound moves nowhere).
      const Vec to = within_bounds(p, cur.values + step);
      // Converged where the least-damped move is already negligible: no run is spent to confirm it.
      if (tries == 0 && negligible(cur.values, to)) break;
      const Iterate trial = trial_at(p, to, out.runs);
      if (trial.rss < cur.rss) {
        converged = negligible(cur.values, to);
        cur = trial;
        improved = true;
      }
    }
    if (!improved) break;
    lambda = std::max(lambda / 100.0, 1e-6);
    J = jacobian(p, cur, out.runs);
    if (converged) break;
  }
  out.values = cur.values;
  out.response = cur.response;
  out.linear_beta = cur.linear_beta;
  out.rss = cur.rss;
  out.jacobian = J;
  return out;
}

Vec rerun_half_widths(const RerunProblem& p, const RerunFit& f, const Mat& G, const SpectralCalibration& cal) {
  const auto [Jp, zp] = projected_system(p, f.response, f.jacobian);
  // In the values scaled to unit columns (x_s = D x, Jp x = (Jp D^-1) x_s, g^T x = (D^-1 g)^T x_s), so that a
  // direction counts as unseen by its share of the data's response, not by its units.
  const Vec norms = Jp.colwise().norm().transpose();
  const Vec inverse = norms.unaryExpr([](double n) { return n > 0.0 ? 1.0 / n : 1.0; });
  const Mat Js = Jp * inverse.asDiagonal();
  const Mat Gs = inverse.asDiagonal() * G;
  const Mat JtJ = Js.transpose() * Js;
  Eigen::CompleteOrthogonalDecomposition<Mat> cod(JtJ.rows(), JtJ.cols());
  cod.setThreshold(kUnseenDirection);  // before compute(): the decomposition's rank is fixed there
  cod.compute(JtJ);
  const Mat pinv = cod.pseudoInverse();
  const Mat influence = Js * (pinv * Gs);
  const Mat unseen = Gs - JtJ * (pinv * Gs);  // each g's part along directions the data do not see
  const int dof = std::max(1, static_cast<int>(zp.size() - p.linear.cols() - f.values.size()));
  Vec half(G.cols());
  for (int q = 0; q < G.cols(); ++q)
    half[q] = unseen.col(q).norm() > kUnseenShare * Gs.col(q).norm()
                  ? INFINITY
                  : cal.valid() && cal.n == Jp.rows()
                  ? calibrated_half_width_95(cal, Vec(influence.col(q)))
                  : 1.959964 * std::sqrt(std::max(f.rss / dof * influence.col(q).squaredNorm(), 0.0));
  return half;
}

std::pair<double, double> range_within_bounds(const Vec& lo, const Vec& hi, const Vec& values, double value,
                                              const Vec& g) {
  double down = value, up = value;
  for (int k = 0; k < g.size(); ++k) {
    if (g[k] == 0.0) continue;  // (an infinite side times a zero gradient is no change, not NaN)
    const double to_lo = g[k] * (lo[k] - values[k]), to_hi = g[k] * (hi[k] - values[k]);
    down += std::min(to_lo, to_hi);
    up += std::max(to_lo, to_hi);
  }
  return {down, up};
}

}  // namespace sw::reconcile
