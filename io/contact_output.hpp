#pragma once
// What `strainwave contact` writes: contact.json (its schema is ContactResult below, writer and reader side by side;
// beside the figures the case it ran and the tool's version, io/provenance.hpp), torque_twist.csv, contact.svg (the
// torque–twist curve with the catalog's three segments, and the force on every flank at ± rated torque).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "contact/accuracy_band.hpp"
#include "contact/loaded_contact.hpp"
#include "io/case.hpp"
#include "io/provenance.hpp"

namespace sw {

/// A catalog's three-segment law to set beside the computed one (the case's catalog size).
struct CatalogLaw {
  int size = 0, ratio = 0;
  double t1_Nm = 0, t2_Nm = 0, k1_Nm_per_rad = 0, k2_Nm_per_rad = 0, k3_Nm_per_rad = 0;
  SegmentLaw law() const { return {t1_Nm, t2_Nm, k1_Nm_per_rad, k2_Nm_per_rad, k3_Nm_per_rad}; }
};

/// contact.json, key by key in the file's own units (each member is named as its key).
struct ContactResult {
  struct Step {
    double torque_Nm = 0, twist_rad = 0;
    int pairs_in_contact = 0;
    double max_pair_force_N = 0;
    std::optional<std::string> branch;  ///< with friction: "loading" | "unloading"
  };
  /// With friction on the flanks: the load cycle's loop (torque_twist holds its two branches).
  struct Friction {
    double friction_coefficient = 0;
    int steps_per_quarter = 0, cycles = 0;
  };
  /// The three segments of the computed curve.
  struct Catalog {
    double T1_Nm = 0, T2_Nm = 0, K1_Nm_per_rad = 0, K2_Nm_per_rad = 0, K3_Nm_per_rad = 0;
    std::string breakpoints;  ///< "fitted to the curve" | "the catalog's T1 and T2"
  };
  /// The catalog's law of the case's size, and its twist at its breakpoints and at rated torque.
  struct CatalogReference {
    int size = 0, ratio = 0;
    double T1_Nm = 0, T2_Nm = 0, K1_Nm_per_rad = 0, K2_Nm_per_rad = 0;
    std::optional<double> K3_Nm_per_rad;  ///< absent where the catalog lists none (ratio 50)
    double twist_at_T1_rad = 0, twist_at_T2_rad = 0;
    std::optional<double> twist_at_rated_rad;  ///< absent without K3
  };
  struct FaceSection {
    double z_mm = 0, w_major_um = 0, first_closing_arcmin = 0, overlap_at_rest_um = 0, overlap_angle_deg = 0;
  };
  /// The body's share by its parts (fractions of the twist at rated torque, adding to Split::body).
  struct BodyParts {
    double wall = 0, rim = 0, diaphragm = 0, boss = 0;
  };
  struct Split {
    double engagement = 0, body = 0, teeth = 0, generator = 0, circular_spline = 0;
    std::optional<BodyParts> body_parts;  ///< absent in files written before the body was split
  };
  struct EdgeTooth {
    int tooth = 0;
    double angle_deg = 0;
    bool engaged_at_rest = false, contact_candidate = false;
    double radial_overlap_at_rest_um = 0, radial_overlap_min_um = 0, radial_overlap_max_um = 0;
    bool slips_over_the_tip = false, comes_into_mesh = false;
  };
  struct ZoneEdges {
    bool hold = true;
    std::vector<EdgeTooth> teeth;
    double torque_share_at_rated = 0;
    std::optional<double> twist_at_rated_without_them_arcmin;  ///< null when nothing else carries the torque
  };
  struct Flank {
    int tooth = 0, slice = 0;
    double angle_deg = 0;
    std::string flank;     ///< "ccw" | "cw"
    std::string touching;  ///< "flank on tip corner", ...
    bool beyond_tip_circle_at_rest = false;
    double closing_angle_rad = 0, lever_m = 0, contact_radius_m = 0, tooth_pair_compliance_m_per_N = 0;
    double force_at_plus_rated_N = 0, force_at_minus_rated_N = 0;
  };
  /// The drive's figures over drives whose teeth deviate within one ISO 1328-1 tolerance class (`contact
  /// --accuracy-class`), each as its smallest, median and largest over the drives (contact/accuracy_band.hpp Spread).
  struct AccuracyBand {
    std::string standard, deviations;  ///< the standard; how the deviations are drawn and what is left out
    int tolerance_class = 0, drives = 0;
    double single_pitch_tolerance_flexspline_um = 0, single_pitch_tolerance_circular_spline_um = 0;
    std::optional<std::string> outside_scope;
    Spread K1_Nm_per_rad, K2_Nm_per_rad, K3_Nm_per_rad, twist_at_rated_arcmin, lost_motion_arcmin, play_arcmin,
        preload_overlap_at_rest_um;
    std::optional<Spread> hysteresis_loss_arcmin;  ///< with friction: the flanks' part (the middle reading)
  };
  struct Timings {
    double setup = 0, influence = 0, contact = 0, check = 0;
  };
  struct Solver {
    std::string method;  ///< the flexspline body's model: "tet10" | "fourier"
  };

