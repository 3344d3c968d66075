#pragma once
// reconcile: fit the noise -> locate -> admit -> prune -> prefer simpler -> finalise. Given an experiment
// (recording + baseline), find where the residual differs from noise, name the catalog effects that explain it (one
// at a time, then jointly where overlapping effects only together remove their signatures), fit them with
// confidence intervals and keep only those whose removal costs significantly (BIC, held-out block, significance
// against the estimated noise).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "reconcile/experiment.hpp"
#include "reconcile/fit.hpp"
#include "reconcile/stats.hpp"

namespace sw::reconcile {

struct Options {
  double alpha_family = 0.05;    ///< family-wise level of the signature tests (Bonferroni over the kind's signatures)
  double alpha_effect = 0.01;    ///< level an effect must reach (after multiplicity) to be accepted
  double min_delta_bic = 10.0;   ///< BIC must drop by more than this ("very strong" on the Kass-Raftery scale)
  int bootstrap = 99;            ///< parametric bootstrap replicates for effects with nonlinear parameters
  double heldout_fraction = 0.25;///< the last contiguous fraction of the rows is held out
  int ar_max_order = 8;          ///< largest AR order of the noise model
  /// Half-width (Fourier bins) of the spectral calibration of the noise level (stats.hpp SpectralCalibration);
  /// 0: trust the AR model's level at every frequency (anti-conservative for slow patterns under ARMA noise).
  int spectral_half_width = 20;
  std::uint64_t seed = 1;        ///< bootstrap random seed (results are reproducible)
  int max_effects = 6;           ///< forward selection stops here
};

struct Location {
  std::string signature;
  std::string domain;
  std::string description;
  double p_value = 1.0;          ///< Bonferroni-adjusted over the kind's signatures
  bool has_range = false;
  double lo = 0.0, hi = 0.0;     ///< where it is strongest, in `where_unit` of the signature
};

struct AcceptedEffect {
  std::string name;
  std::string physics;
  std::vector<Headline> params;  ///< headline parameters with 95 % intervals
  double delta_bic = 0.0;        ///< BIC(model with it) - BIC(model without it), at acceptance
  double p_value = 1.0;          ///< F-test (times multiplicity) or parametric bootstrap
  std::string test;              ///< "F" or "bootstrap"
  std::string meaning;           ///< what it means for the drive (EffectSpec::meaning), "" when nothing beyond physics
  /// Effects that are changes of the model (dynamics), refitted on re-runs of it: how far the columns from the
  /// baseline's runs missed the model at their own estimate (|run there - the columns' prediction| / |run - baseline|,
  /// of all such effects together) and the runs the refit took; 0: read from the columns.
  double model_discrepancy = 0.0;
  int model_runs = 0;
};

struct Rejected {
  std::string name;
  std::string reason;
  bool operator==(const Rejected&) const = default;
};

struct Result {
  Kind kind = Kind::Torsion;
  int samples = 0;
  std::string baseline_model;            ///< what the recording was held against (Experiment::baseline_model)
  std::string baseline_source;           ///< where the baseline was read ("" when given directly)
  int heldout_rows = 0;                  ///< the last rows, never used to fit what is scored on them
  double baseline_rms = 0.0, baseline_heldout_rms = 0.0;
  double final_rms = 0.0, final_heldout_rms = 0.0;
  bool significant = false;
  std::vector<Location> locations;       ///< significant signatures of the baseline residual
  std::vector<AcceptedEffect> effects;
  std::vector<Rejected> rejected;
  std::vector<Location> unexplained;     ///< signatures still significant after the final model
  std::string verdict;                   ///< no_significant_mismatch | explained | partly_explained
  ArModel noise;                         ///< the estimated noise model
  SpectralCalibration calibration;       ///< its level checked against the data, per frequency
  Eigen::VectorXd residual_before;       ///< recording - baseline - nuisance fit (n)
  Eigen::VectorXd residual_after;        ///< recording - baseline - final model (n)
  Eigen::VectorXd final_prediction;      ///< baseline + final model (n)
  Eigen::VectorXd baseline_prediction;   ///< baseline + nuisance fit (n)
  FitResult final_model;
  std::optional<CatalogFigures> catalog;  ///< torsion: the final model in the catalog's terms
  /// The model re-run with the fitted physical values (model_update.hpp) or dynamics effects (their RunLaw; absent
  /// without either):
  /// recording - refit_prediction over all rows and over the held-out rows, and the prediction itself (n).
  bool refitted = false;
  double refit_rms = 0.0, refit_heldout_rms = 0.0;
  Eigen::VectorXd refit_prediction;
  double seconds = 0.0;
};

/// Runs the whole analysis. Deterministic for a given options.seed. `physical`: physical candidates ("model:KEY"
/// effects, model_update.hpp) weighed beside the kind's catalog whenever a mismatch is located; when one explains the
/// mismatch as well as the best phenomenological effect (BIC within min_delta_bic), it is tried first. The result's
/// terms point into `physical`: it must outlive the result. `held`: effects of `physical` in the model from the start
/// (the baseline's figures include them) and never pruned, as a model update's second pass holds the keys it fitted.
Result reconcile(const Experiment& e, const Options& options = {}, const std::vector<EffectSpec>* physical = nullptr,
                 const std::vector<const EffectSpec*>& held = {});


}  // namespace sw::reconcile
