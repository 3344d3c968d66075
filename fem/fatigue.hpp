#pragma once
// Fatigue of the flexspline: the stress history of a material point over one generator revolution. The generator and
// the torque's engagement zones turn together, so a point at (r, z) sees the loaded field turned past it: its history
// is the field around the circle through it. Alternating and mean hoop and meridional (axial in the wall) stress, and
// a Goodman safety factor per component, 1/(σ_a/S_e + σ_m/S_u) for a tensile mean, S_e/σ_a for a compressive one
// (no credit for compression). Uniaxial per component: a multiaxial criterion (Sines, Crossland) is left out.
#include <optional>
#include <string>
#include <vector>

#include "common/material.hpp"
#include "mesh/flexspline_params.hpp"
#include "fem/post.hpp"

namespace sw {

struct StressCycle {
  double alternating_Pa = 0, mean_Pa = 0;
};

/// Stress history of the material point at (r, z) over one generator revolution: entry k is the field at 1°·k from the
/// generator's major axis (the field turned past the point); hoop, and normal along the meridian tangent (t_r, t_z).
/// None when the circle leaves the mesh somewhere (a faceted curved surface).
struct RevolutionHistory {
  std::vector<double> hoop_Pa, meridional_Pa;
};
std::optional<RevolutionHistory> revolution_history(double r_m, double z_m, double t_r, double t_z,
                                                   const PointSampler& sampler, const RowMatrixX6d& stress);

/// Alternating and mean of a periodic history.
StressCycle stress_cycle(const std::vector<double>& history_Pa);

/// Goodman safety factor of one component (infinity when σ_a = 0).
double goodman_safety_factor(const StressCycle& s, double fatigue_limit_Pa, double ultimate_strength_Pa);

struct FatiguePoint {
  std::string place;        ///< "rim bore", "rim outer surface", "diaphragm fillet"
  double r_m = 0, z_m = 0;
  StressCycle hoop, meridional;
  double safety_factor = 0;  ///< min over both components; 0 without [material] fatigue data
};

/// The worst point (lowest safety factor, else largest alternating stress) of the rim (over its width, bore and outer
/// surface) and, for a cup, of the diaphragm's fillet to the wall (not the clamped boss's singular corner), for the nodal stress
/// table `stress` (n_nodes x 6) of the loaded case.
struct FatigueReadout {
  FatiguePoint rim;
  std::optional<FatiguePoint> diaphragm;
};
FatigueReadout flexspline_fatigue(const FlexsplineParams& f, double rim_outer_radius_m, double generator_z_m,
                                  double band_width_m, const Material& material, const PointSampler& sampler,
                                  const RowMatrixX6d& stress);

}  // namespace sw
