#pragma once
// The catalog of effects reconcile can name (SPEC.md "Effects reconcile can name") and the signatures that point to
// them. Both are tables: adding a kind (e.g. dynamics) means appending rows, not changing the algorithm.
//
// Every effect is separable: its contribution to the residual (recording - baseline) is columns(theta) * beta, with
// beta entering linearly (fitted by least squares) and theta a few bounded nonlinear parameters (breakpoints,
// transition widths), fitted by bounded Levenberg-Marquardt from several starts.
#include <cmath>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include "design/catalog.hpp"
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
  /// Variants of one law (stiffness with one or two breakpoints) exclude each other in a model; harmonic orders
  /// of one name do not.
  bool exclusive_variants = false;

  std::string id() const { return order ? name + "#" + std::to_string(order) : name; }
  /// Same name and an exclusive family: the two cannot both be in one model.
  bool conflicts(const EffectSpec& o) const { return exclusive_variants && o.name == name && o.id() != id(); }
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
/// The whole three-segment law is twist = T/K3 + (1/K2 - 1/K3) clamp(T, T2) + (1/K1 - 1/K2) clamp(T, T1).
Eigen::VectorXd soft_start_column(const Eigen::VectorXd& torque_Nm, double t1_Nm);

/// Twist of the catalog's three-segment law at torque T (odd in T), rad.
double segment_law_twist(double torque_Nm, double k1, double k2, double k3, double t1_Nm, double t2_Nm);

/// The catalog row of a recording's size when it lists the size's stiffness (design/catalog.hpp); nullptr otherwise.
const CatalogDrive* catalog_stiffness(int size);

/// A torsion model in the catalog's terms (the report's "catalog" block). Torques N*m, stiffness N*m/rad, angles
/// arcmin. The catalog's lost motion is the twist between -4 % and +4 % of rated torque read on the loop's middle
/// line: it includes elastic twist and is not the play effect `lost_motion` (width_rad).
struct CatalogFigures {
  bool valid = false;
  int segments = 1;                       ///< 1: one slope (no soft start); 2: K1, K2 (T1); 3: K1, K2, K3 (T1, T2)
  double k1 = 0, k2 = 0, k3 = 0, t1 = 0, t2 = 0;
  double rated_torque_Nm = 0;             ///< the torque the loss and lost motion are read at
  std::string rated_from;                 ///< "metadata rated_torque_Nm", "catalog size N", "recording amplitude"
  double hysteresis_loss_arcmin = 0;      ///< branch gap at zero torque after cycling to +-rated
  double play_arcmin = 0;                 ///< the play effect's width (dead band), 0 when not in the model
  double catalog_lost_motion_arcmin = 0;  ///< twist between +-4 % rated on the middle line (includes elastic twist)
  const CatalogDrive* reference = nullptr;///< the catalog row of the recording's size (metadata `size`), if any
};
/// The catalog figures of a fitted torsion model (baseline C_tau plus its effects).
CatalogFigures catalog_figures(const Experiment& e, const FitResult& model);

inline constexpr double kArcminPerRad = 10800.0 / M_PI;
/// Friction hysteresis column (Dahl-type branch transition): -dir * (1/2 - exp(-|T - T_reversal| / T_h)), unitless
/// (times the saturated branch gap h in rad). Loading branch below, unloading above.
Eigen::VectorXd hysteresis_column(const Experiment& e, double transition_Nm);
/// Branch gap at zero torque of a hysteresis with saturated gap h and transition T_h after reversals at +-A.
double hysteresis_loss_rad(double h_rad, double transition_Nm, double amplitude_Nm);
/// Lost-motion column: tanh(T / T_s) / 2 (times the width in rad).
Eigen::VectorXd lost_motion_column(const Eigen::VectorXd& torque_Nm, double transition_Nm);

}  // namespace sw::reconcile
