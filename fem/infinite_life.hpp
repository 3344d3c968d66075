#pragma once
// The flexspline's torque for infinite fatigue life, on the harmonic solution: the largest output torque at which
// every material point outside the clamp's corner survives the stress cycle of one generator revolution.
//
// A point at (r, z) sees the loaded field turned past it (the generator and the torque's engagement zones turn
// together), so its history over a revolution is the field around the circle through it: six cylindrical stress
// components, each a Fourier series in θ read from the nodal amplitudes. Under torque T the field is the generator's
// plus T times what 1 N·m adds with the generator in place (FourierSolution::torque_with_generator: the cam holds the
// rim against the torque's ovalising part; linear about the case's torque, the cam's contact as it is there).
//
// Criterion: Sines' multiaxial criterion with Goodman's mean-stress line (Sines 1959, "Behavior of metals under
// complex static and alternating stresses", in Metal Fatigue, McGraw-Hill, pp. 145–169; as used in Bannantine, Comer &
// Handrock, Fundamentals of Metal Fatigue Analysis, 1990, §5.2): the alternating von Mises stress of the components'
// amplitudes against the fatigue limit S_e and the sum of the mean normal stresses (three times the mean hydrostatic
// stress) against the ultimate strength S_u,
//   1/n = σ_a,vM / S_e + max(0, σ_m,1 + σ_m,2 + σ_m,3) / S_u,
// each component's amplitude and mean from its own extremes over the revolution ((max − min)/2, (max + min)/2: the
// non-proportional history taken component by component, as Bannantine does). A static shear (the torque's mean τ_θz)
// has no hydrostatic part and costs no life: Sines' finding for mean torsion. A compressive mean earns no credit.
//
// Idealisations, said with the figure: a smooth polished part at the material's fatigue limit (no surface, size or
// reliability factors); the rim without its teeth (the tooth root is gear/tooth_root.hpp's); the clamp's re-entrant
// corner, where the linear solution is singular, left out (points within one wall of a clamped node and the boss).
#include <array>
#include <string>
#include <vector>

#include "fem/flexspline_model.hpp"
#include "fem/fourier_solver.hpp"

namespace sw {

/// Six stress components (σ_r, σ_z, σ_θ, τ_rz, τ_rθ, τ_θz) of a point, each sampled over one revolution (Pa).
using StressHistory = std::array<std::vector<double>, 6>;

/// Sines–Goodman safety factor of a history (infinity when nothing alternates and no tensile mean): see the header.
/// S_e, S_u in Pa, S_e < S_u.
double sines_goodman_safety_factor(const StressHistory& history, double fatigue_limit_Pa,
                                   double ultimate_strength_Pa);

/// The worst point of the flexspline at one torque.
struct FatigueState {
  double torque_Nm = 0;
  double safety_factor = 0;
  double r_m = 0, z_m = 0;
  std::string place;           ///< "rim", "body wall", "diaphragm"
  double alternating_von_mises_Pa = 0, mean_normal_sum_Pa = 0;
};

struct InfiniteLife {
  FatigueState at_zero;        ///< the generator's bending alone
  FatigueState at_limit;       ///< at the torque for infinite life (safety factor 1)
  double torque_Nm = 0;        ///< 0 when the generator alone exceeds the limit; infinity beyond `search_limit_Nm`
};

/// The largest von Mises stress over one revolution at a torque, and where (the same surface points as the fatigue's).
struct StressPeak {
  double torque_Nm = 0;
  double von_mises_Pa = 0;
  double r_m = 0, z_m = 0;
  std::string place;
};

/// The torque at which the flexspline first yields (von Mises against material.yield_strength_MPa, the instantaneous
/// field of the generator plus the torque at every sample of the revolution): the static limit beside the fatigue's.
struct FirstYield {
  StressPeak at_zero;   ///< the generator's bending alone
  StressPeak at_yield;  ///< at the torque found
  double torque_Nm = 0;  ///< 0 when the generator alone yields; infinity beyond the search
};

/// The largest von Mises stress of the harmonic solution `s` at output torque T over the fatigue's points.
StressPeak flexspline_peak_stress_at(const FourierSolution& s, const FlexsplineModel& c, double torque_Nm);

/// The smallest torque at which the largest von Mises stress reaches the yield strength: the same scan and bisection
/// (1e-4 of the torque) as infinite_life_torque. InputError without material.yield_strength_MPa or a generator.
FirstYield first_yield_torque(const FourierSolution& s, const FlexsplineModel& c, double search_limit_Nm);

/// The worst point of the harmonic solution `s` of model `c` at output torque T (N·m), over the section's nodes
/// outside the boss and more than one wall from a clamped node.
FatigueState flexspline_fatigue_at(const FourierSolution& s, const FlexsplineModel& c, double torque_Nm);

/// The smallest torque at which the worst point's Sines–Goodman safety factor is 1: the first crossing on a scan of
/// [0, search_limit_Nm] in 64 steps, then bisection to 1e-4 of the torque. Throws InputError when the material has no fatigue_limit_MPa / ultimate_strength_MPa or the
/// solution has no generator.
InfiniteLife infinite_life_torque(const FourierSolution& s, const FlexsplineModel& c, double search_limit_Nm);

}  // namespace sw
