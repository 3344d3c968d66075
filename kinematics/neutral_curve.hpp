#pragma once
// The deformed neutral curve of the flexspline rim, in the wave generator's frame (φ = 0 on the major axis = +x,
// counter-clockwise positive). A material point at angle φ on the undeformed neutral circle (radius r_m) moves by
// w(φ) radially (outwards positive) and v(φ) tangentially (counter-clockwise positive); the rim's cross-section
// rotates by μ(φ) relative to the rigid rotation v/r_m (counter-clockwise positive).
//
// All three functions are stored as truncated Fourier series in φ, so they are smooth, periodic and cheap to evaluate
// with exact derivatives:
//   cam       w = w0 cos 2φ,   v = −∫₀^φ w dφ = −(w0/2) sin 2φ,   μ = −(1/r_m) dw/dφ = (2 w0/r_m) sin 2φ
//   ring      thin inextensible ring under self-equilibrated radial point forces P_i at θ_i (curved-beam theory, the
//             n = 0, 1 modes carry no load): w(φ) = C Σ_{n≥2} Σ_i P_i cos n(φ − θ_i) / (n² − 1)²; C fixed by w(0) = w0
//             (so EI and the force magnitude drop out); v and μ as for the cam. four_force: equal forces at ±β and
//             π ± β; two_force: at 0 and π; forces: the case's list (weights), mirrored to π + θ.
//   fem       a least-squares Fourier fit (order ≤ 64) of the columns of neutral_curve.csv written by `strainwave fem`
//             (there μ is the tangent's whole rotation (v − w')/r; the tooth placement takes its rotation from w and v
//             alone, so every source is placed alike).
#include <string>
#include <vector>

#include "generator/wave_generator.hpp"
#include "mesh/flexspline_params.hpp"

namespace sw {

/// Σ a_n cos nφ + b_n sin nφ, n = 0..N (b_0 unused).
struct FourierSeries {
  std::vector<double> a, b;
  /// Value at φ (rad).
  double value(double phi_rad) const;
  /// d/dφ at φ.
  double derivative(double phi_rad) const;
};

/// w, v, μ at one material angle.
struct NeutralPoint {
  double w_m = 0;     ///< radial displacement, outwards positive
  double v_m = 0;     ///< tangential displacement, counter-clockwise positive
  double mu_rad = 0;  ///< extra rotation of the cross-section (−(1/r_m) dw/dφ for an inextensible ring)
};

struct NeutralCurve {
  double mean_radius_m = 0;  ///< r_m of the undeformed neutral circle
  FourierSeries w, v, mu;
  std::string source;        ///< "cam", "ring four_force β=30°", "fem path.csv (wg)", ... for reports
  /// w, v, μ at the material angle φ (rad, from the major axis).
  NeutralPoint at(double phi_rad) const;
};

/// Cam-shaped generator: w = w0 cos 2φ (w0 in metres, r_m > 0).
NeutralCurve cam_neutral_curve(double mean_radius_m, double w0_m);

/// Thin inextensible ring under the generator's radial point forces (model FourForce, TwoForce or Forces; Cam gives
/// the cam curve), scaled so that w(0) = w0. Series to order n_max (terms fall as n⁻⁴: n_max = 400 leaves < 1e-8·w0).
/// Throws InputError if the forces give w(0) ≤ 0 (no outward bulge on the major axis) or the model has no forces.
NeutralCurve generator_neutral_curve(double mean_radius_m, double w0_m, const WaveGeneratorParams& wg, int n_max = 400);

/// Least-squares Fourier fit (order min(64, samples/2 − 1)) of sampled w, v, μ (metres, radians) at material angles
/// phi (rad, ≥ 360 samples over the full circle), e.g. the FEM's neutral_curve.csv as read by io/fem_output.hpp.
/// `source` names the data in messages and reports. Throws InputError for too few samples or a partial circle.
NeutralCurve fit_neutral_curve(double mean_radius_m, const std::vector<double>& phi, const std::vector<double>& w,
                               const std::vector<double>& v, const std::vector<double>& mu, std::string source);

/// Mean radius of the rim's neutral layer: inner radius + rim thickness / 2 (metres).
double rim_mean_radius(const FlexsplineParams& f);

}  // namespace sw
