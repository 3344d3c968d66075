#pragma once
// Statistics for reconcile: the noise model (an autoregressive process estimated from the data), prewhitening, and
// the F-test of nested linear models in the whitened space (generalised least squares with an estimated AR filter).
#include <cstdint>
#include <random>
#include <vector>

#include <Eigen/Dense>

namespace sw::reconcile {

/// e_t = x_t - sum_k a[k] x_{t-1-k} is white with standard deviation `innovation_sd` (same units as the data).
struct ArModel {
  std::vector<double> a;           ///< AR coefficients a_1..a_p (empty: white noise)
  double innovation_sd = 0.0;      ///< sd of the white innovations
  double process_sd = 0.0;         ///< sd of the AR process itself (what a plot of the noise shows)
  int order() const { return static_cast<int>(a.size()); }
};

/// Fits AR(p), p = 0..max_order, by Yule-Walker (Levinson-Durbin; always stationary) to a zero-mean-ish residual and
/// keeps the order with the lowest BIC. Precondition: x.size() > 4 * max_order.
ArModel fit_ar(const Eigen::VectorXd& x, int max_order = 8);

/// The prewhitened rows p..n-1 of a vector or of each column (n-p rows): the GLS transform for that AR model.
Eigen::VectorXd whiten(const ArModel& ar, const Eigen::VectorXd& x);
Eigen::MatrixXd whiten(const ArModel& ar, const Eigen::MatrixXd& X);

/// n samples of the AR process (burn-in discarded), innovations N(0, innovation_sd^2).
Eigen::VectorXd simulate_ar(const ArModel& ar, int n, std::mt19937_64& rng);

/// Regularised incomplete beta I_x(a, b), 0 <= x <= 1, a, b > 0.
double incomplete_beta(double a, double b, double x);

/// Upper tail P(F(d1, d2) > f).
double f_upper_tail(double f, double d1, double d2);

/// Least squares on whitened data with column-pivoting QR (rank-revealing).
struct LsResult {
  Eigen::VectorXd beta;      ///< coefficients (zeros for dropped, collinear columns)
  Eigen::VectorXd residual;  ///< y - X beta
  double rss = 0.0;
  int rank = 0;
};
LsResult least_squares(const Eigen::MatrixXd& X, const Eigen::VectorXd& y);

/// Nested F-test: does adding `extra` to `base` explain more of y than noise would? Inputs already whitened.
/// Returns the p-value (1 when `extra` adds no rank).
struct FTest {
  double f = 0.0;
  double p_value = 1.0;
  int df_extra = 0;
  int df_resid = 0;
  double rss_base = 0.0;
  double rss_full = 0.0;
};
FTest f_test(const Eigen::MatrixXd& base, const Eigen::MatrixXd& extra, const Eigen::VectorXd& y);

/// Nonparametric check of the parametric noise model, used to calibrate tests of slow (low-order) patterns.
///
/// A finite AR model of noise that is not AR (AR(1) + white + quantisation is ARMA(1,1)) gets the spectrum's level at
/// low frequencies wrong: the AR(4..6) that AIC picks underestimates the long-run variance by 5-16 %. Every signature
/// that varies slowly (a mean offset, a torque step, a harmonic per torque level or per output revolution, a drift)
/// is tested against exactly that level, so the GLS F-test with the AR model alone is anti-conservative there.
/// The calibration keeps the AR model for the spectrum's shape and measures what it gets wrong: the periodogram of the
/// whitened residual of a rich model (every signature basis), smoothed over +-half_width Fourier bins and corrected
/// for the dimensions that rich model removed from each bin (its leverage), is the level of the whitened noise at
/// each frequency (1 where the AR model is right). A test's denominator is that level weighted by where the tested
/// pattern's energy lies, with Satterthwaite degrees of freedom (tens, not thousands: the level is estimated).
struct SpectralCalibration {
  int n = 0;                   ///< whitened rows
  int half_width = 0;          ///< smoothing half-width in Fourier bins
  Eigen::VectorXd periodogram; ///< |U r|^2 over the full circle (U the unitary DFT), r the whitened rich residual
  Eigen::VectorXd leverage;    ///< sum over the rich model's orthonormal columns of |U q|^2 (full circle)
  bool valid() const { return n > 0; }
};

/// rich_w: the whitened rich design (n_w x K), resid_w: the whitened residual of y on it.
SpectralCalibration spectral_calibration(const Eigen::MatrixXd& rich_w, const Eigen::VectorXd& resid_w,
                                         int half_width = 20);

/// The calibrated level sum_j w_j s_j of the whitened noise under spectral weights w (full circle), with the
/// Satterthwaite degrees of freedom of that estimate.
struct CalibratedLevel {
  double value = 0.0;
  double dof = 0.0;
};
CalibratedLevel calibrated_level(const SpectralCalibration& cal, const Eigen::VectorXd& w);

/// The 95 % half-width of v^T r for r the whitened noise (n = cal.n rows): its variance at the calibrated level of each
/// frequency (s^2 ||v||^2 where the AR model is right, more where the noise has more power than it says: a slow v, a
/// mean offset, a torque level), times Student's t at that level's Satterthwaite degrees of freedom.
double calibrated_half_width_95(const SpectralCalibration& cal, const Eigen::VectorXd& v);

/// The p-quantile of Student's t with `dof` degrees of freedom (dof > 0).
double t_quantile(double p, double dof);

/// Nested test like f_test, but with the noise level in the denominator taken from the calibration at the
/// frequencies where the extra columns (orthogonalised against base) carry their energy: F(df_extra, nu) with nu the
/// Satterthwaite degrees of freedom of that level. Inputs whitened with the AR model the calibration was built with.
FTest calibrated_f_test(const SpectralCalibration& cal, const Eigen::MatrixXd& base, const Eigen::MatrixXd& extra,
                        const Eigen::VectorXd& y);

/// Horizontal concatenation that tolerates zero-column blocks.
Eigen::MatrixXd hcat(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b);

}  // namespace sw::reconcile
