#pragma once
// The bearings the generator bearing's tests share: a 6205 of published geometry and Stribeck's load distribution.
#include <cmath>
#include <numbers>
#include <vector>

#include "generator/generator_bearing.hpp"

namespace sw::testing {

/// The SKF 6205-2RS JEM of the Case Western Reserve University bearing data center ("Bearing information", drive-end
/// bearing): 9 balls of 0.3126 in, pitch diameter 1.537 in. Conformities: ISO 281's basis 0.52 (see the f_c test).
inline GeneratorBearing bearing_6205() {
  GeneratorBearing b;
  b.balls = 9;
  b.ball_diameter_m = 0.3126 * 25.4e-3;
  b.pitch_radius_m = 0.5 * 1.537 * 25.4e-3;
  b.inner_groove_conformity = b.outer_groove_conformity = 0.52;
  return b;
}

/// Stribeck's zero-clearance distribution under a radial load F_r along ψ = 0 (Harris & Kotzalas vol. 1, ch.
/// "Distributions of internal loading in statically loaded bearings"): Q_j = Q_max·cos^1.5 ψ_j for |ψ_j| < 90°, 0
/// elsewhere, ψ_j = phase + 2πj/Z, Q_max set so that Σ Q_j cos ψ_j = F_r exactly (≈ 4.37 F_r/Z for large Z).
inline std::vector<double> stribeck_loads(int Z, double Fr, double phase) {
  std::vector<double> Q(Z);
  double sum = 0;
  for (int j = 0; j < Z; ++j) {
    const double c = std::cos(phase + 2 * std::numbers::pi * j / Z);
    Q[j] = c > 0 ? std::pow(c, 1.5) : 0.0;
    sum += Q[j] * c;
  }
  for (double& q : Q) q *= Fr / sum;
  return Q;
}

}  // namespace sw::testing
