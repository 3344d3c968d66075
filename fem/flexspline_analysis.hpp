#pragma once
// The flexspline analysis: supports, wave-generator and torque load cases on one factorisation, and the figures the
// backlash module needs (φ₀, C_τ, the deformed neutral curve) plus stresses and checks.
//
// Conventions: z is the axis, the clamped end at z = 0, the open (toothed) end at z = length; θ from +x, the wave
// generator's major axis. The torque T > 0 acts on the rim about +z; φ₀ > 0 is the rim's rotation about +z.
//
// Wave-generator models:
//  - cam: the generator as a body: frictionless unilateral contact between its surface (polar r + w0·cos2φ or a true
//    ellipse, with a radial fit) and the bore over the generator's band (fem/generator_contact.hpp): it pushes where
//    it touches and the flexspline lifts off elsewhere. The torque and combined cases keep the cam in place (contact
//    is solved again with the torque), so a locked cam carries part of the torque through its tilted normal.
//  - rollers: rigid rollers at ±β from both ends of the major axis, each a line contact across the band (spread over
//    one station's hat), unilateral; set out so the major axis reaches w0. Under torque a roller may lift off.
//  - four_force, two_force, forces: the seed paper's idealisation, radial forces over small patches of the inner
//    wall (never at nodes). four_force: four equal forces at θ = ±β and π ± β, i.e. ±β from the major axis at both of
//    its ends (the seed paper words it as "forces at β = 30° and 150° (major axis) and at 60° and 120° (minor axis)",
//    which, read literally, would push the minor axis out too; the reading ±β from the major axis produces the
//    described pattern). two_force: θ = 0 and π. forces: the case's list of (angle from the major axis, weight).
//    With radial_deformation set, the forces are scaled so the neutral radius of the rim mid-width moves out by w0 at
//    the major axis (mean of θ = 0 and π); otherwise each end of the major axis carries force_N in total. The paper
//    says nothing of where such a generator touches under torque: the torque case holds the band radially at the
//    contact stations (bilateral, the idealisation's "generator in place"), and the combined case is the sum.
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "fem/flexspline_model.hpp"
#include "fem/cholmod_factor.hpp"
#include "fem/fatigue.hpp"
#include "fem/flexspline_system.hpp"
#include "fem/generator_contact.hpp"
#include "fem/post.hpp"
#include "mesh/tet_mesh.hpp"

namespace sw {

// Shared by the TET10 and the harmonic analysis, so that both read the flexspline alike.
/// Points on the reading circle (1° steps).
inline constexpr int kRingSamples = 360;
/// A generator station touches when it carries force or its gap is within 0.25 % of w0 (0.5 µm at w0 = 0.2 mm: the
/// roughness of a ground bearing race, and the level at which the mesh's own asymmetry shows in the gaps).
inline constexpr double kTouchingGap = 2.5e-3;
/// The torque sweep's torques, in T_ref.
inline constexpr double kSweep[] = {0.25, 0.5, 1.0, 2.0};

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
  /// Nominal hoop stress of the wall away from load application: at the minor axis (90° from the major axis) in the
  /// profile's plane, split into bending (outer − inner)/2 and membrane (outer + inner)/2, and the thin
  /// (inextensible) ring theory's bending stress there for the same w0 and the same wall (inner radius to the rim's
  /// outer radius). The extremes above are the local peaks, where the generator touches or at the clamp side.
  double nominal_angle_deg = 90, nominal_bending_Pa = 0, nominal_membrane_Pa = 0, ring_theory_bending_Pa = 0;
};

/// Closed form of the cup's torsional rotation at the reading plane, term by term (SI): the diaphragm as an annular
/// plate in circumferential shear between the boss and the wall's mid-surface, φ = T/(4π·G·h)·(1/a² − 1/b²); the body
/// wall from the diaphragm's face to the rim, T·L/(G·J); the rim from its start to the reading plane with the rim's
/// J (inner radius to the rim's outer radius, teeth as the mesh's ring). A tube has no diaphragm term.
struct CupTorsionTheory {
  double diaphragm_rad = 0, body_rad = 0, rim_rad = 0;
  double total_rad() const { return diaphragm_rad + body_rad + rim_rad; }
  double diaphragm_inner_radius_m = 0, diaphragm_outer_radius_m = 0, body_length_m = 0, rim_length_m = 0;
  double rim_outer_radius_m = 0;
};
CupTorsionTheory cup_torsion_theory(const FlexsplineParams& f, double rim_outer_radius_m, const Material& material,
                                    double torque_Nm, double reading_z_m);

/// Thin inextensible ring theory: hoop bending stress E·(t/2)·Δκ (Pa, tension on the outer fibre > 0) at angle `at_rad`
/// from the major axis of a ring of mid radius r_mid and thickness t, deformed by the generator to w(0) = w0: a cam's
/// w0·cos2θ gives Δκ = −(w'' + w)/r² = 3·w0·cos2θ/r²; given forces by their Fourier series.
double ring_theory_bending_stress(const WaveGeneratorParams& w, double youngs_modulus_Pa, double r_mid_m,
                                  double thickness_m, double w0_m, double at_rad);

