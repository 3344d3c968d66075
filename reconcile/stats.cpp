#include "reconcile/stats.hpp"

#include <cassert>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace sw::reconcile {

ArModel fit_ar(const Eigen::VectorXd& x_in, int max_order) {
  const int n = static_cast<int>(x_in.size());
  assert(n > 4 * max_order);
  const Eigen::VectorXd x = x_in.array() - x_in.mean();
  std::vector<double> r(max_order + 1, 0.0);
  for (int k = 0; k <= max_order; ++k) r[k] = x.head(n - k).dot(x.tail(n - k)) / n;
  ArModel best;
  best.process_sd = std::sqrt(r[0]);
  best.innovation_sd = std::sqrt(r[0]);
  if (r[0] <= 0.0) return best;
  double best_bic = n * std::log(r[0]);
  // Levinson-Durbin recursion.
  std::vector<double> a;
  double err = r[0];
  for (int p = 1; p <= max_order; ++p) {
    double acc = r[p];
    for (int j = 0; j < p - 1; ++j) acc -= a[j] * r[p - 1 - j];
    const double k = acc / err;
    std::vector<double> next(p);
    for (int j = 0; j < p - 1; ++j) next[j] = a[j] - k * a[p - 2 - j];
    next[p - 1] = k;
    a = next;
    err *= (1.0 - k * k);
    if (err <= 0.0) break;
    // AIC rather than BIC: a richer AR fits the noise spectrum's shape better at high frequencies, where harmonic
    // tests would otherwise be anti-conservative.
    const double bic = n * std::log(err) + 2.0 * p;
    if (bic < best_bic) {
      best_bic = bic;
      best.a = a;
      best.innovation_sd = std::sqrt(err);
    }
  }
  return best;
}

Eigen::VectorXd whiten(const ArModel& ar, const Eigen::VectorXd& x) {
  const int p = ar.order();
  const int n = static_cast<int>(x.size());
  Eigen::VectorXd out(std::max(0, n - p));
  for (int t = p; t < n; ++t) {
    double v = x[t];
    for (int k = 0; k < p; ++k) v -= ar.a[k] * x[t - 1 - k];
    out[t - p] = v;
  }
  return out;
}

Eigen::MatrixXd whiten(const ArModel& ar, const Eigen::MatrixXd& X) {
  const int p = ar.order();
  const int n = static_cast<int>(X.rows());
  Eigen::MatrixXd out(std::max(0, n - p), X.cols());
  out = X.bottomRows(std::max(0, n - p));
  for (int k = 0; k < p; ++k) out -= ar.a[k] * X.middleRows(p - 1 - k, n - p);
  return out;
}

Eigen::VectorXd simulate_ar(const ArModel& ar, int n, std::mt19937_64& rng) {
  std::normal_distribution<double> normal(0.0, ar.innovation_sd);
  const int p = ar.order();
  const int burn = 200 + 20 * p;
  std::vector<double> x(n + burn, 0.0);
  for (int t = 0; t < n + burn; ++t) {
    double v = normal(rng);
    for (int k = 0; k < p && t - 1 - k >= 0; ++k) v += ar.a[k] * x[t - 1 - k];
    x[t] = v;
  }
  return Eigen::Map<Eigen::VectorXd>(x.data() + burn, n);
}

namespace {
// Continued fraction for the incomplete beta (modified Lentz).
double beta_cf(double a, double b, double x) {
  const double tiny = 1e-300;
  double c = 1.0, d = 1.0 - (a + b) * x / (a + 1.0);
  if (std::abs(d) < tiny) d = tiny;
  d = 1.0 / d;
  double h = d;
  for (int m = 1; m <= 500; ++m) {
    const double m2 = 2.0 * m;
    double aa = m * (b - m) * x / ((a + m2 - 1.0) * (a + m2));
    d = 1.0 + aa * d;
    if (std::abs(d) < tiny) d = tiny;
    c = 1.0 + aa / c;
    if (std::abs(c) < tiny) c = tiny;
    d = 1.0 / d;
    h *= d * c;
    aa = -(a + m) * (a + b + m) * x / ((a + m2) * (a + m2 + 1.0));
    d = 1.0 + aa * d;
    if (std::abs(d) < tiny) d = tiny;
    c = 1.0 + aa / c;
    if (std::abs(c) < tiny) c = tiny;
    d = 1.0 / d;
    const double del = d * c;
    h *= del;
    if (std::abs(del - 1.0) < 1e-15) break;
  }
  return h;
}
}  // namespace

double incomplete_beta(double a, double b, double x) {
  if (x <= 0.0) return 0.0;
  if (x >= 1.0) return 1.0;
  const double lbt = std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) + a * std::log(x) + b * std::log1p(-x);
  if (x < (a + 1.0) / (a + b + 2.0)) return std::exp(lbt) * beta_cf(a, b, x) / a;
  return 1.0 - std::exp(lbt) * beta_cf(b, a, 1.0 - x) / b;
}

double f_upper_tail(double f, double d1, double d2) {
  if (!(f > 0.0)) return 1.0;
  return incomplete_beta(0.5 * d2, 0.5 * d1, d2 / (d2 + d1 * f));
}

LsResult least_squares(const Eigen::MatrixXd& X, const Eigen::VectorXd& y) {
  LsResult out;
  if (X.cols() == 0) {
    out.beta = Eigen::VectorXd(0);
    out.residual = y;
    out.rss = y.squaredNorm();
    return out;
  }
  if (X.rows() == 0 || !X.allFinite() || !y.allFinite())
    throw std::runtime_error("least_squares: " + std::to_string(X.rows()) + "x" + std::to_string(X.cols()) +
                             " system with non-finite entries or no rows");
  // Scale columns so the rank threshold is meaningful across units.
  Eigen::VectorXd scale = X.colwise().norm().transpose();
  for (int j = 0; j < scale.size(); ++j)
    if (!(scale[j] > 0.0)) scale[j] = 1.0;
  const Eigen::MatrixXd Xs = X * scale.cwiseInverse().asDiagonal();
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(Xs);
  qr.setThreshold(1e-9);
  out.rank = static_cast<int>(qr.rank());
  out.beta = qr.solve(y).cwiseQuotient(scale);
  out.residual = y - X * out.beta;
  out.rss = out.residual.squaredNorm();
  return out;
}

Eigen::MatrixXd hcat(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  if (a.cols() == 0) return b;
  if (b.cols() == 0) return a;
  Eigen::MatrixXd out(a.rows(), a.cols() + b.cols());
  out << a, b;
  return out;
}

FTest f_test(const Eigen::MatrixXd& base, const Eigen::MatrixXd& extra, const Eigen::VectorXd& y) {
  FTest t;
  const LsResult r0 = least_squares(base, y);
  const LsResult r1 = least_squares(hcat(base, extra), y);
  t.rss_base = r0.rss;
  t.rss_full = r1.rss;
  t.df_extra = r1.rank - r0.rank;
  t.df_resid = static_cast<int>(y.size()) - r1.rank;
  if (t.df_extra <= 0 || t.df_resid <= 0 || !(r1.rss > 0.0)) return t;
  t.f = std::max(0.0, (r0.rss - r1.rss) / t.df_extra) / (r1.rss / t.df_resid);
  t.p_value = f_upper_tail(t.f, t.df_extra, t.df_resid);
  return t;
}

}  // namespace sw::reconcile
