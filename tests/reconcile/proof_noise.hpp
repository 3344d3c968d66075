#pragma once
// The recordings of the single-effect proofs (tests/reconcile/test_identify.cpp, test_coverage.cpp and
// bench_reconcile_coverage): each kind's baseline and fixed noise, in response units: torsion white 1e-6 rad + AR(1)
// 1e-6 rad (phi 0.8) + 5e-7 rad quantum; transmission 2e-6 + 2e-6 + 1e-6 rad; backlash 0.2 + 0.2 + 0.1 µm. 4000
// samples.
#include <cmath>
#include <cstdint>

#include "reconcile/synth.hpp"

namespace sw::reconcile::testing {

inline double basic_backlash_um(double wg_rad) { return 20.0 + 15.0 * std::cos(2.0 * wg_rad); }

inline SynthOptions proof_options(Kind kind, std::uint64_t seed) {
  SynthOptions o;
  o.samples = 4000;
  o.seed = seed;
  o.ar1_phi = 0.8;
  switch (kind) {
    case Kind::Torsion:
      o.baseline.prediction = TorsionPrediction{.compliance_rad_per_Nm = 5e-5};
      o.white_sd = 1e-6; o.ar1_sd = 1e-6; o.quantum = 5e-7;
      break;
    case Kind::Transmission:
      o.baseline.gear = {.teeth_flexspline = 190, .teeth_circular = 192};
      o.baseline.prediction = TransmissionPrediction{};
      o.rows = TransmissionRows{.output_revolutions = 2.0};
      o.white_sd = 2e-6; o.ar1_sd = 2e-6; o.quantum = 1e-6;
      break;
    default:
      o.baseline.gear.pitch_radius_m = 0.019;
      o.baseline.prediction = BacklashPrediction{.backlash_um = basic_backlash_um};
      o.rows = BacklashRows{};
      o.white_sd = 0.2; o.ar1_sd = 0.2; o.quantum = 0.1;
      break;
  }
  return o;
}

}  // namespace sw::reconcile::testing
