#pragma once
// Fitting a model (nuisance columns + catalog effects) to the residual recording - baseline by generalised least
// squares under an AR noise model: linear coefficients by least squares (variable projection), nonlinear ones by
// bounded Levenberg-Marquardt (Eigen, logistic reparameterisation) from several starts.
#include <vector>

#include <Eigen/Dense>

#include "reconcile/effects.hpp"
#include "reconcile/stats.hpp"

namespace sw::reconcile {

/// The design matrix (n rows): nuisance columns, then each term's columns at its theta.
Eigen::MatrixXd design_matrix(const Experiment& e, const std::vector<Term>& terms);

/// The contribution (n rows) of a model with given parameters.
Eigen::VectorXd model_contribution(const Experiment& e, const FitResult& model);

struct FitOptions {
  int rows = -1;                 ///< fit the first `rows` rows only (a training block); -1: all
  bool multistart_last = true;   ///< grid search the last term's theta for starts
  int starts = 3;                ///< best grid points polished by LM
  bool covariance = false;       ///< compute cov (costs one Jacobian)
};

/// Fits `y` (the residual recording - baseline, n rows) with nuisance + terms under AR noise `ar`.
/// Terms' theta are the starting values (ignored for the last term when multistart_last).
FitResult fit_model(const Experiment& e, const Eigen::VectorXd& y, std::vector<Term> terms, const ArModel& ar,
                    const FitOptions& options = {});

/// The noise behind a fit's intervals: its calibration (`cal`, built on the same whitened rows as the fit), and the
/// data the fit was made to with its AR model (`y`, `ar`: the profile of a nonlinear parameter refits them). Any may
/// be null: Wald's intervals then.
struct IntervalNoise {
  const SpectralCalibration* cal = nullptr;
  const Eigen::VectorXd* y = nullptr;
  const ArModel* ar = nullptr;
};

/// Headline parameters of term `term` (a fit to all rows) with 95 % intervals (value, lo, hi) by the delta method:
/// Wald's, or, with a valid calibration, the headline's variance at the level the calibration measured where its
/// influence lies, with Student's t at that level's degrees of freedom. A headline that is one of the term's nonlinear
/// parameters gets, with `y` and `ar`, the hull of that interval and its profile interval. A parameter the effect holds
/// (EffectSpec::held) has no interval: lo = hi = value and `fixed_from` says where it is read.
struct Headline {
  std::string name;
  double value = 0.0, lo = 0.0, hi = 0.0;
  std::string fixed_from;  ///< "" for a fitted parameter
  bool fixed() const { return !fixed_from.empty(); }
};
std::vector<Headline> headline_with_ci(const Experiment& e, const FitResult& model, int term,
                                       const IntervalNoise& noise = {});

/// Evenly spaced start grid between lo and hi; log-spaced when lo > 0 and hi / lo > 20.
std::vector<double> start_grid(double lo, double hi, int count);

}  // namespace sw::reconcile
