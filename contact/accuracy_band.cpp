#include "contact/accuracy_band.hpp"

#include <algorithm>
#include <random>

#include "common/error.hpp"
#include "common/progress.hpp"

namespace sw {

ToothDeviations draw_pitch_deviations(const GearParams& g, double fpt_f_um, double fpt_c_um, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(-0.5, 0.5);
  const bool paired = g.teeth_flexspline % 2 == 0;
  const auto draw = [&](int z, double fpt_um) {
    std::vector<double> e(z);
    const int n = paired ? z / 2 : z;
    for (int k = 0; k < n; ++k) e[k] = unit(rng) * fpt_um * 1e-6;
    for (int k = n; k < z; ++k) e[k] = e[k - n];
    return e;
  };
  ToothDeviations d;
  d.flexspline_m = draw(g.teeth_flexspline, fpt_f_um);
  d.circular_spline_m = draw(g.teeth_circular, fpt_c_um);
  return d;
}

AccuracyBand accuracy_band(const FlexsplineModel& model, const ContactBody& body, const FemReadout& fem,
                           const ContactOptions& options, int tolerance_class, int drives) {
  if (drives < 2) throw InputError("an accuracy band needs at least 2 drives, not " + std::to_string(drives));
  const GearParams& g = *model.gear;
  const double m_mm = g.module_m * 1e3;
  const double d_f = m_mm * g.teeth_flexspline, d_c = m_mm * g.teeth_circular;
  AccuracyBand band;
  band.tolerance_class = tolerance_class;
  band.drives = drives;
  band.flexspline = iso1328_tolerances(d_f, m_mm, tolerance_class);
  band.circular_spline = iso1328_tolerances(d_c, m_mm, tolerance_class);
  band.outside_scope = iso1328_scope(d_f, m_mm);
  ContactOptions o = options;
  o.ratcheting_ceiling_Nm = 0;  // the band is the curve's; the ramp past rated is the nominal drive's
  for (int i = 1; i <= drives; ++i) {
    progress("accuracy band: drive " + std::to_string(i) + " of " + std::to_string(drives));
    o.deviations = draw_pitch_deviations(g, band.flexspline.single_pitch_um, band.circular_spline.single_pitch_um,
                                         static_cast<std::uint64_t>(i));
    const ContactAnalysis a = analyse_contact(model, body, fem, o);
    AccuracyBand::Drive d;
    d.k1_Nm_per_rad = a.catalog.k1_Nm_per_rad;
    d.k2_Nm_per_rad = a.catalog.k2_Nm_per_rad;
    d.k3_Nm_per_rad = a.catalog.k3_Nm_per_rad;
    d.twist_at_rated_rad = a.curve.twist_rad.back();
    d.lost_motion_rad = a.lost_motion_rad;
    d.play_rad = a.play_rad;
    d.overlap_at_rest_m = a.overlap_at_rest_m;
    if (a.friction) d.hysteresis_rad = a.friction->hysteresis_loss_rad;
    d.flanks_at_rated = a.steps.back().pairs_in_contact;
    band.drive.push_back(d);
  }
  return band;
}

Spread spread(std::vector<double> v) {
  if (v.empty()) return {};
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  const double median = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
  return {v.front(), median, v.back()};
}

}  // namespace sw
