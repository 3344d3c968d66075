#pragma once
// The drive's figures as a band over drives made to one ISO 1328-1 flank tolerance class: the teeth of each drive sit
// off their nominal places by pitch deviations drawn within the class, the loaded contact is solved for each, and the
// figures (K1, K2, K3, twist at rated torque, lost motion, play, hysteresis) are reported over the drives.
//
// The drawn deviations (an idealisation, stated in every report): each tooth's position along its pitch circle
// independent and uniform in ±f_pT/2 (gear/accuracy.hpp), so every single pitch deviation lies within f_pT and the
// cumulative within f_pT ≤ F_pT; the long-wave part of the cumulative deviation (runout, eccentricity) is left out: it
// turns one mesh zone against the other, which the contact's half-turn pairing cannot carry, and each drawn tooth's
// deviation is its half-turn partner's. Profile and helix deviations are left out. Seeds are fixed: the band is
// reproducible.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "contact/loaded_contact.hpp"
#include "gear/accuracy.hpp"
#include "gear/gear.hpp"

namespace sw {

/// One drive's deviations for the tolerances of its flexspline's and circular spline's teeth (µm as ISO 1328-1
/// gives them): positions uniform in ±f_pT/2, a tooth's equal to its half-turn partner's when z_f is even.
ToothDeviations draw_pitch_deviations(const GearParams& g, double single_pitch_flexspline_um,
                                      double single_pitch_circular_um, std::uint64_t seed);

struct AccuracyBand {
  int tolerance_class = 0, drives = 0;
  FlankTolerances flexspline, circular_spline;  ///< ISO 1328-1's tolerances of each gear's teeth
  std::optional<std::string> outside_scope;     ///< where the gears lie outside the standard's scope
  /// One per drive, in the order drawn (seed 1, 2, …).
  struct Drive {
    double k1_Nm_per_rad = 0, k2_Nm_per_rad = 0, k3_Nm_per_rad = 0;
    double twist_at_rated_rad = 0, lost_motion_rad = 0, play_rad = 0;
    double overlap_at_rest_m = 0;          ///< the largest preload at rest along a contact normal (0: none)
    std::optional<double> hysteresis_rad;  ///< with friction on the flanks: its part of the loss (the middle reading)
    int flanks_at_rated = 0;
  };
  std::vector<Drive> drive;
};

/// The band over `drives` drives of tolerance class `tolerance_class`: the loaded contact of `options` (whose own
/// deviations are replaced) solved once per drive on `body`. Throws InputError for a class outside 1–11 or fewer than
/// 2 drives.
AccuracyBand accuracy_band(const FlexsplineModel& model, const ContactBody& body, const FemReadout& fem,
                           const ContactOptions& options, int tolerance_class, int drives);

/// Smallest, median and largest of one figure over the band's drives.
struct Spread {
  double min = 0, median = 0, max = 0;
};
Spread spread(std::vector<double> values);

}  // namespace sw
