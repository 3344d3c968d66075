#pragma once
// The circular spline as an elastic body in the loaded contact: the ring under its teeth (from the teeth's root circle
// out to its outer radius, over its axial width) as a body of revolution, solved by circumferential harmonics on its
// meridian section (fem/fourier_solver.hpp band_responses), held as the drive holds it:
//   - "outer": its outside cylinder fixed (a ring shrunk into a rigid housing bore: the stiff idealisation);
//   - "bolted_face": one end face (the one toward the flexspline's open end) held on the annulus between the bolt
//     circles (the housing's face under the bolts, every displacement fixed there), the rest free.
// Each tooth flank's force on the circular spline (the opposite of the flexspline's: +normal at the contact point on
// the circular spline's tooth) is carried down a rigid tooth to the ring's inner surface as the flexspline's is to its
// rim (contact/hat_patterns.hpp: hats one circular-spline pitch wide, exactly the force's resultant and its moment
// about the axis). Its work-conjugate displacement there, along the flank's normal, adds to the flexspline's: the
// circular spline's block of the contact's compliance. The teeth themselves stay in the tooth pair's compliance
// (gear/tooth_stiffness.hpp), in series. What it leaves out: the bolts' and the housing's own compliance (the held
// annulus is rigid and does not slip). SI units.
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "common/material.hpp"
#include "contact/contact_body.hpp"
#include "fem/fourier_section.hpp"
#include "fem/fourier_solver.hpp"
#include "gear/gear.hpp"

namespace sw {

enum class CircularSplineMounting { Outer, BoltedFace };

/// [circular_spline]: the ring's outer radius, its axial width and how it is held. Metres.
struct CircularSplineParams {
  double outer_radius_m = 0;
  double width_m = 0;
  CircularSplineMounting mounting = CircularSplineMounting::BoltedFace;
  double bolt_circle_inner_m = 0, bolt_circle_outer_m = 0;  ///< bolted_face: the held annulus on the end face
};

/// The [circular_spline] table's schema (common/case_keys.hpp); its ranges depend on [gear] (validate_circular_spline).
const std::vector<CaseKey<CircularSplineParams>>& circular_spline_keys();

/// "outer" | "bolted_face".
std::string to_string(CircularSplineMounting m);

/// Outer radius of the design rule, metres: 0.7 × the pitch diameter z_c·m (an outer diameter of about 1.4 pitch
/// diameters; our reading of the component sets' dimension tables, an estimate, not a drawing).
inline constexpr double kCircularSplineOuterDiameterPerPitchDiameter = 1.4;

/// The held annulus of the design rule, as fractions of the way from the teeth's root circle to the outer radius: the
/// bolt circle at 0.6 (the component sets' bolt holes sit a little outside the ring's middle) and the bolt heads' and
/// housing's footprint ±0.2 of the ring's depth about it (about a bolt diameter: M3 on size 17, M4 on size 25). An
/// estimate from the component sets' outline drawings, not a drawing.
inline constexpr double kBoltCircleInnerFraction = 0.4, kBoltCircleOuterFraction = 0.8;

/// The held annulus of the rule (inner, outer radius; metres) on a ring from root_radius_m to outer_radius_m.
std::pair<double, double> default_bolt_circles_m(double root_radius_m, double outer_radius_m);

/// The default of an absent [circular_spline] table or key: outer radius and bolt circles by the rules above, width =
/// the flexspline's toothed face width (the teeth the ring carries; the soft estimate: a real ring is wider than its
/// teeth), mounted by its bolted face (as a catalog drive's circular spline is, and as its stiffness is measured).
CircularSplineParams default_circular_spline(const GearParams& gear, double face_width_m);

/// Checks width_m > 0, outer_radius_m > root_radius_m (the circular spline's root circle) and, bolted on its face,
/// root_radius_m <= bolt_circle_inner_m < bolt_circle_outer_m <= outer_radius_m. Throws InputError
/// "circular_spline.outer_radius_mm = 20; must be > the circular spline's root radius 21.9 mm (from [gear])", prefixed
/// by `file`.
void validate_circular_spline(const CircularSplineParams& c, double root_radius_m, const std::string& file = "");

/// The ring solved once for the loaded contact: its section, the nodes its mounting holds, and the responses of its
/// inner surface (the whole width, then each of `slices` axial slices when more than one) for harmonics 0..harmonics.
struct CircularSplineRing {
  SectionMesh section;        ///< r from the root circle to the outer radius, z from the face toward the cup's
                              ///< diaphragm (0) to the one toward its open end (width)
  std::vector<bool> held;     ///< per node
  std::vector<BandResponse> bands;
  Material material;
  double pitch_rad = 0;       ///< 2π/z_c: the hats' half-width
  int harmonics = 0;
  int slices = 1;
};

/// Harmonics per circular-spline tooth the ring is solved with: a hat one pitch wide has its spectrum's main lobe up
/// to n = z_c. Measured on the size-17 ring (z_c = 202), held either way: the block's diagonal at N = z_c is within
/// 0.02 % (radial force) and 0.25 % (tangential) of N = 4·z_c's, off the diagonal within 0.01 %; at N = z_c/2 it is
/// 1 % and 9 % short (the tangential pattern's couple is two hats half as wide).
inline constexpr int kCircularSplineHarmonicsPerTooth = 1;

/// The ring of `c` (validated against the gear's root circle) for the gear `g` (its root circle, z_c, and z_f's
/// parity: odd harmonics only for an odd z_f, whose flanks have no half-turn partner), of material `m`, its inner
/// surface cut into `slices` axial slices as the flexspline's face (contact/contact_body.hpp face_slice_m, scaled to
/// the ring's width). `harmonics` ≤ 0: kCircularSplineHarmonicsPerTooth·z_c. Throws InputError for a ring that fails
/// validate_circular_spline.
CircularSplineRing circular_spline_ring(const CircularSplineParams& c, const GearParams& g, const Material& m,
                                        int slices = 1, int harmonics = 0);

/// The circular spline's part of the loaded contact for a list of flank patterns.
struct CircularSplineBlock {
  /// flanks × flanks (m/N): the work-conjugate displacement of each pattern per unit force of each, symmetric
  Eigen::MatrixXd A;
  /// N·m per N: the moment about the axis of each pattern's load on the ring (the torque it carries)
  Eigen::VectorXd moment_m;
  /// The torque the ring puts on its mounting under forces x (per pattern), from a direct solve of the ring: the
  /// mounting's reaction, K₀·u − F on the held nodes. Equals moment_mᵀx (the flanks' torque) to round-off. The ring
  /// must outlive it.
  std::function<double(const Eigen::VectorXd& x)> mounting_torque_Nm;
};

/// The block of `patterns` on the ring: each one flank's unit force on the circular spline (force_dir: +normal at the
/// contact point, contact_radius_m: its radius on the circular spline's tooth, stations_rad: that point's angle and
/// its half-turn partner's, slice: its axial slice or −1). Throws std::logic_error for a slice the ring was not cut
/// into.
CircularSplineBlock circular_spline_block(const CircularSplineRing& ring, const std::vector<FlankPattern>& patterns);

}  // namespace sw
