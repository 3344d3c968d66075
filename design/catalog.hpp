#pragma once
// Published data of cup-type harmonic drives by catalog size (shared/reference/catalog_torsional_stiffness.md: the
// CSF/CSG component sets, ratio >= 80): pitch diameter, the three-segment torsional stiffness and the rated torque.
// One table for every stage that names a catalog size (design, the case's [catalog] key, contact, reconcile).
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

/// Every listed size, in increasing size: 14, 17, 20 (with stiffness), 25 and 32 (without).
const std::vector<CatalogDrive>& catalog_drives();

/// The row of a size; nullptr when the reference does not list it.
const CatalogDrive* catalog_drive(int size);

/// "14, 17, 20, 25, 32": the listed sizes, for messages.
std::string catalog_sizes_text();

}  // namespace sw
