#pragma once
// Shared by `strainwave reconcile` and `strainwave synth`: the baseline (current simulation) of a recording kind,
// from the case, the FEM result and the kinematics module. Messages name the file and field on bad input.
#include <optional>
#include <string>
#include <vector>

#include "dynamics/model.hpp"
#include "io/contact_output.hpp"
#include "io/case.hpp"
#include "reconcile/experiment.hpp"
#include "reconcile/recording.hpp"

namespace sw::app {

/// What a torsion recording is held against: the flexspline body alone (C_tau T, from the FEM) or the whole drive's
/// torque-twist curve from the loaded tooth contact (contact.json).
enum class TorsionBaseline { Fem, Contact };

/// "fem" or "contact"; throws InputError naming `--baseline` otherwise.
TorsionBaseline parse_torsion_baseline(const std::string& text);

struct BaselineSources {
  std::optional<Case> case_file;           ///< the case, when given
  TorsionBaseline torsion = TorsionBaseline::Fem;
  std::string fem_result;                  ///< path of result.json ("" if none)
  std::optional<double> compliance;        ///< --compliance overrides the FEM result
  std::string contact_result;              ///< path of contact.json (torsion, TorsionBaseline::Contact)
  /// The torque-twist curve already in memory (a re-run of the model): read instead of contact_result, which then
  /// only names it.
  std::optional<ContactCurve> contact_curve;
  const reconcile::Recording* recording = nullptr;  ///< metadata used where the case is silent
};

/// The dynamics baseline of a model (a DynamicsPrediction: its run with a variation, f_m, c0, steady output speed;
/// the source names the pair model); the model's own stiffness variation should be 0 (constant mesh stiffness).
reconcile::Baseline dynamics_baseline(const DynamicsModel& model);

/// A torque beyond the contact curve by at most this fraction of its rated torque (a torque sensor's overshoot at the
/// turning points) is read on the extended end segment, and said so in the notes; further out is an error.
inline constexpr double kCurveEndTolerance = 0.01;

/// Builds the baseline of `kind`. `notes` receives case/metadata disagreements and where each number came from.
/// Dynamics: the model `strainwave dynamics` builds from the case ([dynamics] pairs and rim; rim = "fem" solves the
/// FEM first), with constant mesh stiffness; its runs are remembered (reconcile::with_remembered_runs).
reconcile::Baseline make_baseline(reconcile::Kind kind, const BaselineSources& src, std::vector<std::string>& notes);

}  // namespace sw::app