/// What the generator does to the flexspline: contact forces per station, zones, totals.
struct GeneratorReadout {
  std::string model;                      ///< case key: "cam", "four_force", ...
  bool unilateral = false;                ///< contact (cam) or the force idealisation
  std::vector<double> station_angle_rad;  ///< first station of each pair (the other at + π)
  std::vector<double> force_wg_N;         ///< normal force per station, generator case (force models: empty)
  std::vector<double> force_comb_N;       ///< per station, generator + torque (force models: the torque case's support)
  std::vector<std::pair<double, double>> zones_wg_deg, zones_comb_deg;  ///< [from, to] from the major axis
  double total_radial_force_N = 0;        ///< generator case, whole circumference
  double min_contact_force_N = 0;         ///< smallest station (or point) force of the generator case
  double reaction_torque_Nm = 0;          ///< moment about z of the generator on the flexspline in the torque case
  double w_major_m = 0, w_minor_m = 0;    ///< generator case, neutral circle at the rim mid-width (mean of both ends)
  int contact_iterations = 0;             ///< outer iterations of the generator case (bearing secant, band turn)
  double bearing_max_ball_load_N = 0;     ///< cam with a bearing: the largest ball load (generator or combined case)
  double bearing_max_approach_m = 0;      ///< and its Hertzian approach δ_i + δ_o
  Eigen::VectorXd obstacle_m;             ///< unilateral: the standoff each station pair pushes against (m, summed)
};

/// The balances and closed forms the FEM's figures are checked against (written and printed beside them).
struct FemChecks {
  double applied_torque_Nm = 0;       ///< moment of the applied torque loads about z
  double reaction_torque_Nm = 0;      ///< moment about z of the clamp's and the generator's reactions (torque case)
  double phi0_theory_rad = 0;         ///< T·L/(G·J) of the body wall
  CupTorsionTheory phi0_theory_cup;   ///< body wall + diaphragm + rim, term by term
  double generator_rotation_rad = 0;  ///< net rim rotation of the generator-alone case (0 by symmetry)
  Eigen::Vector3d generator_net_force = Eigen::Vector3d::Zero();   ///< resultant of the generator loads (N)
  Eigen::Vector3d generator_net_moment = Eigen::Vector3d::Zero();  ///< and their moment about the origin (N·m)
};

/// What the solve cost: the factorisation's size, flops and times, the assembly and the load cases' solves.
struct FemTimings {
  FactorStats factor;
  double assemble_s = 0, solve_s = 0;
};

/// The flexspline's results, with their checks and what they cost beside them.
struct FlexsplineSolution {
  std::vector<LoadCaseSolution> cases;
  double torque_Nm = 0;
  double phi0_rad = 0;                ///< torque alone
  double compliance_rad_per_Nm = 0;   ///< φ₀ / T
  double phi0_engaged_rad = 0;        ///< mean rotation of the rim's neutral circle over the engagement zones
  double generator_force_N = 0;       ///< force of each of the generator's point loads after scaling
  double generator_w0_m = 0;          ///< major-axis radial displacement reached
  std::vector<std::pair<double, double>> torque_sweep;  ///< (T, φ₀/T) from the combined case at several torques
  std::optional<NeutralCurveSamples> neutral_curve;     ///< when there is a generator
  std::optional<GeneratorReadout> generator;
  std::optional<FatigueReadout> fatigue;  ///< over one generator revolution of the combined case (with a generator)
  HoopStressExtreme hoop;             ///< of the generator case if any, else of the torque case
  double reading_radius_m = 0, reading_z_m = 0;  ///< where φ₀ is read
  FemChecks checks;
  FemTimings timings;
};

/// Radius of the rim's neutral circle (mid-thickness under the teeth, or of the body wall for a plain tube).
double neutral_radius(const FlexsplineParams& f);

/// Consistent load vector (3·n_nodes, N) of the case's torque load (rim engagement zones, uniform rim, or the exact
/// torsion shear on a plain tube's open end), scaled to `torque_Nm`.
Eigen::VectorXd torque_load_vector(const FlexsplineModel& c, const TetMesh& mesh, double torque_Nm);

/// Least-squares rigid rotation about z (rad) of the reading ring of displacement field u (3·n_nodes): the open end
/// face of a plain tube, else 360 points on the rim's neutral circle at its mid-width.
double reading_rotation(const FlexsplineModel& c, const TetMesh& mesh, const Eigen::VectorXd& u);

/// The rim's curves (w, v, μ at 1° steps, in the *_wg fields) of displacement field u (3·n_nodes) on the neutral circle
/// at axial positions z_m (from the closed end): the neutral curves of other sections than the rim's mid-width.
std::vector<NeutralCurveSamples> neutral_curves_at(const FlexsplineModel& c, const TetMesh& mesh,
                                                   const Eigen::VectorXd& u, const std::vector<double>& z_m);

/// Solves every load case of the flexspline on one factorisation and extracts φ₀, C_τ, the neutral curve and
/// stresses. The mesh must come from mesh_flexspline for the same parameters.
FlexsplineSolution analyse_flexspline(const FlexsplineModel& c, const TetMesh& mesh);
/// The same on a system already factorised for this case and mesh (kept for later stages, e.g. the tooth contact).
FlexsplineSolution analyse_flexspline(const FlexsplineModel& c, const TetMesh& mesh, const FlexsplineSystem& system);

}  // namespace sw
