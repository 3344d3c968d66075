#pragma once
// Where the power goes in a running drive at one output torque (circular spline fixed, generator driven at the input
// speed, the flexspline the output), read from the loaded contact at that torque:
//  - the generator bearing: Palmgren's friction moment (generator/bearing_friction.hpp) of its balls' loads (the
//    contact's station forces spread ball by ball, datasheet/limits.hpp ball_loads_N), at the speed of its rings
//    relative to each other n_in·(1 + 1/ratio) (the inner ring on the plug, the outer in the turning flexspline) and
//    the lubricant's viscosity at its temperature (ASTM D341, common/lubricant.hpp); its viscous part M0 and load part
//    M1 kept apart;
//  - the flanks' sliding: Coulomb friction μ·F_i on each loaded flank times its kinematic sliding speed |s_i|·σ̇
//    (dynamics/moving_mesh_build.hpp flank_velocity: the two contact points' relative velocity along the profile per
//    unit σ = θ_w − θ_f, on the rim's generator-deformed neutral curve at rest), σ̇ = ω_in·(1 + 1/ratio);
//  - the flexspline's material damping: the generator's deformation is a wave fixed to the generator, so harmonic n of
//    it (strain energy U_n, fem/fourier_solver.hpp harmonic_strain_energy_J) strains every point of the turning body
//    at n·σ̇. With a hysteretic loss factor η (the complex modulus E(1 + iη): per cycle 2π·η times the energy stored)
//    a travelling wave of energy U_n dissipates 2·η·n·σ̇·U_n (two standing waves in quadrature, each 2π·η·U_n per
//    cycle), so P = 2·η·σ̇·Σ n·U_n. Rate-independent: the same torque at the input at any speed, breakaway included;
//  - the generator's outer ring slipping on the flexspline's bore (generator/ring_slip.hpp): rim and ring bent
//    together differ in surface strain by d·Δκ, and the running wave makes the bore slide on the ring under the
//    stations' forces, μ·Ω·R·d·Σ F_i·|Δκ_i − κ_c| (Goodman and Klumpp's slip damping); rate-independent too.
// P_in = P_out + the losses, efficiency P_out/P_in, the input torque P_in/ω_in.
//
// Idealisations (said in every figure's method): the contact's flank forces and contact points at one generator
// position and at rest stand for the running mesh (the teeth's sliding read where they touch at rest, not where the
// load has moved the contact); μ constant over the flank; the damping from the generator's deformation alone (what
// the torque adds to the wave left out) at the loss factor of small strain amplitudes (at a flexspline's stresses
// steels damp more: Lazan, Damping of Materials and Members in Structural Mechanics, 1968); no churning or drag of
// the lubricant beyond what Palmgren's f0 holds for the bearing, no seal, no heat (the temperature is the case's).
// A loss left out makes the efficiency an upper bound.
#include <functional>
#include <string>
#include <vector>

#include "common/lubricant.hpp"
#include "contact/loaded_contact.hpp"
#include "generator/bearing_friction.hpp"
#include "generator/ring_slip.hpp"
#include "kinematics/backlash.hpp"

