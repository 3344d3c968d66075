#pragma once
// Model updating: physical candidates are numeric case keys (rim, wall and diaphragm thickness, the generator's
// radial deformation, how the circular spline is held, tip rounding, flank friction) whose change the model itself
// turns into a change of the recording. Their columns are the model's own sensitivities (central differences of
// re-runs), selection weighs them beside the phenomenological effects (reconcile.hpp), and the accepted ones are
// refitted by Levenberg-Marquardt on re-runs of the model, under the same noise model.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "reconcile/effects.hpp"
#include "reconcile/experiment.hpp"
#include "reconcile/reconcile.hpp"

namespace sw::reconcile {

/// A case key the model may be updated on: what a change of it means for the part, its plausible range and the case's
/// (resolved) value, in the case file's units.
struct ModelCandidate {
  std::string key;      ///< "flexspline.rim_thickness_mm"
  std::string physics;  ///< "the rim under the teeth is thinner or thicker than drawn"
  double lo = 0.0, hi = 0.0;
  double case_value = 0.0;
};

/// Fraction of a candidate's plausible range used as the half step of its central difference (see sensitivity_step).
inline constexpr double kSensitivityStepFraction = 0.02;

/// The half step of a candidate's central difference: kSensitivityStepFraction of its plausible range. Large enough
/// that the contact's discrete events (a flank closing between two torque steps) average over the curve instead of
/// setting the column, small enough that the curvature of the response adds O(step^2) (0.04 % of a column over the
/// range for a quadratic response).
double sensitivity_step(const ModelCandidate& c);

/// The physical effects of an experiment: one EffectSpec "model:KEY" per candidate the model responds to (its column
/// the sensitivity of the response to the key, per unit of the key; beta = the change of the key), and the candidates
/// it does not respond to with the reason. Terms of a Result point into `specs`: keep the value alive with it.
struct ModelEffects {
  std::vector<ModelCandidate> candidates;  ///< those with a column, in the order of specs
  std::vector<EffectSpec> specs;
  std::vector<Rejected> rejected;
};

/// Runs the model at each candidate's value at `at` (the case's for a key it does not set) +- its step (one-sided
/// where the range ends there) and builds the columns; beta is the change from that value. `base.model_run` must be set; its runs should be remembered (with_remembered_model_runs): selection,
/// refit and every recording of one torque history share them.
std::shared_ptr<const ModelEffects> model_effects(const Experiment& e, const Baseline& base,
                                                  const std::vector<ModelCandidate>& candidates,
                                                  const ModelKeyValues& at = {});

/// The same baseline with its model runs remembered by key values (a run is a deterministic function of them).
/// Copies share the store; not thread-safe.
Baseline with_remembered_model_runs(Baseline base);

/// Two physical candidates whose columns, after the nuisance columns are projected out and the AR noise whitened,
/// correlate above this are reported together: the data cannot tell which of the two it is.
inline constexpr double kIndistinguishableCorrelation = 0.95;

/// One refitted key: the value with its 95 % interval (from the final Jacobian under the noise model) and the case's.
struct RefitValue {
  std::string key;
  double value = 0.0, lo = 0.0, hi = 0.0, case_value = 0.0;
  bool at_range_edge = false;          ///< the bounded refit stopped on an end of the key's plausible range
  double range_lo = 0.0, range_hi = 0.0;  ///< that range (ModelCandidate::lo, hi)
};

/// The model re-run at the refitted values.
struct Refit {
  std::vector<RefitValue> values;
  ModelKeyValues key_values;           ///< the fitted values as the re-run takes them
  Eigen::VectorXd model_response;      ///< the re-run's response on the rows (n): predicted_response of the run
  Eigen::VectorXd prediction;          ///< model_response + the nuisance and phenomenological terms refitted (n)
  double rms = 0.0, heldout_rms = 0.0; ///< of recording - prediction: all rows; the held-out rows (fitted without them)
  int iterations = 0;
};

/// Levenberg-Marquardt over the accepted physical keys of `result` on re-runs of the model (re-linearised by fresh
/// central differences at each iterate), the phenomenological terms' linear coefficients and the nuisance refitted at
/// each iterate with their nonlinear parameters held, whitened by the result's AR noise model. The values come from
/// all rows; the held-out RMS from the same fit on the training rows. nullopt without an accepted physical effect.
std::optional<Refit> refit_model(const Experiment& e, const Baseline& base, const ModelEffects& effects,
                                 const Result& result, const Options& options = {});

/// Physical candidates and the phenomenological catalog together: selection (reconcile()), the physical effects that
/// the data cannot tell from another candidate reported with its equivalent value, and the refit.
struct ModelUpdate {
  std::shared_ptr<const ModelEffects> effects;
  Result result;
  std::optional<Refit> refit;
};

/// The whole model update of an experiment against its re-runnable baseline: selection with the columns at the case
/// values and the refit; when physical keys were refitted, selection and refit again with the baseline and the
/// columns at the refitted values (the response bends over the change, and a linear column would leave that bend to
/// the phenomenological effects). The baseline's figures and the located mismatch are the case model's.
ModelUpdate update_model(const Experiment& e, const Baseline& base, const std::vector<ModelCandidate>& candidates,
                         const Options& options = {});

}  // namespace sw::reconcile
