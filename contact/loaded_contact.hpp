#pragma once
// Loaded tooth contact of a locked drive: the output (the flexspline's boss) turned against the fixed circular spline
// with the wave generator locked, the torque shared among the tooth pairs in the mesh zones, the drive's torque–twist
// curve from −rated to +rated torque.
//
// Model (contact/README.md has the derivation):
//  - Contacts: both flanks of every flexspline tooth in the mesh zones at the generator's angle, and the generator's
//    stations on the bore. A flank's gap at rest is the backlash module's exact closing angle times its moment arm,
//    on the FEM's own generator-deformed neutral curve (the rim as the generator leaves it).
//  - Body: the flexspline's influence coefficients from the one factorisation: each flank's force is a load pattern
//    on the rim's outer surface (a linear hat one tooth pitch wide, across the face width) along the flank's contact
//    normal, its tangential part scaled so the pattern's moment about the axis is the geometric moment arm; the
//    generator's stations as the FEM's generator contact (fem/generator_contact.hpp). Teeth and stations at θ and
//    θ + π form one unknown (the half-turn symmetry of the generator and of an even tooth count), as in the FEM.
//  - In series, on the diagonal: each tooth pair's own compliance (bending, foundation and flattening of both teeth;
//    gear/tooth_stiffness.hpp) and the generator bearing's Hertzian balls (nonlinear, iterated on the secant); the
//    circular spline's torsion adds T·C_cs to the twist.
//  - Generator: a cam or rollers in unilateral contact take part in the same contact problem (torque shifts their
//    contact); the paper's given forces hold the band radially at the stations (eliminated, bilateral).
//  - No friction: loading and unloading coincide; the loop's middle line is the curve itself.
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "common/params.hpp"
#include "contact/torque_twist.hpp"
#include "fem/flexspline_analysis.hpp"
#include "fem/flexspline_system.hpp"
#include "kinematics/backlash.hpp"
#include "mesh/tet_mesh.hpp"

namespace sw {

/// What acts in series with the flexspline body; an empty function (or 0) is a rigid part.
struct SeriesParts {
  /// Compliance of one tooth pair over the whole face width (m/N) at the contact radius on the flexspline tooth.
  std::function<double(double contact_radius_f_m)> tooth_pair_m_per_N;
  std::string teeth_source;  ///< what the tooth compliance comes from, for reports
  /// Approach of the generator bearing's races (m) under one ball's load (N), and the number of balls.
  std::function<double(double ball_load_N)> bearing_approach_m;
  int bearing_balls = 0;
  double circular_spline_rad_per_Nm = 0;  ///< torsion of the circular spline's body
};

struct ContactOptions {
  double rated_torque_Nm = 0;  ///< the curve runs from −rated to +rated
  int steps = 20;              ///< torque steps each way (beyond the two limits at zero)
  double wg_angle_rad = 0;     ///< where the generator is locked (0: a flexspline tooth on the major axis)
  SeriesParts series;
  /// Flanks closing more than this many body twists at rated torque (C_τ·T_R) after the first stay out; doubled until
  /// the twist at rated torque stays short of them.
  double reach_factor = 3.0;
  /// Catalog breakpoints (T1, T2) to read K1..K3 at; 0: fitted to the curve.
  double catalog_t1_Nm = 0, catalog_t2_Nm = 0;
};

/// One flank that can take part.
struct FlankContact {
  int tooth = 0;               ///< flexspline tooth index (its half-turn partner is tooth + z_f/2 when paired)
  double phi_rad = 0;          ///< material angle from the major axis
  Flank flank = Flank::Ccw;
  double closing_angle_rad = 0;  ///< rigid turn of the output that closes it (< 0: overlap at rest)
  double lever_m = 0;          ///< signed moment arm (> 0 ccw: closed by a positive turn)
  double contact_radius_m = 0;  ///< on the flexspline tooth, its own frame
  double compliance_m_per_N = 0;  ///< the tooth pair's own (series)
  ToothPart part_f = ToothPart::Flank, part_c = ToothPart::Flank;  ///< where the teeth touch (flank, tip corner)
};

struct TorqueStep {
  double torque_Nm = 0, twist_rad = 0;
  int pairs_in_contact = 0;       ///< tooth flanks carrying force (both partners of a half-turn pair counted)
  double max_pair_force_N = 0;
  double balance_error_rel = 0;   ///< |Σ moments − T| / |T|
  std::vector<double> flank_force_N;    ///< per FlankContact, at each of the pair's teeth
  std::vector<double> station_force_N;  ///< per generator station pair (unilateral generators)
};

/// Fractions of the twist at rated torque (sum 1): the tangent line at rated torque split by energy, its intercept
/// being the engagement (play taken up and pairs engaging progressively).
struct ComplianceSplit {
  double engagement = 0, body = 0, teeth = 0, generator = 0, circular_spline = 0;
};

struct ContactAnalysis {
  std::vector<FlankContact> flanks;
  bool half_turn_pairs = false;
  std::string generator_support;   ///< how the generator takes part
  std::vector<TorqueStep> steps;   ///< −rated … +rated, increasing torque, two steps at 0 (the limits)
  TorqueTwist curve;
  double rated_torque_Nm = 0;
  double play_rad = 0;             ///< jump of the curve at zero torque
  double lost_motion_rad = 0;      ///< catalog's: between ±4 % of rated on the middle line
  SegmentLaw catalog;
  ComplianceSplit split;
  double torque_balance_error_rel = 0;  ///< worst over the steps
  double fem_reaction_torque_Nm = 0;    ///< at +rated: the clamp's reaction to the contact forces in a direct FEM solve
  /// at +rated: the contacts' displacements from the influence coefficients against the direct FEM solve with the same
  /// nodal forces (largest difference over the largest displacement)
  double superposition_error_rel = 0;
  /// Wall clock: building the patterns and gaps, the influence coefficients, the torque steps, the independent check.
  double setup_s = 0, influence_s = 0, contact_s = 0, check_s = 0;
  int unknowns = 0;
  double reach_rad = 0;  ///< flanks closing this much later than the first on their side were left out
  double min_closing_rad = 0;  ///< smallest closing angle at rest over both sides (< 0: the teeth overlap at rest)
  double overlap_at_rest_m = 0;  ///< largest overlap at rest along a contact normal (0: none)
};

/// Checks that the case can be analysed (a [gear], a [wave_generator] with radial_deformation_mm, teeth "ring" or
/// "none", the tet10 solver) before any work is done. Throws InputError naming the file and what is missing.
void check_contact_case(const Case& c);

/// The contact analysis of a case with [gear], [wave_generator] and teeth = "ring", on the system its FEM solution
/// came from. Throws InputError for a case it cannot handle (no gear, explicit teeth, no flank in the mesh zone).
ContactAnalysis analyse_contact(const Case& c, const TetMesh& mesh, const FlexsplineSystem& system,
                                const FlexsplineSolution& fem, const ContactOptions& options);

}  // namespace sw