namespace sw {

/// The running conditions of a loss evaluation.
struct LossConditions {
  Lubricant lubricant;            ///< with its temperature
  double input_speed_rpm = 2000;  ///< the generator's speed, ≥ 0
  double flank_friction = 0;      ///< μ of the flanks, in [0, 1]
  PalmgrenCoefficients palmgren;  ///< the bearing's coefficients
  double loss_factor = 0;         ///< η of the flexspline's material, in [0, 1)
  /// The generator's deformation's strain energy per harmonic n = 0.. (J); empty: no damping counted.
  std::vector<double> wave_energy_J;
  /// The generator's outer ring on the bore (generator/ring_slip.hpp) at the contact's stations; no curvatures: no
  /// slip counted.
  RingOnBore ring;
};

/// The flexspline's material damping as a moment between the generator and the flexspline against the wave's turn
/// σ̇ (N·m): 2·η·Σ n·U_n over the wave's harmonics U_n (J) (the power 2·η·σ̇·Σ n·U_n over σ̇). InputError for η
/// outside [0, 1) or a negative energy.
double damping_moment_Nm(const std::vector<double>& wave_energy_J, double loss_factor);

/// The input torque the flexspline's material damping takes (N·m): damping_moment_Nm·(1 + 1/ratio) (the power over
/// ω_in). InputError as damping_moment_Nm's and for ratio < 1.
double damping_input_torque_Nm(const std::vector<double>& wave_energy_J, double loss_factor, int ratio);

/// The power balance at one output torque and input speed. W unless named otherwise.
struct LossSplit {
  double output_torque_Nm = 0, input_speed_rpm = 0;
  double output_power_W = 0;
  double bearing_viscous_W = 0;  ///< Palmgren's M0 at the rings' relative speed
  double bearing_load_W = 0;     ///< Palmgren's M1
  double flank_sliding_W = 0;    ///< Σ μ·F·|v_slide| over the loaded flanks (both teeth of a half-turn pair)
  double flexspline_damping_W = 0;  ///< the material's hysteresis under the generator's wave
  double ring_slip_W = 0;        ///< the generator's outer ring slipping on the bore
  double viscosity_mm2_s = 0;    ///< the lubricant's at its temperature
  double loss_W() const {
    return bearing_viscous_W + bearing_load_W + flank_sliding_W + flexspline_damping_W + ring_slip_W;
  }
  double input_power_W() const { return output_power_W + loss_W(); }
  /// P_out / P_in; 1 with no loss; 0 at zero output torque.
  double efficiency() const { return input_power_W() > 0 ? output_power_W / input_power_W() : 0.0; }
  /// The torque the input needs, N·m (P_in / ω_in); at zero output torque the no-load running torque.
  double input_torque_Nm() const;
};

/// The kinematic sliding of each of the contact's flanks per unit σ (m/rad, signed), at its tooth's material angle on
/// `model` (the rim's generator-deformed curve the contact was built on).
std::vector<double> flank_sliding_m_per_rad(const BacklashModel& model, const ContactAnalysis& contact);

/// The power balance at the contact's step `step` (its torque, magnitude taken: the sense of the load does not change
/// the losses), with `sliding` from flank_sliding_m_per_rad and the balls' loads of that step. `ratio` = z_f/(z_c − z_f).
/// Validates the lubricant, the coefficients, μ in [0, 1] and the speed ≥ 0 (InputError naming the field).
LossSplit drive_losses(const ContactAnalysis& contact, std::size_t step, const std::vector<double>& sliding_m_per_rad,
                       const GeneratorBearing& bearing, const std::vector<double>& ball_loads_N, int ratio,
                       const LossConditions& conditions);

/// The losses over the running conditions a catalog plots: the efficiency against input speed at several loads (the
/// case's temperature), against the lubricant's temperature at rated torque and 2,000 rpm, and the no-load running
/// torque against speed at several temperatures. Every point is drive_losses at the contact's step nearest that load.
struct LossMap {
  double temperature_C = 0;  ///< the case's: the speed and load curves'
  std::vector<double> speeds_rpm = {500, 1000, 1500, 2000, 2500, 3000, 3500};
  std::vector<double> load_fractions = {0.1, 0.25, 0.5, 0.75, 1.0};  ///< of rated torque
  std::vector<double> temperatures_C = {-10, 0, 10, 20, 30, 40};
  double rated_speed_rpm = 2000;                            ///< of the temperature curve
  std::vector<std::vector<double>> efficiency;              ///< [load][speed] at temperature_C
  std::vector<double> efficiency_at_rated;                  ///< [temperature] at rated torque and rated_speed_rpm
  std::vector<std::vector<double>> no_load_torque_Nm;       ///< [temperature][speed], at the input
};

/// One point of the map: the power balance at the contact's step `step` under `conditions` (drive_losses with that
/// step's ball loads).
using LossAt = std::function<LossSplit(std::size_t step, const LossConditions& conditions)>;

/// The map of `contact` (its steps from −rated to +rated; the loads read at the nearest step at or above zero) under
/// `base` (its lubricant's temperature the curves' by speed and load).
LossMap loss_map(const ContactAnalysis& contact, const LossAt& at, const LossConditions& base);

/// The input torque that starts the drive from rest with no load on the output, N·m: Palmgren's breakaway moment of
/// the generator bearing under these ball loads (palmgren_breakaway_moment_Nm: M1 alone, a lower bound) carried to
/// the input as in the power balance, ×(1 + 1/ratio) (the rings turn against each other at σ̇ = ω_in·(1 + 1/ratio)),
/// plus the rate-independent losses' input torque at rest (`rate_independent_Nm`: the flexspline's damping,
/// damping_input_torque_Nm, the ring's slip on the bore and the flanks' sliding of a mesh preloaded at rest, there at
/// breakaway).
double starting_torque_Nm(const GeneratorBearing& bearing, const std::vector<double>& ball_loads_N, int ratio,
                          const PalmgrenCoefficients& palmgren = {}, double rate_independent_Nm = 0);

/// The output torque that starts the drive turning its free input from rest (backdriving), N·m. At breakaway the
/// output's power goes into the losses: T·ω_out = T_start·ω_in + k·T·ω_in with ω_in = ratio·ω_out, T_start the
/// starting torque at the input (the generator bearing's breakaway) and k the flanks' sliding loss per output torque
/// and input speed, read from the loaded state `loaded` (k = flank_sliding_W / (T·ω_in): the flanks' loss is
/// proportional to their forces, so to the torque). So T = ratio·T_start / (1 − ratio·k); +∞ when ratio·k ≥ 1 (the
/// mesh locks itself against the output). InputError for ratio < 1 or a loaded state without torque or speed.
double backdriving_torque_Nm(double starting_torque_Nm, const LossSplit& loaded, int ratio);

}  // namespace sw
