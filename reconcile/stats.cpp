#include "reconcile/stats.hpp"

#include <cassert>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <fftw3.h>

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

namespace {

/// The residual sums of squares without and with the extra columns, and the extra columns' degrees of freedom; the
/// full model's rank in `rank_full`.
FTest nested_fits(const Eigen::MatrixXd& base, const Eigen::MatrixXd& extra, const Eigen::VectorXd& y,
                  int& rank_full) {
  FTest t;
  const LsResult r0 = least_squares(base, y);
  const LsResult r1 = least_squares(hcat(base, extra), y);
  t.rss_base = r0.rss;
  t.rss_full = r1.rss;
  t.df_extra = r1.rank - r0.rank;
  rank_full = r1.rank;
  return t;
}

}  // namespace

FTest f_test(const Eigen::MatrixXd& base, const Eigen::MatrixXd& extra, const Eigen::VectorXd& y) {
  int rank_full = 0;
  FTest t = nested_fits(base, extra, y, rank_full);
  t.df_resid = static_cast<int>(y.size()) - rank_full;
  if (t.df_extra <= 0 || t.df_resid <= 0 || !(t.rss_full > 0.0)) return t;
  t.f = std::max(0.0, (t.rss_base - t.rss_full) / t.df_extra) / (t.rss_full / t.df_resid);
  t.p_value = f_upper_tail(t.f, t.df_extra, t.df_resid);
  return t;
}

namespace {

/// |U x|^2 over the full circle, U the unitary DFT (sums to ||x||^2).
Eigen::VectorXd power_spectrum(const Eigen::VectorXd& x) {
  const int n = static_cast<int>(x.size());
  const int nc = n / 2 + 1;
  std::vector<double> in(x.data(), x.data() + n);
  fftw_complex* c = fftw_alloc_complex(nc);
  fftw_plan plan = fftw_plan_dft_r2c_1d(n, in.data(), c, FFTW_ESTIMATE);
  fftw_execute(plan);
  Eigen::VectorXd p(n);
  for (int j = 0; j < nc; ++j) {
    const double v = (c[j][0] * c[j][0] + c[j][1] * c[j][1]) / n;
    p[j] = v;
    if (j > 0 && n - j >= nc) p[n - j] = v;
  }
  fftw_destroy_plan(plan);
  fftw_free(c);
  return p;
}

/// Orthonormal basis of the column space of X (rank-revealing), n x rank.
Eigen::MatrixXd orthonormal_basis(const Eigen::MatrixXd& X) {
  if (X.cols() == 0) return Eigen::MatrixXd(X.rows(), 0);
  Eigen::VectorXd scale = X.colwise().norm().transpose();
  for (int j = 0; j < scale.size(); ++j)
    if (!(scale[j] > 0.0)) scale[j] = 1.0;
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(X * scale.cwiseInverse().asDiagonal());
  qr.setThreshold(1e-9);
  const int r = static_cast<int>(qr.rank());
  Eigen::MatrixXd q = qr.householderQ() * Eigen::MatrixXd::Identity(X.rows(), r);
  return q;
}

/// Circular moving sum over +-h of v.
Eigen::VectorXd circular_moving_sum(const Eigen::VectorXd& v, int h) {
  const int n = static_cast<int>(v.size());
  Eigen::VectorXd out(n);
  double acc = 0.0;
  for (int k = -h; k <= h; ++k) acc += v[((k % n) + n) % n];
  for (int j = 0; j < n; ++j) {
    out[j] = acc;
    acc += v[(j + h + 1) % n] - v[((j - h) % n + n) % n];
  }
  return out;
}

}  // namespace

SpectralCalibration spectral_calibration(const Eigen::MatrixXd& rich_w, const Eigen::VectorXd& resid_w,
                                         int half_width) {
  SpectralCalibration cal;
  const int n = static_cast<int>(resid_w.size());
  if (n < 4 * (2 * half_width + 1)) return cal;  // too short to smooth: no calibration (plain F-test)
  cal.n = n;
  cal.half_width = half_width;
  cal.periodogram = power_spectrum(resid_w);
  cal.leverage = Eigen::VectorXd::Zero(n);
  const Eigen::MatrixXd q = orthonormal_basis(rich_w);
  for (int c = 0; c < q.cols(); ++c) cal.leverage += power_spectrum(q.col(c));
  return cal;
}

