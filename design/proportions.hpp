#pragma once
// A cup-type strain wave gear for a catalog size from one set of proportions: every length is a fixed multiple of the
// pitch diameter d = size × 2.54 mm (or of the module m = d/z_f), the tooth numbers follow from the ratio, and nothing
// is tuned per size. Each rule and where it comes from is in proportions.cpp beside the rule and in the header
// comment of the written case. Since all lengths scale with d, the drive of one ratio is the same shape at every size;
// the teeth's geometry in modules depends on the ratio alone.
#include <string>

#include "common/material.hpp"
#include "contact/circular_spline.hpp"
#include "gear/gear.hpp"
#include "generator/wave_generator.hpp"
#include "mesh/flexspline_params.hpp"

namespace sw {

/// Sizes and ratios `strainwave design` accepts: the component sets' sizes 8–65 and the catalog ratios 50–160
/// (z_f = 2·ratio; the short-tooth rule is verified against interference over this range of ratios).
inline constexpr int kDesignSizeMin = 8, kDesignSizeMax = 65;
inline constexpr int kDesignRatioMin = 50, kDesignRatioMax = 160;

/// Everything the written case holds (SI), with where the rated torque came from.
struct CupDesign {
  int size = 0;
  int ratio = 0;
  double pitch_diameter_m = 0;  ///< z_f·m = size × 2.54 mm
  GearParams gear;
  FlexsplineParams flexspline;
  Material material;
  WaveGeneratorParams wave_generator;  ///< cam, w0 = m, with its bearing
  CircularSplineParams circular_spline;
  double rated_torque_Nm = 0;
  std::string rated_torque_from;  ///< "catalog size 17 (CSG, ratio 100)" or the scaling used
};

/// The design of a size (kDesignSizeMin..kDesignSizeMax) and ratio (kDesignRatioMin..kDesignRatioMax). Throws
/// InputError "--size 7; must be an integer in [8, 65] ..." for a size or ratio outside them.
CupDesign design_cup(int size, int ratio);

/// The design as a case file (TOML, lengths in mm) with a header comment naming the source of every proportion.
/// It loads with io/case.hpp's load_case and passes the flexspline, gear and bearing validation.
std::string design_case_toml(const CupDesign& d);

}  // namespace sw
