#pragma once
// What the FEM solves: the flexspline, its material, the wave generator, the loads, the mesh size (the generator's
// contact stations follow it) and the solver. Every fem/ function takes this, never the whole case, so the FEM cannot
// depend on a later stage's options ([dynamics], [catalog], [circular_spline]) or on where the case came from; a
// message that needs the case file is completed by the caller.
#include <optional>

#include "common/material.hpp"
#include "fem/fem_params.hpp"
#include "gear/gear.hpp"
#include "generator/wave_generator.hpp"
#include "mesh/flexspline_params.hpp"

namespace sw {

struct FlexsplineModel {
  FlexsplineParams flexspline;
  std::optional<GearParams> gear;  ///< the teeth as a ring: the rim's outer radius (mesh/flexspline.hpp)
  Material material;
  std::optional<WaveGeneratorParams> wave_generator;  ///< absent: torque alone
  LoadParams load;
  MeshParams mesh;
  SolverParams solver;
};

}  // namespace sw
