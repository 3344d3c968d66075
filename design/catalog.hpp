#pragma once
// Published data of cup-type harmonic drives by catalog size (shared/reference/catalog_torsional_stiffness.md: the
// CSF/CSG component sets, ratio >= 80): pitch diameter, the three-segment torsional stiffness and the rated torque.
// One table for every stage that names a catalog size (design, the case's [catalog] key, contact, reconcile).
#include <optional>
#include <string>
#include <vector>

namespace sw {

/// One catalog size. SI except torques (N*m) and stiffnesses (N*m/rad), as the catalog gives them.
struct CatalogDrive {
  int size = 0;                    ///< the size number: pitch diameter in tenths of an inch
  double pitch_diameter_m = 0;     ///< approximate, as the reference lists it
  double t1_Nm = 0, t2_Nm = 0;     ///< breakpoints of the three-segment law
  /// Segment stiffnesses K1, K2, K3; 0 where the reference lists none (sizes 25 and 32).
  double k1_Nm_per_rad = 0, k2_Nm_per_rad = 0, k3_Nm_per_rad = 0;
  /// Rated torque at ratio 100 (CSG rating; CSF about 30 % lower); 0 where the reference lists none (size 32).
  double rated_torque_Nm = 0;
  bool has_stiffness() const { return k1_Nm_per_rad > 0; }
  bool has_rated_torque() const { return rated_torque_Nm > 0; }
};

/// Published strength, life and loss figures of one catalog size (shared/reference/catalog_strength_life_losses.md:
/// the CSF/CSG component sets; the losses from another maker's ratio-100 cup sets at 20 °C with grease). N·m unless
/// named otherwise; 0 where the reference lists none.
struct CatalogLimits {
  int size = 0;
  /// Ratcheting torque with the wave generator fixed, at the ratios listed (ratio, CSF, CSG; 0: not offered).
  struct Ratcheting {
    int ratio = 0;
    double csf_Nm = 0, csg_Nm = 0;
  };
  std::vector<Ratcheting> ratcheting;
  double buckling_csf_Nm = 0, buckling_csg_Nm = 0;  ///< the flexspline, every ratio
  /// CSG at ratio 100: rated, limit for repeated peak, limit for average, limit for momentary peak.
  double rated_csg_Nm = 0, repeated_peak_csg_Nm = 0, average_csg_Nm = 0, momentary_csg_Nm = 0;
  /// L10 of the wave generator's bearing at rated torque and 2,000 rpm input (hours).
  double bearing_l10_csf_h = 7000, bearing_l10_csg_h = 10000;
  /// Ratio 100, 20 °C, grease: efficiency at rated torque and 2,000 rpm; no-load running torque (input, 2,000 rpm);
  /// starting torque (input); backdriving torque (output).
  double efficiency = 0, no_load_running_torque_Nm = 0, starting_torque_Nm = 0, backdriving_torque_Nm = 0;
  /// The published ratcheting torque at `ratio` (CSF when `csg` is false); 0 when the ratio is not listed.
  double ratcheting_Nm(int ratio, bool csg) const {
    for (const Ratcheting& r : ratcheting)
      if (r.ratio == ratio) return csg ? r.csg_Nm : r.csf_Nm;
    return 0;
  }
};

/// The published limits of a size (14, 17, 20); nullptr when the reference does not list them.
const CatalogLimits* catalog_limits(int size);

/// Every listed size, in increasing size: 14, 17, 20 (with stiffness), 25 and 32 (without).
const std::vector<CatalogDrive>& catalog_drives();

/// The row of a size; nullptr when the reference does not list it.
const CatalogDrive* catalog_drive(int size);

/// The published stiffness of a size at a reduction ratio: the size's row at ratio >= 80, the catalog's own rows at
/// ratios 30 and 50 (K1, K2, K3 at 30; K1, K2 at 50, where k3_Nm_per_rad is 0: not listed); T1 and T2 the size's at
/// every ratio. nullopt for a size without stiffness or a ratio the catalog does not list (31-49, 51-79).
std::optional<CatalogDrive> catalog_stiffness(int size, int ratio);

/// "14, 17, 20, 25, 32": the listed sizes, for messages.
std::string catalog_sizes_text();

}  // namespace sw
