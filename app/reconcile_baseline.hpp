#pragma once
// Shared by `strainwave reconcile` and `strainwave synth`: the baseline (current simulation) of a recording kind,
// from the case, the FEM result and the kinematics module. Messages name the file and field on bad input.
#include <optional>
#include <string>
#include <vector>

#include "dynamics/model.hpp"
#include "io/case.hpp"
#include "reconcile/experiment.hpp"
#include "reconcile/recording.hpp"

namespace sw::app {

struct BaselineSources {
  std::optional<Case> case_file;           ///< the case, when given
  std::string fem_result;                  ///< path of result.json ("" if none)
  std::optional<double> compliance;        ///< --compliance overrides the FEM result
  const reconcile::Recording* recording = nullptr;  ///< metadata used where the case is silent
};

/// The dynamics baseline of a model (its run with a variation, f_m, c0, steady output speed); the model's own
/// stiffness variation should be 0 (constant mesh stiffness).
reconcile::Baseline dynamics_baseline(const DynamicsModel& model);

/// Builds the baseline of `kind`. `notes` receives case/metadata disagreements and where each number came from.
reconcile::Baseline make_baseline(reconcile::Kind kind, const BaselineSources& src, std::vector<std::string>& notes);

}  // namespace sw::app
