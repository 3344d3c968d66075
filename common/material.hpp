#pragma once
// The elastic material of the drive's steel parts (the case file's [material] table), SI units. A value every stage
// reads (the teeth, the flexspline's FEM, the multibody model); it depends on no stage. Its schema beside it.
#include <optional>
#include <string>
#include <vector>

#include "common/case_keys.hpp"

namespace sw {

struct Material {
  double youngs_modulus_Pa = 210e9;
  double poisson_ratio = 0.3;
  double density_kg_m3 = 7850.0;
  std::optional<double> fatigue_limit_Pa;      ///< endurance limit (fully reversed) for the Goodman safety factor
  std::optional<double> ultimate_strength_Pa;  ///< tensile strength, the Goodman line's intercept
  std::optional<double> yield_strength_Pa;     ///< 0.2 % proof stress: the flexspline's first yield (momentary limit)
  /// Hysteretic loss factor η (complex modulus E(1 + iη)): the flexspline's damping under the generator's wave. The
  /// default is the top of iron's bending loss factor, 2–6·10⁻⁴ (Cremer & Heckl, Structure-Borne Sound, 1988, table of
  /// material loss factors), a small-amplitude figure: at a flexspline's stresses steels damp more (Lazan, 1968).
  double loss_factor = 6e-4;
  double shear_modulus_Pa() const { return youngs_modulus_Pa / (2.0 * (1.0 + poisson_ratio)); }
};

/// The [material] table's schema (common/case_keys.hpp).
inline const std::vector<CaseKey<Material>>& material_keys() {
  using M = Material;
  static const std::vector<CaseKey<M>> keys = {
      number_key<M>("youngs_modulus_Pa", &M::youngs_modulus_Pa, 1, "Pa", above(0), "E of the steel parts"),
      number_key<M>("poisson_ratio", &M::poisson_ratio, 1, "", within(-1, 0.5, true, true), "nu"),
      number_key<M>("density_kg_m3", &M::density_kg_m3, 1, "kg/m^3", above(0), "for the bodies' inertias"),
      optional_number_key<M>("fatigue_limit_MPa", &M::fatigue_limit_Pa, 1e6, "MPa", above(0),
                             "fully reversed endurance limit (the Goodman line; with ultimate_strength_MPa)"),
      optional_number_key<M>("ultimate_strength_MPa", &M::ultimate_strength_Pa, 1e6, "MPa", above(0),
                             "tensile strength, the Goodman line's intercept (with fatigue_limit_MPa)"),
      optional_number_key<M>("yield_strength_MPa", &M::yield_strength_Pa, 1e6, "MPa", above(0),
                             "0.2 % proof stress: the flexspline's first yield, <= ultimate_strength_MPa"),
      number_key<M>("loss_factor", &M::loss_factor, 1, "", within(0, 1, false, true),
                    "hysteretic loss factor eta: the flexspline's damping under the generator's wave (iron 2-6e-4, "
                    "Cremer & Heckl)"),
  };
  return keys;
}

/// Checks the keys' ranges and that the Goodman line's two strengths come together, the fatigue limit below the
/// ultimate strength and the yield strength not above it. Throws InputError "material.<key> = value; ...".
inline void validate_material(const Material& m) {
  check_key_ranges(m, material_keys(), "material");
  auto mpa = [](double pa) { return key_value_text(file_units(pa, 1e6)); };
  if (m.fatigue_limit_Pa.has_value() != m.ultimate_strength_Pa.has_value())
    throw InputError("material.fatigue_limit_MPa and material.ultimate_strength_MPa go together (the Goodman line "
                     "needs both)");
  if (m.fatigue_limit_Pa && !(*m.fatigue_limit_Pa < *m.ultimate_strength_Pa))
    throw InputError("material.fatigue_limit_MPa = " + mpa(*m.fatigue_limit_Pa) +
                     "; must be < material.ultimate_strength_MPa = " + mpa(*m.ultimate_strength_Pa));
  if (m.yield_strength_Pa && m.ultimate_strength_Pa && !(*m.yield_strength_Pa <= *m.ultimate_strength_Pa))
    throw InputError("material.yield_strength_MPa = " + mpa(*m.yield_strength_Pa) +
                     "; must be <= material.ultimate_strength_MPa = " + mpa(*m.ultimate_strength_Pa));
}

}  // namespace sw
