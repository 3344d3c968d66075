#pragma once
// The catalog of effects reconcile can name (SPEC.md "Effects reconcile can name") and the signatures that point to
// them. Both are tables: adding a kind (e.g. dynamics) means appending rows, not changing the algorithm.
//
// Every effect is separable: its contribution to the residual (recording - baseline) is columns(theta) * beta, with
// beta entering linearly (fitted by least squares) and theta a few bounded nonlinear parameters (breakpoints,
// transition widths), fitted by bounded Levenberg-Marquardt from several starts.
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include "reconcile/experiment.hpp"

namespace sw::reconcile {

struct FitResult;  // fit.hpp

using NamedValues = std::vector<std::pair<std::string, double>>;

struct EffectSpec {
  std::string name;                          ///< SPEC name, e.g. "wg_harmonic"
  Kind kind = Kind::Torsion;
  int order = 0;                             ///< harmonic order (0: not a harmonic)
  std::string physics;                       ///< plain words: the physics the simulation left out
  int n_linear = 1;                          ///< columns of columns()
  std::vector<std::string> nonlinear_names;  ///< theta's names (empty: linear effect)
  /// Bounds of theta for this experiment (lo, hi), and a start grid per parameter.
  std::function<std::pair<Eigen::VectorXd, Eigen::VectorXd>(const Experiment&)> bounds;
  /// n x n_linear matrix: the contribution is columns * beta (units of the response per unit beta).
  std::function<Eigen::MatrixXd(const Experiment&, const Eigen::VectorXd& theta)> columns;
  /// The headline parameters (SPEC units) of term `term` of a fitted model.
  std::function<NamedValues(const Experiment&, const FitResult&, int term)> headline;
  /// Number of sibling hypotheses this one was chosen among (harmonic orders): its p-value is multiplied by it.
  int multiplicity = 1;

  std::string id() const { return order ? name + "#" + std::to_string(order) : name; }
  int n_nonlinear() const { return static_cast<int>(nonlinear_names.size()); }
};

/// A residual pattern tested against the current model: does `basis` (given `condition`) explain more than noise?
struct SignatureSpec {
  std::string name;         ///< e.g. "loading_unloading"
  std::string domain;       ///< report domain: "torque", "torque branch", "wave-generator angle", "time", ...
  std::string what;         ///< plain words
  std::function<Eigen::MatrixXd(const Experiment&)> basis;
  std::function<Eigen::MatrixXd(const Experiment&)> condition;  ///< extra null columns (may return n x 0)
  std::vector<std::string> triggers;                            ///< effect ids it points to
  /// Variable that locates the mismatch (for ranges in the report) and its unit; periodic ones report amplitude.
  std::function<Eigen::VectorXd(const Experiment&)> where;
  std::string where_unit;
  bool periodic = false;
};

/// Largest harmonic order searched in wave-generator and output angle.
inline constexpr int kMaxHarmonicOrder = 4;

/// The effects of a kind (harmonics appear once per order).
const std::vector<EffectSpec>& effect_catalog(Kind kind);

/// The signatures of a kind.
const std::vector<SignatureSpec>& signature_catalog(Kind kind);

/// Columns that are part of every model of a kind (not physics): torsion: twist offset; transmission: angle offset
/// and ratio/encoder scale; backlash: none.
Eigen::MatrixXd nuisance_columns(const Experiment& e);

// Model laws shared by synth and the fit (so a synthetic effect is exactly representable).

/// Soft-start column of the catalog law: clamp(T, -T1, T1) in N*m (times the compliance step 1/K1 - 1/K2).
Eigen::VectorXd soft_start_column(const Eigen::VectorXd& torque_Nm, double t1_Nm);
/// Friction hysteresis column (Dahl-type branch transition): -dir * (1/2 - exp(-|T - T_reversal| / T_h)), unitless
/// (times the saturated branch gap h in rad). Loading branch below, unloading above.
Eigen::VectorXd hysteresis_column(const Experiment& e, double transition_Nm);
/// Branch gap at zero torque of a hysteresis with saturated gap h and transition T_h after reversals at +-A.
double hysteresis_loss_rad(double h_rad, double transition_Nm, double amplitude_Nm);
/// Lost-motion column: tanh(T / T_s) / 2 (times the width in rad).
Eigen::VectorXd lost_motion_column(const Eigen::VectorXd& torque_Nm, double transition_Nm);

}  // namespace sw::reconcile
