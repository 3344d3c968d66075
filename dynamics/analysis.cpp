#include "dynamics/analysis.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>

#include <fftw3.h>

#include "common/constants.hpp"

namespace sw {
namespace {

constexpr int kLines = 10;
// Without load the references of the relative errors vanish; below these floors the errors are taken against them.
constexpr double kForceFloor_N = 1e-6;
constexpr double kTorqueFloor_Nm = 1e-6;

}  // namespace

Spectrum amplitude_spectrum(const std::vector<double>& signal, double dt) {
  const int n = int(signal.size());
  assert(n >= 8);
  double mean = 0.0;
  for (double v : signal) mean += v;
  mean /= n;
  std::vector<double> in(n);
  double gain = 0.0;
  for (int i = 0; i < n; ++i) {
    const double w = 0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * i / n);  // periodic Hann: exact on-bin gain
    in[i] = (signal[i] - mean) * w;
    gain += w;
  }
  std::vector<fftw_complex> out(n / 2 + 1);
  fftw_plan plan = fftw_plan_dft_r2c_1d(n, in.data(), out.data(), FFTW_ESTIMATE);
  fftw_execute(plan);
  fftw_destroy_plan(plan);
  Spectrum s;
  s.resolution_Hz = 1.0 / (n * dt);
  s.frequency_Hz.resize(n / 2 + 1);
  s.amplitude_N.resize(n / 2 + 1);
  for (int k = 0; k <= n / 2; ++k) {
    s.frequency_Hz[k] = k * s.resolution_Hz;
    s.amplitude_N[k] = (k == 0 ? 1.0 : 2.0) * std::hypot(out[k][0], out[k][1]) / gain;
  }
  return s;
}

std::vector<SpectralLine> spectral_lines(const Spectrum& s, double fmin, int max_lines) {
  std::vector<SpectralLine> lines;
  const auto& a = s.amplitude_N;
  for (std::size_t k = 1; k + 1 < a.size(); ++k) {
    if (s.frequency_Hz[k] < fmin || !(a[k] > a[k - 1] && a[k] >= a[k + 1])) continue;
    double shift = 0.0;
    if (a[k - 1] > 0 && a[k + 1] > 0) {
      const double l = std::log(a[k - 1]), c = std::log(a[k]), r = std::log(a[k + 1]);
      const double den = l - 2.0 * c + r;
      if (den < 0) shift = std::clamp(0.5 * (l - r) / den, -0.5, 0.5);
    }
    lines.push_back({s.frequency_Hz[k] + shift * s.resolution_Hz, a[k]});
  }
  std::sort(lines.begin(), lines.end(), [](auto& x, auto& y) { return x.amplitude_N > y.amplitude_N; });
  if (int(lines.size()) > max_lines) lines.resize(max_lines);
  return lines;
}

double noise_floor(const Spectrum& s, double fmin) {
  std::vector<double> a;
  for (std::size_t k = 0; k < s.amplitude_N.size(); ++k)
    if (s.frequency_Hz[k] >= fmin) a.push_back(s.amplitude_N[k]);
  if (a.empty()) return 0.0;
  std::nth_element(a.begin(), a.begin() + a.size() / 2, a.end());
  return a[a.size() / 2];
}