  std::string case_path;  ///< key "case_file": the case file the run read
  Provenance provenance;  ///< keys "case" (the resolved case) and "version"
  double rated_torque_Nm = 0;
  std::vector<Step> torque_twist;
  Catalog catalog;
  std::optional<CatalogReference> catalog_reference;
  double lost_motion_arcmin = 0, play_arcmin = 0, overlap_at_rest_um = 0, min_closing_angle_arcmin = 0;
  int face_slices = 1;
  std::vector<FaceSection> face_sections;
  double twist_at_rated_arcmin = 0, torque_balance_error_rel = 0, fem_reaction_torque_Nm = 0;
  Split compliance_split;
  ZoneEdges zone_edges;
  std::string generator_support;
  bool half_turn_pairs = false;
  std::vector<Flank> flanks;
  Timings timings_s;
  int unknowns = 0;
  Solver solver;
  std::optional<Friction> friction;
  std::optional<double> hysteresis_loss_arcmin, dissipated_energy_J, friction_work_J;  ///< with friction
  /// With friction: the hysteresis loss as a rig reads it (the output stays at the dead band's edge it arrives at).
  std::optional<double> rig_hysteresis_loss_arcmin;
  /// With friction: the loop's widest place (its width between the branches, and the torque where it is).
  std::optional<double> widest_loop_width_arcmin, widest_loop_width_at_Nm;
  std::optional<AccuracyBand> accuracy_band;
};

/// The band's figures as contact.json keeps them.
ContactResult::AccuracyBand accuracy_band_figures(const AccuracyBand& band);

/// The file's figures of a contact analysis of the case `c`. `reference`: the catalog's law of the case's size, if any.
ContactResult contact_result(const ContactAnalysis& a, const Case& c, const std::optional<CatalogLaw>& reference);

/// contact.json text.
std::string contact_json(const ContactResult& r);

/// Reads contact.json back. Throws InputError, one line naming the file, the key and the value, when the file is
/// missing, not JSON, or a key the writer always writes is missing or of another kind.
ContactResult read_contact_result(const std::filesystem::path& contact_json);

/// What the torsion baseline of `strainwave reconcile` reads of contact.json: the middle line of the torque–twist
/// loop, the rated torque and the breakpoints of `catalog`.
struct ContactCurve {
  TorqueTwist middle_line;
  std::optional<TorqueLoop> loop;  ///< the two branches, when the unloading branch spans a torque range (friction)
  double rated_torque_Nm = 0.0;
  double catalog_t1_Nm = 0.0, catalog_t2_Nm = 0.0;  ///< `catalog.T1_Nm`, `catalog.T2_Nm` when given, else 0
};

/// Reads `torque_twist` (a list of {torque_Nm, twist_rad, ...}), `rated_torque_Nm` and, when present, the breakpoints
/// of `catalog` of a contact.json, and nothing else (a file holding only them serves too). The list is the loading
/// branch (torque rising) followed, optionally, by the unloading branch (torque falling back); the result is their
/// middle line (contact/torque_twist.hpp middle_line) and, with both, the loop. Throws InputError, one line naming the file, the key and the
/// value: file missing or not JSON, key missing or not a number, rated torque <= 0, torque that falls on the loading
/// branch or rises on the unloading branch, fewer than two points.
ContactCurve read_contact_curve(const std::filesystem::path& contact_json);

/// The same from a contact.json's text (`name` names it in messages): the curve of a contact analysis held in memory
/// reads exactly as its file would.
ContactCurve parse_contact_curve(const std::string& contact_json_text, const std::string& name);

/// torque_twist.csv text: torque_Nm,twist_rad,twist_arcmin,pairs_in_contact,max_pair_force_N.
std::string torque_twist_csv(const ContactAnalysis& a);

/// contact.svg text: two plots stacked.
std::string contact_svg(const ContactAnalysis& a, const std::optional<CatalogLaw>& reference);

}  // namespace sw
