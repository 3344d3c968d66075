#pragma once
// Post-processing of a dynamics run: steady speeds against the kinematic relations, mean pair forces against the
// quasi-static load sharing of the same contact law, the torque and energy balances, and the force spectrum (FFTW).
#include <string>
#include <vector>

#include "dynamics/model.hpp"
#include "dynamics/simulate.hpp"

namespace sw {

struct SpeedCheck {
  std::string body;
  double simulated_rpm = 0.0;   ///< mean over the steady window: Δθ/Δt
  double theory_rpm = 0.0;      ///< steady_state()
  double error_rel = 0.0;       ///< |sim − theory|/|theory| (0 for a fixed body)
};

struct PairForceCheck {
  int pair = 0;
  double angle_deg = 0.0;        ///< position from the major axis
  double arm_m = 0.0;            ///< n·ρ
  double mean_N = 0.0;           ///< mean over the steady window (signed, drive flank positive)
  double quasi_static_N = 0.0;   ///< quasi_static_load_sharing()
  double error_rel = 0.0;        ///< |mean − qs| / |qs|; for unloaded pairs |mean − qs| / max|qs|
};

struct Spectrum {
  double resolution_Hz = 0.0;
  std::vector<double> frequency_Hz, amplitude_N;  ///< single-sided amplitude of a sinusoid (Hann, coherent gain)
};

struct SpectralLine {
  double frequency_Hz = 0.0;  ///< refined by a parabola through the log-amplitudes of the peak and its neighbours
  double amplitude_N = 0.0;
};

/// Mean powers over the steady window (W), from the integrated works at its ends. Balance:
/// input = output + friction + dissipated + stored.
struct SteadyPower {
  double input_W = 0.0;        ///< the drive's
  double output_W = 0.0;       ///< into the load and the drags
  double friction_W = 0.0;     ///< the flanks' friction, Σ |F_t·v_slide|
  double bearing_W = 0.0;      ///< the generator bearing's friction, M·|ω_w − ω_rim|
  double dissipated_W = 0.0;   ///< contact damping and torsion-spring damping
  double stored_W = 0.0;       ///< rate of kinetic + potential energy, less the parametric power of k(t)
  /// The drive's efficiency under the flanks' and the generator bearing's friction: output / (output + friction +
  /// bearing); 1 without either. The contact damping's loss (dissipated_W) is the model's idealisation of the teeth's
  /// damping, reported beside it.
  double efficiency = 1.0;
  double balance_error_rel = 0.0;  ///< |input − (output + friction + dissipated + stored)| / |input|
  /// dissipated_W > output_W: the contact's damper (the paper's idealisation, not a loss the drive's physics gives)
  /// takes more than the output delivers, so the run is dominated by vibration that damper sets, and the efficiency
  /// and the loss split describe the model's damper more than the drive (e.g. the FEM-coupled rim ringing at a mesh
  /// harmonic, or no load).
  bool damping_exceeds_output = false;
};

struct DynamicsSummary {
  SteadyState theory;
  double window_start_s = 0.0;              ///< steady window [window_start_s, duration_s]: whole mesh periods
  std::vector<SpeedCheck> speeds;
  double max_speed_error_rel = 0.0;
  std::vector<PairForceCheck> pair_forces;
  double max_pair_force_error_rel = 0.0;    ///< over loaded pairs
  double mesh_torque_Nm = 0.0;              ///< Σ mean F_i·arm_i
  double torque_balance_error_rel = 0.0;    ///< |Σ mean F_i·arm_i − M_theory| / max(|M_theory|, 1e-6 N·m)
  double energy_error_rel = 0.0;
  SteadyPower power;
  double mean_total_force_N = 0.0;
  double force_fluctuation_N = 0.0;         ///< standard deviation of the total meshing force in the steady window
  Spectrum spectrum;                        ///< of the total meshing force in the steady window
  std::vector<SpectralLine> lines;          ///< strongest first
  double noise_floor_N = 0.0;               ///< median amplitude of the force spectrum above 2.5 bins
  Spectrum te_spectrum;                     ///< of the transmission error (rad) in the steady window
  std::vector<SpectralLine> te_lines;       ///< strongest first
  double te_noise_floor_rad = 0.0;
  double generator_frequency_Hz = 0.0;      ///< |n_w − n_f|/60: a flexspline tooth's turn relative to the generator
  // over the steady window (whole mesh periods)
  double deflection_min_rad = 0.0, deflection_max_rad = 0.0;  ///< mesh deflection e
  double max_pair_force_N = 0.0;            ///< largest flank force
  double flanks_in_contact_min = 0.0, flanks_in_contact_max = 0.0;
  double te_peak_to_peak_rad = 0.0;
};

/// Median amplitude of the bins at or above min_frequency_Hz: the floor against which the lines stand.
double noise_floor(const Spectrum& s, double min_frequency_Hz);

/// Amplitude spectrum of a uniformly sampled signal (dt [s]): mean removed, periodic Hann window, FFTW r2c; a sinusoid
/// of amplitude A on a bin shows A exactly. Precondition: ≥ 8 samples.
Spectrum amplitude_spectrum(const std::vector<double>& signal, double dt_s);

/// Local maxima of the spectrum above min_frequency_Hz, strongest first, at most max_lines.
std::vector<SpectralLine> spectral_lines(const Spectrum& s, double min_frequency_Hz, int max_lines);

/// The bodies whose speeds are reported, in order: wave generator, flexspline rim (when compliant), flexspline
/// (flange), circular spline.
std::vector<BodyId> reported_bodies(const DynamicsParams& p);

/// Everything dynamics.json reports, over the steady window: from steady_from_s (moved later to span a whole number of
/// mesh periods) to duration_s.
DynamicsSummary summarize(const DynamicsModel& m, const DynamicsSeries& series);

}  // namespace sw
