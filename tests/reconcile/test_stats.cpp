// Statistics building blocks: F tail, AR estimation and whitening, branch detection.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "reconcile/experiment.hpp"
#include "reconcile/reconcile.hpp"
#include "reconcile/stats.hpp"

using namespace sw::reconcile;

TEST(IncompleteBeta, MatchesClosedForms) {
  // I_x(1, 1) = x; I_0.5(a, a) = 1/2 by symmetry; I_x(a, 1) = x^a.
  constexpr double kTol = 1e-12;  // continued fraction converges to machine precision here
  EXPECT_NEAR(incomplete_beta(1.0, 1.0, 0.3), 0.3, kTol);
  EXPECT_NEAR(incomplete_beta(7.5, 7.5, 0.5), 0.5, kTol);
  EXPECT_NEAR(incomplete_beta(3.0, 1.0, 0.6), 0.216, kTol);
}

TEST(FTail, MatchesTabulatedCriticalValues) {
  // Tabulated: F(1, 1000) 95 % point 3.851; F(3, 100) 99 % point 3.984.
  constexpr double kTableTol = 2e-4;  // tables give 4 significant digits
  EXPECT_NEAR(f_upper_tail(3.851, 1, 1000), 0.05, kTableTol);
  EXPECT_NEAR(f_upper_tail(3.984, 3, 100), 0.01, kTableTol);
}

TEST(ArModel, RecoversAnAr1ProcessAndWhitensIt) {
  ArModel truth;
  truth.a = {0.7};
  truth.innovation_sd = 2.0;
  std::mt19937_64 rng(7);
  const Eigen::VectorXd x = simulate_ar(truth, 20000, rng);
  const ArModel fit = fit_ar(x, 8);
  ASSERT_GE(fit.order(), 1);
  // Standard error of phi-hat ~ sqrt((1 - phi^2) / n) = 0.005: allow 5 sigma.
  EXPECT_NEAR(fit.a[0], 0.7, 0.025);
  EXPECT_NEAR(fit.innovation_sd, 2.0, 0.05);
  const Eigen::VectorXd w = whiten(fit, x);
  // Whitened lag-1 autocorrelation ~ N(0, 1/n): 5 sigma = 0.035.
  const double r1 = w.head(w.size() - 1).dot(w.tail(w.size() - 1)) / w.squaredNorm();
  EXPECT_LT(std::abs(r1), 0.035);
}

TEST(Branches, SplitATorqueCycleAtItsReversalsOnly) {
  const int n = 1000;
  Eigen::VectorXd t(n);
  std::mt19937_64 rng(3);
  std::normal_distribution<double> noise(0.0, 0.2);
  for (int i = 0; i < n; ++i) t[i] = 40.0 * std::sin(2 * M_PI * 2.0 * i / n) + noise(rng);
  const Branches b = find_branches(t, 0.02 * 80.0);
  // Two cycles starting at zero going up: reversals near samples 125, 375, 625, 875.
  ASSERT_EQ(b.reversals.size(), 4u);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(b.reversals[k], 125 + 250 * k, 15);
  EXPECT_EQ(b.direction[50], 1);
  EXPECT_EQ(b.direction[200], -1);
}

TEST(SpectralCalibration, MakesTheMeanOffsetTestNominalUnderAr1PlusWhiteNoise) {
  // AR(1) (phi 0.9) + white noise of equal size is ARMA(1,1) (MA root 0.63): the AR(p) that the order selection
  // picks underestimates its long-run variance (sigma_e^2 / (1 - sum a)^2; by ~35 % at p = 5), so the GLS F-test of a
  // mean offset, which is judged against exactly that variance, rejects too often. The calibrated test is nominal.
  constexpr int kReps = 400, kN = 2000;
  constexpr double kAlpha = 0.05;
  // Binomial(400, 0.05): mean 20, sd 4.4; allow 3 sd above.
  constexpr int kMaxRejections = 33;
  ArModel ar1;
  ar1.a = {0.9};
  ar1.innovation_sd = std::sqrt(1.0 - 0.81);  // process sd 1
  int rej_plain = 0, rej_cal = 0;
  for (int rep = 0; rep < kReps; ++rep) {
    std::mt19937_64 rng(1000 + rep);
    std::normal_distribution<double> white(0.0, 1.0);
    Eigen::VectorXd x = simulate_ar(ar1, kN, rng);
    for (int i = 0; i < kN; ++i) x[i] += white(rng);
    Eigen::MatrixXd rich(kN, 3);
    for (int i = 0; i < kN; ++i) {
      rich(i, 0) = 1.0;
      rich(i, 1) = std::cos(2 * M_PI * 3.0 * i / kN);
      rich(i, 2) = std::sin(2 * M_PI * 3.0 * i / kN);
    }
    const ArModel ar = fit_ar(least_squares(rich, x).residual, 8);
    const Eigen::MatrixXd rich_w = whiten(ar, rich);
    const Eigen::VectorXd xw = whiten(ar, x);
    const SpectralCalibration cal = spectral_calibration(rich_w, least_squares(rich_w, xw).residual);
    const Eigen::MatrixXd none(xw.size(), 0);
    const Eigen::MatrixXd ones = whiten(ar, Eigen::MatrixXd(Eigen::MatrixXd::Ones(kN, 1)));
    rej_plain += f_test(none, ones, xw).p_value < kAlpha;
    const FTest t = calibrated_f_test(cal, none, ones, xw);
    rej_cal += t.p_value < kAlpha;
    EXPECT_GT(t.df_resid, 30);  // the level is estimated from tens of Fourier bins, not thousands
  }
  std::printf("[calibration] mean-offset rejections at 5 %%: plain GLS %d / %d, calibrated %d / %d\n", rej_plain, kReps,
              rej_cal, kReps);
  EXPECT_LE(rej_cal, kMaxRejections);
  EXPECT_LT(rej_cal, rej_plain);
}