namespace {

/// The steady window's first and last sample.
struct Window {
  std::size_t i0 = 0, i1 = 0;
};

/// From steady_from_s, moved later to span a whole number of mesh periods (to the nearest sample), so that means over
/// it are not biased by a fraction of a period of the k(t) oscillation; at least 8 samples.
Window steady_window(const DynamicsParams& p, const std::vector<double>& t, double mesh_frequency_Hz) {
  const std::size_t n = t.size();
  Window w;
  w.i1 = n - 1;
  double t_start = p.steady_from_s;
  const double fm = mesh_frequency_Hz;
  if (fm > 0 && (t[w.i1] - t_start) * fm >= 1.0) t_start = t[w.i1] - std::floor((t[w.i1] - t_start) * fm + 1e-9) / fm;
  w.i0 = std::size_t(std::lround(t_start / p.output_step_s));
  if (w.i0 + 8 > n) w.i0 = n > 8 ? n - 8 : 0;
  return w;
}

double window_mean(const std::vector<double>& v, Window w) {
  double sum = 0.0;
  for (std::size_t j = w.i0; j <= w.i1; ++j) sum += v[j];
  return sum / double(w.i1 - w.i0 + 1);
}

/// Each reported body's mean speed over the window (Δθ/Δt) against its steady kinematic speed.
void check_speeds(const DynamicsModel& m, const DynamicsSeries& s, Window w, DynamicsSummary& r) {
  const double span = s.time_s[w.i1] - s.time_s[w.i0];
  for (BodyId b : reported_bodies(m.params)) {
    const int k = static_cast<int>(b);
    SpeedCheck c;
    c.body = body_name(b);
    c.simulated_rpm = (s.angle_rad[k][w.i1] - s.angle_rad[k][w.i0]) / span * kRpmPerRadS;
    c.theory_rpm = r.theory.speed_rad_s[k] * kRpmPerRadS;
    c.error_rel = c.theory_rpm == 0.0 ? std::abs(c.simulated_rpm) : std::abs(c.simulated_rpm / c.theory_rpm - 1.0);
    r.max_speed_error_rel = std::max(r.max_speed_error_rel, c.error_rel);
    r.speeds.push_back(c);
  }
}

/// Frozen pairs: each pair's mean force against the quasi-static load sharing of the same contact law at the
/// theory's mesh torque, and the mesh torque Σ mean F_i·arm_i they carry.
void check_pair_forces(const DynamicsModel& m, const DynamicsSeries& s, Window w, DynamicsSummary& r) {
  const LoadSharing qs = quasi_static_load_sharing(m.pairs, m.params, r.theory.mesh_torque_Nm);
  double qs_max = 0.0;
  for (double f : qs.force_N) qs_max = std::max(qs_max, std::abs(f));
  r.mesh_torque_Nm = 0.0;
  for (std::size_t i = 0; i < m.pairs.size(); ++i) {
    PairForceCheck c;
    c.pair = int(i) + 1;
    c.angle_deg = m.pairs[i].angle_rad * 180.0 / std::numbers::pi;
    c.mean_N = window_mean(s.pair_force_N[i], w);
    c.arm_m = c.mean_N >= 0.0 ? m.pairs[i].arm_m() : m.pairs[i].coast_arm();
    c.quasi_static_N = qs.force_N[i];
    const bool loaded = std::abs(c.quasi_static_N) > 1e-9 * qs_max;
    c.error_rel = std::abs(c.mean_N - c.quasi_static_N) /
                  (loaded ? std::abs(c.quasi_static_N) : std::max(qs_max, kForceFloor_N));
    if (loaded) r.max_pair_force_error_rel = std::max(r.max_pair_force_error_rel, c.error_rel);
    r.mesh_torque_Nm += c.mean_N * c.arm_m;
    r.pair_forces.push_back(c);
  }
}

/// The window's mean powers from the energy terms at its ends, their balance and the efficiency.
SteadyPower steady_power(const DynamicsSeries& s, Window w) {
  const EnergyBalance& a = s.energy_to_sample[w.i0];
  const EnergyBalance& b = s.energy_to_sample[w.i1];
  const double span = s.time_s[w.i1] - s.time_s[w.i0];
  SteadyPower p;
  p.input_W = (b.input_J - a.input_J) / span;
  p.output_W = (b.output_J - a.output_J) / span;
  p.friction_W = (b.friction_J - a.friction_J) / span;
  p.bearing_W = (b.bearing_J - a.bearing_J) / span;
  p.dissipated_W = (b.dissipated_J - a.dissipated_J) / span;
  p.stored_W = ((b.kinetic_J + b.potential_J - b.parametric_J) - (a.kinetic_J + a.potential_J - a.parametric_J)) / span;
  if (p.friction_W + p.bearing_W > 0.0) p.efficiency = p.output_W / (p.output_W + p.friction_W + p.bearing_W);
  p.balance_error_rel = std::abs(p.input_W - (p.output_W + p.friction_W + p.bearing_W + p.dissipated_W + p.stored_W)) /
                        std::max(std::abs(p.input_W), 1e-300);
  p.damping_exceeds_output = p.dissipated_W > p.output_W;
  return p;
}

/// The total force's mean and fluctuation over the window, and the spectra of the total force and of the
/// transmission error with their lines and noise floors.
void analyse_spectra(const DynamicsParams& p, const DynamicsSeries& s, Window w, DynamicsSummary& r) {
  std::vector<double> window(s.total_force_N.begin() + w.i0, s.total_force_N.begin() + w.i1 + 1);
  double mean = 0.0, var = 0.0;
  for (double v : window) mean += v;
  mean /= double(window.size());
  for (double v : window) var += (v - mean) * (v - mean);
  r.mean_total_force_N = mean;
  r.force_fluctuation_N = std::sqrt(var / double(window.size()));
  // The spectrum takes the window without its last sample, so that it spans exactly (t_end − t_start) and a tone
  // with a whole number of periods in it (f_m·span integer) falls on a bin.
  window.pop_back();
  r.spectrum = amplitude_spectrum(window, p.output_step_s);
  // Lines below two bins are the Hann window's own leakage of the removed mean and of slow drifts.
  r.lines = spectral_lines(r.spectrum, 2.5 * r.spectrum.resolution_Hz, kLines);
  r.noise_floor_N = noise_floor(r.spectrum, 2.5 * r.spectrum.resolution_Hz);
  std::vector<double> te(s.transmission_error_rad.begin() + w.i0, s.transmission_error_rad.begin() + w.i1);
  r.te_spectrum = amplitude_spectrum(te, p.output_step_s);
  r.te_lines = spectral_lines(r.te_spectrum, 2.5 * r.te_spectrum.resolution_Hz, kLines);
  r.te_noise_floor_rad = noise_floor(r.te_spectrum, 2.5 * r.te_spectrum.resolution_Hz);
}

/// The extremes over the window of the mesh deflection, the largest flank force, the flanks in contact and the
/// transmission error.
void window_extremes(const DynamicsSeries& s, Window w, DynamicsSummary& r) {
  const auto from = [&](const std::vector<double>& v) { return v.begin() + w.i0; };
  const auto to = [&](const std::vector<double>& v) { return v.begin() + w.i1 + 1; };
  r.deflection_min_rad = *std::min_element(from(s.deflection_rad), to(s.deflection_rad));
  r.deflection_max_rad = *std::max_element(from(s.deflection_rad), to(s.deflection_rad));
  r.max_pair_force_N = *std::max_element(from(s.max_pair_force_N), to(s.max_pair_force_N));
  r.flanks_in_contact_min = *std::min_element(from(s.flanks_in_contact), to(s.flanks_in_contact));
  r.flanks_in_contact_max = *std::max_element(from(s.flanks_in_contact), to(s.flanks_in_contact));
  const auto te_mm = std::minmax_element(from(s.transmission_error_rad), to(s.transmission_error_rad));
  r.te_peak_to_peak_rad = *te_mm.second - *te_mm.first;
}

}  // namespace

