#pragma once
// The elastic material of the drive's steel parts (the case file's [material] table), SI units. A value every stage
// reads (the teeth, the flexspline's FEM, the multibody model); it depends on no stage.
#include <optional>

namespace sw {

struct Material {
  double youngs_modulus_Pa = 210e9;
  double poisson_ratio = 0.3;
  double density_kg_m3 = 7850.0;
  std::optional<double> fatigue_limit_Pa;      ///< endurance limit (fully reversed) for the Goodman safety factor
  std::optional<double> ultimate_strength_Pa;  ///< tensile strength, the Goodman line's intercept
  std::optional<double> yield_strength_Pa;     ///< 0.2 % proof stress: the flexspline's first yield (momentary limit)
  double shear_modulus_Pa() const { return youngs_modulus_Pa / (2.0 * (1.0 + poisson_ratio)); }
};

}  // namespace sw
