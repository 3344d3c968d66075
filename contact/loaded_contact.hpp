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
//    on the rim's outer surface (hats one tooth pitch wide, across the face width): the contact force carried down a
//    rigid tooth, its force and its moment about the tooth's foot, with exactly the contact force's resultant; the
//    generator's stations as the FEM's generator contact (fem/generator_contact.hpp). Teeth and stations at θ and
//    θ + π form one unknown (the half-turn symmetry of the generator and of an even tooth count), as in the FEM.
//  - In series, on the diagonal: each tooth pair's own compliance (bending, foundation and flattening of both teeth;
//    gear/tooth_stiffness.hpp) and the generator bearing's Hertzian balls (nonlinear, iterated on the secant).
//  - Circular spline: an elastic ring held as it is mounted (contact/circular_spline.hpp); its displacement along each
//    flank's normal adds to the flexspline's, a block of the flanks' compliance.
//  - Generator: a cam or rollers in unilateral contact take part in the same contact problem (torque shifts their
//    contact); the paper's given forces hold the band radially at the stations (eliminated, bilateral).
//  - No friction: loading and unloading coincide; the loop's middle line is the curve itself.
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "fem/flexspline_model.hpp"
#include "contact/circular_spline.hpp"
#include "contact/contact_body.hpp"
#include "contact/contact_params.hpp"
#include "contact/contact_problem.hpp"
#include "contact/frictional_contact.hpp"
#include "contact/ratcheting.hpp"
#include "contact/tet10_body.hpp"
#include "contact/torque_twist.hpp"
#include "fem/flexspline_analysis.hpp"
#include "fem/flexspline_system.hpp"
#include "fem/loads.hpp"
#include "kinematics/backlash.hpp"
#include "mesh/tet_mesh.hpp"