CalibratedLevel calibrated_level(const SpectralCalibration& cal, const Eigen::VectorXd& w) {
  const int n = cal.n;
  // Smoothed level s_j = sum_band I / sum_band (1 - h); estimate sum_j w_j s_j = sum_i c_i I_i.
  const Eigen::VectorXd free_dims = (1.0 - cal.leverage.array()).max(0.0).matrix();
  const Eigen::VectorXd denom = circular_moving_sum(free_dims, cal.half_width);
  Eigen::VectorXd wd(n);
  for (int j = 0; j < n; ++j) wd[j] = denom[j] > 1e-9 ? w[j] / denom[j] : 0.0;
  const Eigen::VectorXd c = circular_moving_sum(wd, cal.half_width);
  CalibratedLevel out;
  out.value = c.dot(cal.periodogram);
  // Satterthwaite: I_i (i and n - i are the same ordinate) ~ m_i chi2_2 / 2, m_i = s_i (1 - h_i); m_i from the data.
  const Eigen::VectorXd s_hat = circular_moving_sum(cal.periodogram, cal.half_width).cwiseQuotient(
      denom.cwiseMax(1e-9));
  double mean = 0.0, var = 0.0;
  for (int i = 0; i <= n / 2; ++i) {
    const int k = (n - i) % n;
    const bool single = i == 0 || k == i;
    const double ci = single ? c[i] : c[i] + c[k];
    const double mi = s_hat[i] * free_dims[i];
    mean += ci * mi;
    var += (single ? 2.0 : 1.0) * ci * ci * mi * mi;
  }
  out.dof = var > 0.0 ? 2.0 * mean * mean / var : 1e9;
  return out;
}

double calibrated_half_width_95(const SpectralCalibration& cal, const Eigen::VectorXd& v) {
  const CalibratedLevel l = calibrated_level(cal, power_spectrum(v));
  return t_quantile(0.975, std::max(l.dof, 1.0)) * std::sqrt(std::max(l.value, 0.0));
}

double t_quantile(double p, double dof) {
  // P(|t| > q) = P(F(1, dof) > q^2) = 2 (1 - p): bisection on the tail, which falls monotonically in q.
  const double tail = 2.0 * (1.0 - p);
  double lo = 0.0, hi = 1.0;
  while (f_upper_tail(hi * hi, 1.0, dof) > tail && hi < 1e6) hi *= 2.0;
  for (int it = 0; it < 100; ++it) {
    const double mid = 0.5 * (lo + hi);
    (f_upper_tail(mid * mid, 1.0, dof) > tail ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

FTest calibrated_f_test(const SpectralCalibration& cal, const Eigen::MatrixXd& base, const Eigen::MatrixXd& extra,
                        const Eigen::VectorXd& y) {
  if (!cal.valid() || cal.n != y.size()) return f_test(base, extra, y);
  int rank_full = 0;
  FTest t = nested_fits(base, extra, y, rank_full);
  if (t.df_extra <= 0) return t;
  // Orthonormal basis of the extra columns with base projected out: where the tested pattern's energy lies.
  const Eigen::MatrixXd qb = orthonormal_basis(base);
  Eigen::MatrixXd ex = extra;
  if (qb.cols() > 0) ex -= qb * (qb.transpose() * extra);
  const Eigen::MatrixXd qe = orthonormal_basis(ex);
  if (qe.cols() == 0) return t;
  Eigen::VectorXd w = Eigen::VectorXd::Zero(cal.n);
  for (int c = 0; c < qe.cols(); ++c) w += power_spectrum(qe.col(c));
  const CalibratedLevel l = calibrated_level(cal, w / w.sum());
  const double level = l.value, nu = l.dof;
  t.df_resid = static_cast<int>(std::max(1.0, std::floor(nu)));
  if (!(level > 0.0)) return t;
  t.f = std::max(0.0, (t.rss_base - t.rss_full) / t.df_extra) / level;
  t.p_value = f_upper_tail(t.f, t.df_extra, nu);
  return t;
}

}  // namespace sw::reconcile
