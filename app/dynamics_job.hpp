#pragma once
// The dynamics model of a case, built one way for `strainwave dynamics` and for reconcile's dynamics baseline: tooth
// pairs frozen at generator angle 0 (clearances from the basic kinematic model or the stand-in) or moving through the
// mesh (a rigid rim, or the rim coupled through the FEM's flexspline body, which solves the FEM first).
#include <memory>
#include <string>

#include "io/atomic_file.hpp"
#include "io/case.hpp"
#include "dynamics/model.hpp"
#include "dynamics/moving_mesh.hpp"

namespace sw::app {

/// The command line's choices that shape the model (the [dynamics] table gives the rest).
struct DynamicsModelOptions {
  std::string clearances = "kinematics";  ///< frozen pairs: "kinematics" (backlash module) | "approximate" (stand-in)
  std::string interference = "preload";   ///< flanks with negative clearance at rest: "preload" | "clip" | "drop"
  std::string fem_result;                 ///< result.json whose C_tau joins rim and flange ("": the case's value)
};

struct DynamicsJobModel {
  DynamicsModel model;
  std::string source;  ///< where the pairs and their clearances come from (reports and progress)
  /// How the generator bearing's friction moment was found, or why the bearing is frictionless in this model.
  std::string bearing_source;
};

/// The model `strainwave dynamics` integrates: the case's [dynamics] values `p` (already resolved), pairs moving or
/// frozen as p.pair_motion says. Precondition: c.gear is set. Throws InputError on invalid values (validate()).
DynamicsJobModel dynamics_model(const Case& c, DynamicsParams p, const DynamicsModelOptions& options, OutputSet& out);

}  // namespace sw::app