namespace sw {

/// What acts in series with the flexspline body; an empty function (or 0) is a rigid part.
struct SeriesParts {
  /// Compliance of one tooth pair over the whole face width (m/N), loaded where the teeth touch: at these radii on the
  /// flexspline's tooth (its own frame) and on the circular spline's (0: the conjugate point).
  std::function<double(double contact_radius_f_m, double contact_radius_c_m)> tooth_pair_m_per_N;
  /// With more than one face section: the flexspline tooth's own part of tooth_pair_m_per_N (m/N over the whole face)
  /// and how a solid tooth shares a section's load with the others (contact/tooth_fem.hpp FaceCoupling::shape, n × n
  /// for n sections), which couples the flanks of one tooth across the face. Either empty: each section's spring on
  /// its own.
  std::function<double(double contact_radius_f_m)> flexspline_tooth_m_per_N;
  std::function<Eigen::MatrixXd(int sections)> face_shape;
  std::string teeth_source;  ///< what the tooth compliance comes from, for reports
  /// Approach of the generator bearing's races (m) under one ball's load (N), and the number of balls.
  std::function<double(double ball_load_N)> bearing_approach_m;
  int bearing_balls = 0;
  /// The circular spline's block for the flanks' patterns on it (contact/circular_spline.hpp): added to the flanks'
  /// compliance. Empty: a rigid circular spline.
  std::function<CircularSplineBlock(const std::vector<FlankPattern>& patterns)> circular_spline;
};

/// The flexspline model's tooth pair compliance over the rim's face width (m/N) at the two contact radii: the flexspline's tooth
/// from the explicit-tooth FEM with the ring model's own share taken off (contact/tooth_fem.hpp), the circular
/// spline's tooth (bending, foundation) and the flattening of both from gear/tooth_stiffness.hpp; the flexspline's
/// radius clamped to its active flank. Builds the FEM tooth once (two small slabs). Empty without a [gear]; the
/// flexspline tooth's part empty too with explicit teeth (the body holds them).
struct ToothCompliances {
  std::function<double(double contact_radius_f_m, double contact_radius_c_m)> pair_m_per_N;
  std::function<double(double contact_radius_f_m)> flexspline_tooth_m_per_N;  ///< its part of pair_m_per_N
};
ToothCompliances tooth_pair_compliance_of(const FlexsplineModel& model);

/// Where each tooth sits off its nominal place along its pitch circle (m, positive counter-clockwise): the pitch
/// deviations of manufacture (contact/accuracy_band.hpp draws them for an ISO 1328-1 class). A flexspline tooth's
/// deviation moves it along the rim as a turn of the output would (its flanks' gaps change by −lever·e/r); a circular
/// spline tooth's turns it about the axis (the gap changes by (p_c × n)·e/r at the contact point). Empty: exact teeth.
/// With the half-turn pairs (an even z_f) a tooth and its partner share one unknown: their deviations must agree.
struct ToothDeviations {
  std::vector<double> flexspline_m;       ///< z_f entries, or none
  std::vector<double> circular_spline_m;  ///< z_c entries, or none
};

struct ContactOptions {
  double rated_torque_Nm = 0;  ///< the curve runs from −rated to +rated
  int steps = 20;              ///< torque steps each way (beyond the two limits at zero)
  SeriesParts series;
  /// Flanks closing more than this many body twists at rated torque (C_τ·T_R) after the first stay out; doubled until
  /// the twist at rated torque stays short of them. That check sees the rigid turn only, while the rim's elastic
  /// deformation under load (the wave turning against the generator) closes flanks farther out too: on the designed
  /// size 17 at ratio 100, two flank pairs beyond 3 body twists close from 23 N·m on (K3 +0.07 %). The default keeps
  /// every flank in (infinity); a finite reach is for the multibody table, whose phases it keeps small.
  double reach_factor = std::numeric_limits<double>::infinity();
  /// The case's [contact] table (contact/contact_params.hpp). face_slices: sections of the face, its two ends and
  /// evenly between (contact/contact_body.hpp face_slice), each flank one contact per section (its own gap, the band
  /// of the face nearer to it than to another section as its load band and its share of the face's tooth stiffness,
  /// the sections' springs side by side: the trapezoid rule across the width); the gaps follow the cup's coning:
  /// each section's from the FEM's rim as the generator leaves it there (needs the solution's generator case);
  /// 1: the face width as one contact at its centre section.
  /// friction_coefficient: Coulomb's μ on the tooth flanks; > 0 adds the load cycle's loop (ContactAnalysis::friction).
  /// The generator's stations roll: frictionless. generator_angle_rad: where the generator is locked (0: a
  /// flexspline tooth on the major axis).
  ContactParams contact;
  /// Catalog breakpoints (T1, T2) to read K1..K3 at; 0: fitted to the curve.
  double catalog_t1_Nm = 0, catalog_t2_Nm = 0;
  /// The loop's torque steps a quarter cycle (T_R/n each; contact/README.md's step study on the size-17 cup).
  int loop_steps_per_quarter = 20;
  /// > 0: the ramp past rated torque to the ratcheting torque (contact/ratcheting.hpp), looked for up to this torque;
  /// 0: not computed.
  double ratcheting_ceiling_Nm = 0;
  ToothDeviations deviations;  ///< the teeth's pitch deviations (none: exact teeth)
};

/// One flank that can take part.
struct FlankContact {
  int tooth = 0;               ///< flexspline tooth index (its half-turn partner is tooth + z_f/2 when paired)
  int slice = 0;               ///< axial slice of the face width (ContactOptions::contact.face_slices)
  double phi_rad = 0;          ///< material angle from the major axis
  Flank flank = Flank::Ccw;
  double closing_angle_rad = 0;  ///< rigid turn of the output that closes it (< 0: overlap at rest)
  double lever_m = 0;          ///< signed moment arm (> 0 ccw: closed by a positive turn)
  double contact_radius_m = 0;  ///< on the flexspline tooth, its own frame
  double contact_radius_c_m = 0;  ///< on the circular spline's tooth
  double compliance_m_per_N = 0;  ///< the tooth pair's own (series), the tooth's other sections unloaded
  ToothPart part_f = ToothPart::Flank, part_c = ToothPart::Flank;  ///< where the teeth touch (flank, tip corner)
  /// Free at rest (the flexspline's tip short of the circular spline's tip circle, near a zone's edge); its gap is its
  /// exact closing turn like every other flank's.
  bool beyond_tip_circle = false;
};

/// The flank `side` of the tooth at material angle `phi_rad` (its clearance at rest `pc`) as a contact that can take
/// part: the tooth engaged, or free within two pitches of a mesh zone's edge (`near_edge`); its moment arm closing it
/// the right way; a finite exact closing turn. Fills everything but the tooth index and the pair's compliance.
/// Shared by the loaded contact and the multibody model's moving mesh, so both see the same flanks.
std::optional<FlankContact> candidate_flank(const BacklashModel& model, const NeutralCurve& curve,
                                            const PairClearance& pc, double phi_rad, Flank side, bool near_edge);

/// A tooth at an edge of a mesh zone, where the flexspline's tip just reaches past the circular spline's tip circle
/// (engaged) or just fails to (free). Whether it can touch at all is its radial overlap, which the rim's radial motion
/// under load changes; it is read at every step through a radial observer pattern at the tooth's tip.
struct EdgeTooth {
  int tooth = 0;
  double phi_rad = 0;
  bool engaged = false;                ///< at rest (a candidate for contact when engaged)
  double overlap_at_rest_m = 0;        ///< radial overlap |tip| − r_a,c at rest (< 0: clear of the tip circle)
  double overlap_min_m = 0, overlap_max_m = 0;  ///< over the torque steps (rest + the rim's radial displacement)
  /// Engaged and carrying force at a step where its overlap is gone: the tip would slip over the circular spline's
  /// tip, which the contact model (fixed contact normal) does not follow.
  bool slips = false;
  bool candidate = false;  ///< its flanks take part in the contact problem
  bool enters = false;  ///< no candidate, overlapping at some step: it would come into mesh
};

struct TorqueStep {
  double torque_Nm = 0, twist_rad = 0;
  std::string branch;             ///< on a friction loop: "loading" | "unloading"; empty on the frictionless curve
  int pairs_in_contact = 0;       ///< tooth flanks carrying force (both partners of a half-turn pair counted)
  double max_pair_force_N = 0;
  double balance_error_rel = 0;   ///< |Σ moments − T| / |T|
  std::vector<double> flank_force_N;    ///< per FlankContact, at each of the pair's teeth
  std::vector<double> station_force_N;  ///< per generator station pair (unilateral generators)
};

/// The drive's loop under the catalog's load cycle with friction on the flanks: from rest to +rated, then +rated →
/// −rated → +rated until a cycle repeats the one before (contact/frictional_contact.hpp run_steady_loop).
struct FrictionLoop : LoopFigures {
  double friction_coefficient = 0;
  int steps_per_quarter = 0, cycles = 0;
  std::vector<TorqueStep> steps;  ///< the last cycle: the loading branch (−rated → +rated), then the unloading one
  double seconds = 0;             ///< wall clock of the loop (its steps and readings)
};

/// Fractions of the twist at rated torque (sum 1): the tangent line at rated torque split by energy, its intercept
/// being the engagement (play taken up and pairs engaging progressively).
struct ComplianceSplit {
  double engagement = 0, body = 0, teeth = 0, generator = 0, circular_spline = 0;
  /// The body's share by its parts (their strain energy under the tangent's force increment): the cup's wall, the
  /// toothed rim (the face's axial range, its whole thickness, with the teeth as a layer when so modelled), the
  /// diaphragm and the boss; they add to `body`.
  double wall = 0, rim = 0, diaphragm = 0, boss = 0;
};

/// What the split's generator share counts, for the summary and the report. A bearing's balls (their Hertzian
/// approach, the only generator compliance the contact problem carries) give it a share > 0, and then its races and the
/// cam's plug are said to be rigid; a share of exactly 0 is a generator without compliance (a rigid cam, or the band
/// held at the given forces), said so instead of naming balls that are not there.
std::string generator_share_meaning(double generator_share);

/// The rim at a section of the toothed face, as the generator leaves it (the cup's coning: the deflection grows with
/// the distance from the diaphragm), and how the teeth sit there at rest.
struct FaceSection {
  double z_m = 0;               ///< from the closed end
  double w_major_m = 0;         ///< radial deflection at the major axis
  double first_closing_rad = 0; ///< smallest closing turn over the engaged flanks (< 0: they overlap at rest)
  double overlap_m = 0;         ///< largest overlap at rest along a contact normal (0: none)
  double overlap_phi_rad = 0;   ///< the tooth where it is (material angle from the nearer end of the major axis)
};

struct ContactAnalysis {
  std::vector<FlankContact> flanks;
  /// The face's diaphragm end, centre and open end (empty for a result read back without its load cases' fields).
  std::vector<FaceSection> face_sections;
  int face_slices = 1;
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
  /// at +rated: the torque the circular spline's mounting carries in a direct solve of its ring under the flank forces
  /// (the flanks' torque: the output's less the locked generator's share; 0 for a rigid circular spline)
  double circular_spline_torque_Nm = 0;
  /// at +rated: the contacts' displacements from the influence coefficients against the direct FEM solve with the same
  /// nodal forces (largest difference over the largest displacement)
  double superposition_error_rel = 0;
  /// Wall clock: building the patterns and gaps, the influence coefficients, the torque steps, the independent check.
  double setup_s = 0, influence_s = 0, contact_s = 0, check_s = 0;
  int unknowns = 0;
  std::string solver;  ///< the flexspline body's model: "tet10" | "fourier"
  double reach_rad = 0;  ///< flanks closing this much later than the first on their side were left out
  double min_closing_rad = 0;  ///< smallest closing angle at rest over both sides (< 0: the teeth overlap at rest)
  double overlap_at_rest_m = 0;  ///< largest overlap at rest along a contact normal (0: none)
  /// The teeth within three pitches of a mesh zone's edge, watched at every step (those within two take part, the free
  /// ones with their first-order gap); `zone_edges_hold` when no loaded engaged tooth loses its radial overlap and no
  /// tooth left out gains one (the candidate set is then the right one).
  std::vector<EdgeTooth> edges;
  bool zone_edges_hold = true;
  /// The teeth within two pitches of a mesh zone's edge at +rated torque: their flanks' share of the torque, and the
  /// twist with them left out (infinity when nothing else can carry it). Engaged a few µm deep or not at all at rest,
  /// they touch at their tips; on sharp corners (no [gear] tip rounding) they can carry much of the torque where a
  /// rounded tip would ride over: what of the curve rests on them.
  double edge_teeth_torque_share = 0;
  double twist_at_rated_without_edge_teeth_rad = 0;
  std::optional<FrictionLoop> friction;  ///< with friction on the flanks
  /// The ratcheting torque (ContactOptions::ratcheting_ceiling_Nm > 0), the teeth's overlap read on the rim and on
  /// the circular spline's ring.
  std::optional<Ratcheting> ratcheting;
  /// The problem solved at every step: flanks (in the order of `flanks`), then the generator's stations when they are
  /// unilateral (their λ 0, their gap the FEM's obstacle); the tooth pairs' compliance on the diagonal, the bearing's
  /// secant not. For the multibody model, which moves the teeth through it.
  ContactProblem problem;
};

/// What keeps the model from the loaded contact, in one sentence; empty when nothing does.
std::optional<std::string> contact_model_gap(const FlexsplineModel& model);

/// What the loaded contact reads of the flexspline's FEM: the generator-deformed neutral curve at the face's centre,
/// C_τ, the generator's model and its stations' obstacle, and the generator case's displacement field, from which the
/// face's other sections are read. A solution read back from result.json (`contact --fem`) has no field: null, and
/// the face is then taken at its centre only.
struct FemReadout {
  NeutralCurveSamples neutral_curve;
  double compliance_rad_per_Nm = 0;
  std::string generator_model;
  Eigen::VectorXd generator_obstacle_m;          ///< per station pair (unilateral generators)
  const Eigen::VectorXd* generator_u = nullptr;  ///< 3·n_nodes of the generator case; null: read back
};

/// The rim's neutral curve fitted to the FEM's samples of the generator case (its radius, w, v and μ): the curve the
/// teeth are placed on. `source` names it in reports.
NeutralCurve fem_neutral_curve(const NeutralCurveSamples& s, const std::string& source = "FEM");

/// The readout of a solved FEM with a generator; its field points into `s`, which must outlive it. Throws InputError
/// when the solution has no generator-deformed neutral curve.
FemReadout fem_readout(const FlexsplineSolution& s);

/// Checks that the model can be analysed (a [gear], a [wave_generator] with radial_deformation_mm, teeth "ring",
/// "layer" or "none") before any work is done. Throws InputError saying what is missing; the caller, which
/// knows the case file, puts its name in front (as for every InputError of this module).
void check_contact_model(const FlexsplineModel& model);

/// The contact analysis of a model with a gear, a wave generator and teeth = "ring", "layer" or "none", on the body its
/// FEM solution came from (contact/tet10_body.hpp, contact/harmonic_body.hpp). Throws InputError for a model it cannot
/// handle (no gear, explicit teeth, no flank in the mesh zone).
ContactAnalysis analyse_contact(const FlexsplineModel& model, const ContactBody& body, const FemReadout& fem,
                                const ContactOptions& options);
/// The same on the TET10 mesh and the system its FEM solution came from.
ContactAnalysis analyse_contact(const FlexsplineModel& model, const TetMesh& mesh, const FlexsplineSystem& system,
                                const FemReadout& fem, const ContactOptions& options);

}  // namespace sw
