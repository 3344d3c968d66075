#pragma once
// Option structs of a case, SI units. Shared by every stage (mesh, fem, kinematics, dynamics) without depending on
// the TOML parser, which lives in io/case.hpp and fills them.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "contact/circular_spline.hpp"    // CircularSplineParams (standard library and gear/gear.hpp only)
#include "fem/generator_bearing.hpp"  // GeneratorBearing (standard library only)
#include "gear/gear.hpp"

namespace sw {

struct DynamicsParams;  // dynamics/dynamics_params.hpp

enum class FlexsplineShape { Cup, Tube };
enum class TeethModel { None, Ring, Explicit };
/// FourForce, TwoForce, Forces: the seed paper's idealisation (given forces, no generator body). Cam, Rollers: bodies
/// that push and never pull (frictionless unilateral contact on the generator band; rollers: rigid, at ±β from both
/// ends of the major axis, set out so the major axis reaches w0).
enum class WaveGeneratorModel { FourForce, TwoForce, Forces, Cam, Rollers };
/// The case key's spelling of a generator model ("four_force", "two_force", "forces", "cam", "rollers").
inline const char* model_name(WaveGeneratorModel m) {
  static const char* kNames[] = {"four_force", "two_force", "forces", "cam", "rollers"};
  return kNames[static_cast<int>(m)];
}
/// The cam's outer surface: polar r + w0·cos2φ (the first-order shape the linear model works in; the default), a
/// true ellipse of semi-axes r + w0 and r − w0 (inside the polar form by up to 1.5·w0²/r at ±45°), or a list of radii
/// against angle over a half turn (fem/cam_profile.hpp).
enum class CamProfile { Polar, Ellipse, List };
enum class TorqueLoading { EngagementZones, Uniform };

struct FlexsplineParams {
  FlexsplineShape shape = FlexsplineShape::Cup;
  double inner_radius_m = 18.4e-3;
  double wall_thickness_m = 0.6e-3;     ///< body wall
  double length_m = 20.0e-3;            ///< clamped end (or diaphragm) to the open end
  double rim_width_m = 6.0e-3;          ///< axial width of the toothed rim at the open end
  double rim_thickness_m = 0.7e-3;      ///< radial thickness under the teeth
  TeethModel teeth = TeethModel::Ring;
  double diaphragm_thickness_m = 1.0e-3;  ///< cup only
  double boss_radius_m = 8.0e-3;          ///< cup only: clamped hub
  double fillet_radius_m = 1.0e-3;        ///< cup only
};

struct Material {
  double youngs_modulus_Pa = 210e9;
  double poisson_ratio = 0.3;
  double density_kg_m3 = 7850.0;
  std::optional<double> fatigue_limit_Pa;      ///< endurance limit (fully reversed) for the Goodman safety factor
  std::optional<double> ultimate_strength_Pa;  ///< tensile strength, the Goodman line's intercept
  double shear_modulus_Pa() const { return youngs_modulus_Pa / (2.0 * (1.0 + poisson_ratio)); }
};

struct WaveGeneratorForce {
  double angle_rad = 0.0;  ///< from the major axis
  double weight = 1.0;
};

/// A point of a listed cam: the radius of the generator's surface that touches the bore, at an angle from the major
/// axis.
struct CamPoint {
  double angle_rad = 0.0;
  double radius_m = 0.0;
};

struct WaveGeneratorParams {
  WaveGeneratorModel model = WaveGeneratorModel::FourForce;
  double beta_rad = 0.5235987755982988;          ///< four_force, rollers: ±β from the major axis at both ends of it
  std::optional<double> radial_deformation_m;    ///< w0 at the major axis; forces are scaled to reach it
  double force_N = 100.0;                        ///< total of one end's forces when w0 is not given
  double axial_position_m = 3.0e-3;              ///< from the open end
  double band_width_m = 4.0e-3;                  ///< axial width of the generator's contact band
  CamProfile cam_profile = CamProfile::Polar;    ///< cam only
  double cam_clearance_m = 0.0;                  ///< cam only: radial fit to the bore, clearance > 0, interference < 0
  std::vector<CamPoint> cam_points;              ///< cam_profile = List: angles in [0, π), increasing
  std::vector<WaveGeneratorForce> forces;        ///< model = forces
  /// The ball bearing between the cam and the flexspline (fem/generator_bearing.hpp); absent: a rigid generator.
  std::optional<GeneratorBearing> bearing;
};

struct LoadParams {
  double torque_Nm = 0.0;
  TorqueLoading torque_loading = TorqueLoading::EngagementZones;
  double engagement_half_angle_rad = 0.3490658503988659;  ///< ± around each end of the major axis (20°)
  /// The torque the contact stage loads to, both ways (N·m): the case's key, else the catalog's rated torque of
  /// [catalog] size; absent when neither gives one.
  std::optional<double> rated_torque_Nm;
  std::string rated_torque_from;  ///< "the case file" or "catalog size N" (empty when absent)
};

struct MeshParams {
  double size_m = 0.6e-3;    ///< target edge length away from thin walls
  int wall_layers = 2;       ///< minimum TET10 layers through any wall
  /// Refinement toward a cup's clamp corners (the boss meets the free diaphragm faces; the field is singular there):
  /// the edge length at the corners is the diaphragm's layer thickness halved this many times, growing away from
  /// them. -1: each solver's default (TET10: none, mesh/flexspline.hpp; harmonic section: 2 + ceil(log2 layers),
  /// fem/fourier_section.cpp); 0: none. Both solvers (the TET10 size field, the graded harmonic section).
  int corner_levels = -1;
  double min_dihedral_deg = 0.0;      ///< TetGen quality switch (0 = TetGen default)
  double max_radius_edge_ratio = 2.0; ///< TetGen -q bound
};

enum class SolverMethod { Tet10, Fourier };
/// Where the TET10 equations are factorised: CHOLMOD in this process, or PETSc on the MPI ranks of an mpirun launch.
enum class SolverBackend { Cholmod, Petsc };

/// How the flexspline is solved: 3-D quadratic tetrahedra (any shape), or, for a body of revolution (teeth "ring" or
/// "none"), the meridian section with circumferential harmonics 0..harmonics (exact in θ up to that order).
struct SolverParams {
  SolverMethod method = SolverMethod::Tet10;
  int harmonics = 64;  ///< fourier only: highest circumferential harmonic kept
  SolverBackend backend = SolverBackend::Cholmod;  ///< tet10 only
};

/// A whole case: what to mesh, load and solve.
struct Case {
  std::string path;      ///< the file it came from (for messages)
  std::string stem;      ///< file name without directory and extension (default output folder)
  std::optional<GearParams> gear;
  FlexsplineParams flexspline;
  Material material;
  std::optional<WaveGeneratorParams> wave_generator;
  LoadParams load;
  MeshParams mesh;
  SolverParams solver;
  /// [catalog] size: the catalog size the case stands for (a row of design/catalog.hpp).
  std::optional<int> catalog_size;
  /// [circular_spline]: the given keys, else the defaults of contact/circular_spline.hpp; absent without [gear].
  std::optional<CircularSplineParams> circular_spline;
  /// [contact] face_slices: axial slices of the toothed face in the loaded contact (contact/loaded_contact.hpp
  /// ContactOptions::face_slices); 1, the default: the face as one contact at its centre section.
  int contact_face_slices = 1;
  /// [dynamics]: the dynamics stage's own options (dynamics/dynamics_params.hpp), null when the table is absent.
  /// Held by pointer so that this header does not depend on a later stage.
  std::shared_ptr<const DynamicsParams> dynamics;
};

}  // namespace sw
