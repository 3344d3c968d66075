#pragma once
// The wave generator as a body that pushes and never pulls: frictionless unilateral contact between the generator and
// the flexspline's bore over the generator's band, solved on the influence coefficients of a few angular stations.
//
// Reduction: the band's contact pressure is a line load in angle, p(θ) = Σ_k p_k·hat_k(θ), uniform across the band's
// width; hat_k is the linear hat of half-width `spacing` about station θ_k (the hats sum to one, so a uniform pressure
// is represented exactly). Station k's unit load is 1 N of normal force spread that way (consistent nodal loads); its
// work-conjugate displacement f_kᵀu is the hat-weighted mean normal displacement of the bore at the station. The
// contact conditions hold at the stations: gap_k = f_kᵀu − s_k ≥ 0, p_k ≥ 0, p_k·gap_k = 0, with s_k how far out the
// generator's surface stands from the unloaded bore (first-order kinematics, like the solver).
// Symmetry: the generator and every torque loading are symmetric under a half turn about the axis, so the stations at
// θ and θ + π carry the same force and form one unknown (the gap condition holds on the pair's sum); this halves the
// solves. The mesh itself is not symmetric, which makes this an approximation at the level of the discretisation.
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "generator/generator_bearing.hpp"
#include "mesh/tet_mesh.hpp"

namespace sw {

struct BandStations {
  std::vector<double> angle_rad;      ///< first station of each pair (the other is at angle + π)
  double half_width_rad = 0;          ///< of each station's hat
  Eigen::SparseMatrix<double> loads;  ///< 3·n_nodes × pairs: 1 N of normal force at each of the pair's stations
};

/// Contact normal of the generator's surface at θ as its tilt from the radial direction: n ∝ e_r − tilt(θ)·e_θ
/// (tilt = ρ'(θ)/ρ(θ) for a surface ρ(θ); zero for a radial support or a roller at its own angle).
using NormalTilt = std::function<double(double theta_rad)>;

/// Station loads on the inner-wall (kSurfaceInner) faces whose centroid lies within `width_m`/2 of `z_m`.
/// Throws InputError when no face lies in the band.
BandStations band_stations(const TetMesh& mesh, double z_m, double width_m, const std::vector<double>& angles_rad,
                           double half_width_rad, const NormalTilt& tilt = {});

/// Result of a contact (or support) problem on the stations.
struct StationForces {
  Eigen::VectorXd force_N;  ///< normal force at each station of each pair (N, ≥ 0 for unilateral contact)
  Eigen::VectorXd gap_m;    ///< pair's gap (sum over its two stations, m; 0 where in contact)
  int iterations = 0;
};

/// Unilateral contact: p ≥ 0, C·p − b ≥ 0, complementary. C (pairs × pairs) is the symmetric positive definite
/// influence matrix (displacement per unit force), b = s − u_ext the gap the external loads leave, per pair.
/// Solved exactly (to round-off) as min ½pᵀCp − bᵀp over p ≥ 0 by the Lawson–Hanson active-set method; written
/// here because Eigen 3.4 (Debian 12) has no NNLS and the problem is small and dense (≤ 180 unknowns).
StationForces unilateral_contact(const Eigen::MatrixXd& C, const Eigen::VectorXd& b);

/// What the generator's contact has beyond the bare gaps of `unilateral_contact`:
///  - a compliance in series at each station (the generator bearing's balls): the pair's radial approach a(p) under
///    the pair's station force p (m, both stations summed; a(0) = 0, increasing), so gap = C·p + a(p) − b;
///  - the wave stays with the generator: the flexspline turns on the bearing, so a rigid turn χ of the band about the
///    axis leaves the gaps alone. In the linear model a turn moves each pair's normal displacement by m·χ (m = the
///    moment about z of the pair's unit load, non-zero where the normal is tilted): that part is taken out,
///    gap = C·p − m·χ + … with χ = χ_ext + h·p the band's turn (h: the band's turn per unit force of each pair).
///    Without it a locked non-circular cam would hold the rim's turn back with a stiffness it does not have.
struct GeneratorContactModel {
  std::function<double(double station_force_N)> approach_m;  ///< empty: a rigid generator
  Eigen::VectorXd turn_gap_m_per_rad;                        ///< m (empty: the gaps follow the band's turn)
  Eigen::VectorXd band_turn_rad_per_N;                       ///< h
};

/// The generator's contact with `model`: p ≥ 0, gap ≥ 0, p·gap = 0 with gap = C·p + a(p) − m·(χ_ext + h·p) − b.
/// Solved as a sequence of exact `unilateral_contact` problems: the series compliance on the secant a(p)/p (the
/// Kačanov iteration, monotone for a compliance a(p)/p that falls with p, as Hertz's p^(2/3) does) and the band's turn
/// from the last forces, to a relative change of the forces below 1e-12. Without a bearing and without m it is
/// `unilateral_contact(C, b)` exactly. `gap_m` is the full gap; `iterations` counts the outer steps.
StationForces generator_contact(const Eigen::MatrixXd& C, const Eigen::VectorXd& b, double band_turn_ext_rad,
                                const GeneratorContactModel& model);

/// The pair's approach of a ball bearing between the generator and the bore: the pressure of stations `spacing_rad`
/// apart smeared over the balls (ball load Q = p·2π/(balls·spacing), an idealisation: the balls are discrete),
/// 2·δ(Q) for the pair, δ = δ(1 N)·Q^(2/3) (generator/generator_bearing.hpp, Hertz).
std::function<double(double)> bearing_pair_approach(const GeneratorBearing& bearing, double spacing_rad);
/// Ball load (N) of a station force (N) for stations `spacing_rad` apart.
double ball_load_N(const GeneratorBearing& bearing, double spacing_rad, double station_force_N);

/// Bilateral support: C·p = b (forces of either sign).
StationForces bilateral_support(const Eigen::MatrixXd& C, const Eigen::VectorXd& b);

/// Which pairs touch: a force above 1e-9 of the largest, or a gap (per station) within `touching_gap_m`. Inside a
/// zone where flexspline and generator conform, the pressure is small and its share among neighbouring stations is
/// set by sub-micrometre differences (the mesh's own asymmetry): the gap says they touch, the force alone would
/// fragment the zone.
std::vector<bool> touching(const StationForces& s, double touching_gap_m);

/// Angular zones (degrees from the major axis, in [−180, 180)) of touching pairs, each as [from, to] station angles,
/// over the whole circumference (both stations of each pair); stations more than `step_rad` apart never join.
std::vector<std::pair<double, double>> contact_zones_deg(const std::vector<double>& pair_angle_rad,
                                                          const std::vector<bool>& touching, double step_rad);

}  // namespace sw
