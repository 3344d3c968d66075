#pragma once
// The catalog of effects reconcile can name (SPEC.md "Effects reconcile can name") and the signatures that point to
// them. Both are tables: adding a kind (e.g. dynamics) means appending rows, not changing the algorithm.
//
// An effect is one row holding its law once, for the fit and for synth alike. For the fit every effect is separable:
// its contribution to the residual (recording - baseline) is columns(theta) * beta, with beta entering linearly
// (fitted by least squares) and theta a few bounded nonlinear parameters (breakpoints, transition widths), fitted by
// bounded Levenberg-Marquardt from several starts. For synth the row's generators add the law (or another structure
// that imitates it) to a recording, so that a synthetic effect is exactly representable.
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include <Eigen/Dense>

#include "design/catalog.hpp"
#include "reconcile/experiment.hpp"
#include "reconcile/laws.hpp"

namespace sw::reconcile {

struct FitResult;       // below
struct CatalogReading;  // below

using NamedValues = std::vector<std::pair<std::string, double>>;

/// A dynamics effect as a change of the model: its columns are the model's response linearised at the baseline, from
/// a few runs; the refit (rerun.hpp) runs the model at its parameters instead. The parameters, their bounds, their
/// difference steps, how they set the model's variation, and the headlines they give.
struct RunLaw {
  Eigen::VectorXd lo, hi;  ///< bounds of the parameters (the model is never run outside them)
  /// The parameters term `term` of a fitted model stands for (the refit's start).
  std::function<Eigen::VectorXd(const Experiment&, const FitResult&, int term)> start;
  /// The difference step of parameter i at p.
  std::function<double(const Experiment&, const Eigen::VectorXd& p, int i)> step;
  /// Sets the effect's fields of the model's variation at p.
  std::function<void(const Experiment&, const Eigen::VectorXd& p, DynamicsVariation& v)> vary;
  /// The headlines at p (the names and order of EffectSpec::headline), given the change of the response that the
  /// model run at p makes (n: the run minus the baseline).
  std::function<NamedValues(const Experiment&, const Eigen::VectorXd& p, const Eigen::VectorXd& change)> headline;
};

/// One variant of an effect's law as the fit sees it: a harmonic order, or a number of breakpoints or friction
/// elements of one law.
struct EffectSpec {
  std::string name;                          ///< SPEC name, e.g. "wg_harmonic"
  Kind kind = Kind::Torsion;
  int order = 0;                             ///< harmonic order, or the variant's number (0: the only one)
  std::string physics;                       ///< plain words: the physics the simulation left out
  std::string label;                         ///< the name with its variant, for messages
  int n_linear = 1;                          ///< columns of columns()
  std::vector<std::string> nonlinear_names;  ///< theta's names (empty: linear effect)
  /// Bounds of theta for this experiment (lo, hi), and a start grid per parameter.
  std::function<std::pair<Eigen::VectorXd, Eigen::VectorXd>(const Experiment&)> bounds;
  /// n x n_linear matrix: the contribution is columns * beta (units of the response per unit beta).
  std::function<Eigen::MatrixXd(const Experiment&, const Eigen::VectorXd& theta)> columns;
  /// The headline parameters (SPEC units) of term `term` of a fitted model.
  std::function<NamedValues(const Experiment&, const FitResult&, int term)> headline;
  /// Where headline parameter `parameter` of term `term` is held from when the fit does not move it (a segment
  /// slope read on the baseline, the model's mesh frequency): a phrase for the report; "" for a fitted parameter,
  /// which gets a 95 % interval. Empty function: every parameter is fitted.
  std::function<std::string(const Experiment&, const FitResult&, int term, const std::string& parameter)> held;
  /// Dynamics: the effect as a change of the model itself (RunLaw), refitted on re-runs of the model; absent: the
  /// effect's contribution is its columns alone.
  std::optional<RunLaw> run_law;
  /// What term `term` of a fitted model means for the drive, in a sentence (a play the model has more of than the
  /// drive, and the case key that sets it); empty function or "": nothing beyond the physics text.
  std::function<std::string(const Experiment&, const FitResult&, int term)> meaning;
  /// Torsion: adds term `term` of a fitted model to the catalog figures and the loop's middle line (empty: the
  /// effect is not read in catalog terms).
  std::function<void(const Experiment&, const FitResult&, int term, CatalogReading&)> catalog;
  /// Why a fitted term cannot stand although it fits (a physical key asked for beyond its plausible range); "" or
  /// empty: it can.
  std::function<std::string(const Experiment&, const FitResult&, int term)> implausible;
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

/// An effect of the catalog in a model, with its parameters (the fit, reconcile/fit.hpp, sets them).
struct Term {
  const EffectSpec* spec = nullptr;
  Eigen::VectorXd theta;  ///< nonlinear parameters (size spec->n_nonlinear())
  Eigen::VectorXd beta;   ///< linear coefficients (size spec->n_linear)
};

struct FitResult {
  std::vector<Term> terms;
  Eigen::VectorXd nuisance_beta;
  Eigen::VectorXd contribution;  ///< nuisance + effects for every row of the experiment (response units)
  double rss_w = 0.0;            ///< whitened residual sum of squares over the fitted rows
  int n_w = 0;                   ///< whitened rows
  int k = 0;                     ///< free parameters (rank of the linear part + nonlinear parameters)
  Eigen::MatrixXd cov;           ///< covariance of params() (whitened Gauss-Newton, s^2 (J^T J)^+)
  Eigen::MatrixXd jac_w;         ///< the whitened Jacobian J of params() behind cov (n_w rows)
  double bic() const;
  /// All parameters stacked: nuisance beta, then per term beta then theta.
  Eigen::VectorXd params() const;
  /// Sets the parameters from params() layout (contribution is not recomputed).
  void set_params(const Eigen::VectorXd& p);
  /// Index of the first term with this effect name; -1 when absent.
  int find(const std::string& name) const;
};

/// The name of a physical effect, a change of a case key (reconcile/model_update.hpp): "model:" + the key.
std::string model_effect_name(const std::string& key);
/// Is this effect a physical candidate (a case key)?
bool is_model_effect(const EffectSpec& spec);

/// One hidden effect synth adds: a generator's name, its harmonic order (0 if none) and its parameters in SPEC units.
/// Missing parameters take defaults (see synth_effect_help()).
struct SynthEffect {
  std::string name;
  int order = 0;
  std::map<std::string, double> params;
};

/// An effect a synthetic law implies besides itself (a stiffness law's last slope other than 1/C_tau is series
/// compliance): its name and parameter, its contribution per unit parameter, and the parameter at an amplitude.
struct ImpliedEffect {
  std::string name, parameter;
  Eigen::VectorXd column;
  std::function<double(double amplitude)> value;
};

/// A hidden effect of a kind with a response column (torsion, transmission, backlash): its contribution per unit
/// amplitude, the amplitude asked for, and the truth's parameters at an amplitude.
struct SynthShape {
  Eigen::VectorXd column;
  double amplitude = 0.0;
  std::function<NamedValues(double amplitude)> truth;
  std::optional<ImpliedEffect> implied;
};

/// A hidden dynamics effect: `vary(v, scale)` sets the effect's own fields of v at `scale` times the parameters asked
/// for; the truth's parameters at a scale.
struct SynthVariation {
  std::function<void(DynamicsVariation& v, double scale)> vary;
  std::function<NamedValues(double scale)> truth;
};

using ColumnLaw = std::function<SynthShape(const SynthEffect&, const Experiment&)>;
using VariationLaw = std::function<SynthVariation(const SynthEffect&, const DynamicsPrediction&)>;

/// How synth generates an effect: the effect's own law, or another structure the fit's law lacks (named in the truth
/// as the effect it imitates). Its law throws InputError for parameters out of range.
struct SynthGenerator {
  std::string name;                 ///< --effect name
  std::vector<std::string> keys;    ///< the parameters it takes ("order" for harmonics)
  std::string help;                 ///< its parameters with their defaults, for synth_effect_help()
  bool names_generator = false;     ///< the truth entry names the generator beside the effect
  std::variant<ColumnLaw, VariationLaw> law;
};

/// One effect of the catalog: its fit variants and its synth generators (the law itself first).
struct Effect {
  std::string name;
  Kind kind = Kind::Torsion;
  std::vector<EffectSpec> variants;
  std::vector<SynthGenerator> generators;
};

/// Largest harmonic order searched in wave-generator and output angle.
inline constexpr int kMaxHarmonicOrder = 4;

/// The effects of a kind, in the order the fit tries them.
const std::vector<Effect>& effect_table(Kind kind);

/// Every fit variant of a kind's effects (harmonics appear once per order), in table order.
const std::vector<EffectSpec>& effect_catalog(Kind kind);

/// A synth generator and the effect it is named as in the truth.
struct SynthLaw {
  const Effect* effect = nullptr;
  const SynthGenerator* generator = nullptr;
};
/// The generator of `fx` among a kind's effects, its parameters checked against the generator's. Throws InputError
/// for a name that is not a generator of the kind or an unknown parameter.
SynthLaw synth_law(Kind kind, const SynthEffect& fx);

/// A parameter of a hidden effect, or its default.
double synth_param(const SynthEffect& fx, const std::string& key, double fallback);

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

/// The signatures of a kind.
const std::vector<SignatureSpec>& signature_catalog(Kind kind);

/// Columns that are part of every model of a kind (not physics): torsion: twist offset; transmission: angle offset
/// and ratio/encoder scale; backlash, dynamics: none.
Eigen::MatrixXd nuisance_columns(const Experiment& e);

/// The catalog row of a recording's size when it lists the size's stiffness (design/catalog.hpp); nullptr otherwise.
const CatalogDrive* catalog_stiffness(int size);

/// A torsion model in the catalog's terms (the report's "catalog" block). Torques N*m, stiffness N*m/rad, angles
/// arcmin. The catalog's lost motion is the twist between -4 % and +4 % of rated torque read on the loop's middle
/// line: it includes elastic twist and is not the play effect `lost_motion` (width_rad).
struct CatalogFigures {
  int segments = 1;                       ///< 1: one slope (no soft start); 2: K1, K2 (T1); 3: K1, K2, K3 (T1, T2)
  double k1 = 0, k2 = 0, k3 = 0, t1 = 0, t2 = 0;
  double rated_torque_Nm = 0;             ///< the torque the loss and lost motion are read at
  std::string rated_from;                 ///< "metadata rated_torque_Nm", "catalog size N", "recording amplitude"
  double hysteresis_loss_arcmin = 0;      ///< branch gap at zero torque after cycling to +-rated
  double play_arcmin = 0;                 ///< the play effect's width (dead band), 0 when not in the model
  double catalog_lost_motion_arcmin = 0;  ///< twist between +-4 % rated on the middle line (includes elastic twist)
  const CatalogDrive* reference = nullptr;///< the catalog row of the recording's size (metadata `size`), if any
};

/// The figures and the loop's middle line after cycling to +-rated torque (everything but the branch-dependent part of
/// hysteresis), as the terms of a fitted model add to them.
struct CatalogReading {
  CatalogFigures figures;
  std::function<double(double torque_Nm)> middle_twist_rad;
};

/// The catalog figures of a fitted torsion model (baseline C_tau plus its effects); nullopt for other kinds.
std::optional<CatalogFigures> catalog_figures(const Experiment& e, const FitResult& model);

/// The series compliance a fitted model adds to the baseline (its series_compliance term; 0 without one), rad/(N*m).
double added_series_compliance(const FitResult& model);

/// The play of a torsion baseline (the jump of its curve across zero torque; 0 for C_tau T), rad.
double baseline_play_rad(const TorsionExperiment& t);

}  // namespace sw::reconcile
