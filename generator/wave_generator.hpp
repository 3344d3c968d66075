#pragma once
// The wave generator (the case file's [wave_generator] table), SI units: one of the seed paper's force idealisations
// (given forces, no generator body) or a body that pushes and never pulls (frictionless unilateral contact on the
// generator band), as a std::variant dispatched once per concern (the functions below, and the case reader): a model
// that is added and not handled somewhere does not compile.
#include <functional>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <Eigen/Core>

#include "common/case_keys.hpp"
#include "generator/cam_profile.hpp"
#include "generator/generator_bearing.hpp"

namespace sw {

struct WaveGeneratorForce {
  double angle_rad = 0.0;  ///< from the major axis
  double weight = 1.0;
};

inline constexpr double kDefaultBeta_rad = 0.5235987755982988;  ///< 30°

/// The seed paper's idealisation: four equal forces at ±β from both ends of the major axis.
struct FourForce {
  double beta_rad = kDefaultBeta_rad;
};
/// Two forces on the major axis.
struct TwoForce {};
/// The case's list of forces (angle, weight) at one end of the major axis.
struct GivenForces {
  std::vector<WaveGeneratorForce> forces;
};
/// Rigid rollers at ±β from both ends of the major axis, set out so that the major axis reaches w0.
struct Rollers {
  double beta_rad = kDefaultBeta_rad;
};
using GeneratorModel = std::variant<FourForce, TwoForce, GivenForces, Cam, Rollers>;

struct WaveGeneratorParams {
  GeneratorModel model = FourForce{};
  std::optional<double> radial_deformation_m;    ///< w0 at the major axis; forces are scaled to reach it
  double force_N = 100.0;                        ///< total of one end's forces when w0 is not given
  double axial_position_m = 3.0e-3;              ///< from the open end
  double band_width_m = 4.0e-3;                  ///< axial width of the generator's contact band
  /// The ball bearing between the cam and the flexspline (generator/generator_bearing.hpp); absent: a rigid generator.
  std::optional<GeneratorBearing> bearing;
};

/// The [wave_generator] table's schema (common/case_keys.hpp): which keys each model takes. The reader and writer of
/// io/case.cpp handle the model's own keys (its lists, the cam's profile, the bearing's table) themselves.
const std::vector<CaseKey<WaveGeneratorParams>>& wave_generator_keys();

/// The case key's spelling of the model ("four_force", "two_force", "forces", "cam", "rollers").
const char* model_name(const GeneratorModel& m);

/// A body that pushes and never pulls (cam, rollers): unilateral contact; false for the given forces.
bool pushes_only(const GeneratorModel& m);

/// The cam of a cam generator, else null.
inline const Cam* cam_of(const WaveGeneratorParams& w) { return std::get_if<Cam>(&w.model); }

/// Angles (from the major axis) and weights of the generator's point forces as the FEM applies them: four forces at
/// ±β at both ends (rollers: where they touch, for ring theory), two on the major axis, or the case's list. Throws
/// std::logic_error for a cam, whose forces come from its contact.
std::vector<WaveGeneratorForce> generator_forces(const WaveGeneratorParams& w);

/// The force on one point of the given forces per unit scale of their weights: 1/2 for the four forces (each end's
/// pair shares the end's force), 1 otherwise.
double point_force_share(const GeneratorModel& m);

/// Where a body generator meets the bore over a half turn (the other half is its mirror through the axis): the
/// stations' angles from the major axis, each one's normal tilt from the radial (a cam's surface; empty: radial) and
/// its obstacle, the generator's standoff from the bore at the station for both stations of a half-turn pair (a cam:
/// 2·its standoff; rollers: 2 per metre of set-out, scaled to w0 later; given forces: 0). Rollers touch at β and π − β;
/// a cam and the given forces' radial support have stations every `spacing_rad` from the major axis.
struct StationLayout {
  bool unilateral = false;
  std::vector<double> angle_rad;
  std::function<double(double)> tilt;
  Eigen::VectorXd obstacle_m;
};
StationLayout station_layout(const WaveGeneratorParams& w, double bore_radius_m, double spacing_rad);

}  // namespace sw
