#pragma once
// What the FEM solves: the flexspline, its material, the wave generator, the loads, the mesh size (the generator's
// contact stations follow it) and the solver. Every fem/ function takes this, never the whole case, so the FEM cannot
// depend on a later stage's options ([dynamics], [catalog], [circular_spline]) or on where the case came from; a
// message that needs the case file is completed by the caller.
#include <optional>
#include <string>

#include "common/material.hpp"
#include "fem/fem_params.hpp"
#include "gear/gear.hpp"
#include "generator/wave_generator.hpp"
#include "mesh/flexspline_params.hpp"

namespace sw {

struct FlexsplineModel {
  FlexsplineParams flexspline;
  std::optional<GearParams> gear;  ///< the teeth as a ring: the rim's outer radius (mesh/flexspline_sizes.hpp)
  Material material;
  std::optional<WaveGeneratorParams> wave_generator;  ///< absent: torque alone
  LoadParams load;
  MeshParams mesh;
  SolverParams solver;
};

/// Angular spacing of the contact stations: two element edges at the bore (a contact pressure resolved more finely
/// than the displacement field checkerboards), at least 2° and at most 6°, dividing 180° evenly.
double station_spacing(const FlexsplineModel& c);

/// The harmonics a case needs (the default of solver.harmonics): 64, or more where the generator's contact stations
/// need them (a hat of half-width Δ has its spectrum's main lobe up to 2π/Δ: two harmonics per station pair) or the
/// teeth's flank patterns do (hats one tooth pitch wide: the loaded contact's twist at rated torque settles at
/// z_f/2, contact/README.md).
int default_harmonics(const FlexsplineModel& c);
/// Where default_harmonics' value comes from, in words (for the resolved case).
std::string default_harmonics_origin(const FlexsplineModel& c);

}  // namespace sw