std::vector<BodyId> reported_bodies(const DynamicsParams& p) {
  std::vector<BodyId> b{BodyId::WaveGenerator, BodyId::FlexsplineFlange, BodyId::CircularSpline};
  if (p.flexspline_compliance_rad_per_Nm > 0.0) b.insert(b.begin() + 1, BodyId::FlexsplineRim);
  return b;
}

DynamicsSummary summarize(const DynamicsModel& m, const DynamicsSeries& s) {
  DynamicsSummary r;
  r.theory = steady_state(m);
  const Window w = steady_window(m.params, s.time_s, r.theory.mesh_frequency_Hz);
  r.window_start_s = s.time_s[w.i0];
  check_speeds(m, s, w, r);
  if (s.per_tooth)  // moving pairs: the mesh torque's mean (pair forces are checked against loaded contact)
    r.mesh_torque_Nm = window_mean(s.mesh_torque_Nm, w);
  else
    check_pair_forces(m, s, w, r);
  r.torque_balance_error_rel = std::abs(r.mesh_torque_Nm - r.theory.mesh_torque_Nm) /
                               std::max(std::abs(r.theory.mesh_torque_Nm), kTorqueFloor_Nm);
  r.energy_error_rel = s.energy.error_rel();
  r.power = steady_power(s, w);
  analyse_spectra(m.params, s, w, r);
  r.generator_frequency_Hz = r.theory.mesh_frequency_Hz / m.teeth_flexspline;
  window_extremes(s, w, r);
  return r;
}

}  // namespace sw
