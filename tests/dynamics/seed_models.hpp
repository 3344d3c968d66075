#pragma once
// Models used by the dynamics tests, built in code from the case defaults (the seed-1 gear 190/192 and the paper's
// small gear 26/28), so the tests do not depend on the case parser.
#include <numbers>

#include "dynamics/model.hpp"

namespace sw::test {

/// Seed-1 gear: module 0.2 mm, z_f = 190, z_c = 192, cup flexspline of the SPEC example; the paper's drive and contact.
inline DynamicsModel seed_model(DynamicsConfiguration config = DynamicsConfiguration::CsFixed) {
  DynamicsModel m;
  GearParams g;  // 190/192, m = 0.2 mm, α = 20°
  FlexsplineParams fs;
  Material mat;
  m.params.configuration = config;
  m.teeth_flexspline = g.teeth_flexspline;
  m.teeth_circular = g.teeth_circular;
  m.inertia = body_inertias(g, fs, true, mat, m.params);
  const double w0 = g.module_m * (g.teeth_circular - g.teeth_flexspline) / 2.0;
  m.pairs = approximate_tooth_pairs(g, w0, 20.0 * std::numbers::pi / 180.0, 0.0);
  return m;
}

/// The paper's small gear with the tooth numbers put right: z_f = 26, z_c = 28, module 1 mm (cases/mbd_26_28.toml).
inline DynamicsModel small_model(DynamicsConfiguration config = DynamicsConfiguration::CsFixed) {
  DynamicsModel m;
  GearParams g;
  g.module_m = 1.0e-3;
  g.teeth_flexspline = 26;
  g.teeth_circular = 28;
  FlexsplineParams fs;
  fs.inner_radius_m = 11.0e-3;
  fs.wall_thickness_m = 0.5e-3;
  fs.length_m = 20.0e-3;
  fs.rim_width_m = 8.0e-3;
  fs.rim_thickness_m = 0.8e-3;
  Material mat;
  m.params.configuration = config;
  m.teeth_flexspline = 26;
  m.teeth_circular = 28;
  m.inertia = body_inertias(g, fs, true, mat, m.params);
  const double w0 = g.module_m * (28 - 26) / 2.0;
  m.pairs = approximate_tooth_pairs(g, w0, 20.0 * std::numbers::pi / 180.0, 0.0);
  return m;
}

}  // namespace sw::test
