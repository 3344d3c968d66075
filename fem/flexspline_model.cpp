#include "fem/flexspline_model.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "common/constants.hpp"

namespace sw {

double station_spacing(const FlexsplineModel& c) {
  const double two_edges_deg = 2 * c.mesh.size_m / c.flexspline.inner_radius_m * 180 / kPi;
  const double n = std::round(180.0 / std::clamp(two_edges_deg, 2.0, 6.0));
  return kPi / n;
}

namespace {

constexpr int kBaseHarmonics = 64;

/// The three needs of default_harmonics: the base, the stations', the teeth's.
std::array<int, 3> harmonic_needs(const FlexsplineModel& c) {
  std::array<int, 3> need{kBaseHarmonics, 0, 0};
  if (c.wave_generator && c.flexspline.inner_radius_m > 0 && c.mesh.size_m > 0)
    need[1] = 2 * static_cast<int>(std::lround(kPi / station_spacing(c)));
  if (c.gear && c.gear->teeth_flexspline > 0 && c.flexspline.rim_width_m > 0)  // a toothed face: the contact's
    need[2] = (c.gear->teeth_flexspline + 1) / 2;
  return need;
}

}  // namespace

int default_harmonics(const FlexsplineModel& c) {
  const auto need = harmonic_needs(c);
  return std::max({need[0], need[1], need[2]});
}

std::string default_harmonics_origin(const FlexsplineModel& c) {
  const auto need = harmonic_needs(c);
  return "the largest of " + std::to_string(need[0]) + " (the base), " + std::to_string(need[1]) +
         " (two per generator station pair) and " + std::to_string(need[2]) +
         " (z_f/2: the teeth's flank patterns in the loaded contact)";
}

}  // namespace sw
