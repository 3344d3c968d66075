#pragma once
// The flexspline analysis: supports, wave-generator and torque load cases on one factorisation, and the figures the
// backlash module needs (φ₀, C_τ, the deformed neutral curve) plus stresses and checks.
//
// Conventions: z is the axis, the clamped end at z = 0, the open (toothed) end at z = length; θ from +x, the wave
// generator's major axis. The torque T > 0 acts on the rim about +z; φ₀ > 0 is the rim's rotation about +z.
//
// Wave-generator models (forces push radially outward on the inner wall, over small patches, never at nodes):
//  - four_force: four equal forces at θ = ±β and π ± β, i.e. ±β from the major axis at both of its ends. This is the
//    classical four-force generator (a roller generator with two rollers each side of the major axis). The seed paper
//    words it as "forces at β = 30° and 150° (major axis) and at 60° and 120° (minor axis)", which, read literally,
//    puts forces on the minor axis that would push it out too and is not a two-lobe deformation; the reading ±β from
//    the major axis is the one that produces the described pattern (tensile hoop stress near the forces, compressive
//    at the minor axis) and is the one the issue fixes.
//  - two_force: two forces at θ = 0 and π.
//  - forces: the case's list of (angle from the major axis, weight).
//  - cam: not a force model; see prescribe below (u_r = w0·cos2θ over the generator band).
// With radial_deformation set, the forces are scaled so the neutral radius of the rim mid-width moves out by w0 at
// the major axis (mean of θ = 0 and π); otherwise each end of the major axis carries force_N in total.
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "common/params.hpp"
#include "fem/cholmod_factor.hpp"
#include "fem/post.hpp"
#include "mesh/tet_mesh.hpp"

namespace sw {

struct LoadCaseSolution {
  std::string name;      ///< "generator", "torque", "generator_torque"
  Eigen::VectorXd u;     ///< 3·n_nodes, m
  RowMatrixX6d stress;   ///< recovered nodal stresses (n_nodes x 6, Pa)
  double rim_rotation_rad = 0;  ///< least-squares rigid rotation of the rim's reading ring
};

/// Radial, tangential displacement and rotation of the normal of the neutral circle at the rim mid-width, sampled at
/// phi_rad (1° steps). Rotation μ = (v − dw/dθ)/r, the first-order rotation of the curve's tangent.
struct NeutralCurveSamples {
  double radius_m = 0, z_m = 0;
  std::vector<double> phi_rad;
  std::vector<double> w_wg_m, v_wg_m, mu_wg_rad;        ///< generator alone
  std::vector<double> w_comb_m, v_comb_m, mu_comb_rad;  ///< generator + torque
};

struct HoopStressExtreme {
  double max_tensile_Pa = 0, max_tensile_angle_deg = 0, max_tensile_z_m = 0;
  double max_compressive_Pa = 0, max_compressive_angle_deg = 0, max_compressive_z_m = 0;
  /// Hoop stress around the rim at the generator's axial position, on the inner and outer wall (1° steps from the
  /// major axis): where the pattern's tension and compression sit, away from the extremes' local peaks.
  double profile_z_m = 0, inner_radius_m = 0, outer_radius_m = 0;
  std::vector<double> inner_Pa, outer_Pa;
};

struct FlexsplineSolution {
  std::vector<LoadCaseSolution> cases;
  double torque_Nm = 0;
  double phi0_rad = 0;                ///< torque alone
  double compliance_rad_per_Nm = 0;   ///< φ₀ / T
  double phi0_theory_rad = 0;         ///< T·L/(G·J) of the body wall
  double applied_torque_Nm = 0;       ///< moment of the applied torque loads about z (check)
  double reaction_torque_Nm = 0;      ///< moment about z of the support reactions (torque case)
  double generator_rotation_rad = 0;  ///< net rim rotation of the generator-alone case (0 by symmetry)
  double generator_force_N = 0;       ///< force of each of the generator's point loads after scaling
  double generator_w0_m = 0;          ///< major-axis radial displacement reached
  Eigen::Vector3d generator_net_force = Eigen::Vector3d::Zero();   ///< resultant of the generator loads (N)
  Eigen::Vector3d generator_net_moment = Eigen::Vector3d::Zero();  ///< and their moment about the origin (N·m)
  std::vector<std::pair<double, double>> torque_sweep;  ///< (T, φ₀/T) from the combined case at several torques
  std::optional<NeutralCurveSamples> neutral_curve;     ///< when there is a generator
  HoopStressExtreme hoop;             ///< of the generator case if any, else of the torque case
  FactorStats factor;
  double assemble_s = 0, solve_s = 0;
  double reading_radius_m = 0, reading_z_m = 0;  ///< where φ₀ is read
};

/// Nodes fixed by the supports: every node on a kSurfaceClamped face (size n_nodes).
std::vector<bool> clamped_nodes(const TetMesh& mesh);

/// Radius of the rim's neutral circle (mid-thickness under the teeth, or of the body wall for a plain tube).
double neutral_radius(const FlexsplineParams& f);

/// Consistent load vector (3·n_nodes, N) of the case's torque load (rim engagement zones, uniform rim, or the exact
/// torsion shear on a plain tube's open end), scaled to `torque_Nm`.
Eigen::VectorXd torque_load_vector(const Case& c, const TetMesh& mesh, double torque_Nm);

/// Least-squares rigid rotation about z (rad) of the reading ring of displacement field u (3·n_nodes): the open end
/// face of a plain tube, else 360 points on the rim's neutral circle at its mid-width.
double reading_rotation(const Case& c, const TetMesh& mesh, const Eigen::VectorXd& u);

/// Solves every load case of the flexspline on one factorisation and extracts φ₀, C_τ, the neutral curve and
/// stresses. The mesh must come from mesh_flexspline for the same parameters.
FlexsplineSolution analyse_flexspline(const Case& c, const TetMesh& mesh);

}  // namespace sw
