#include "datasheet/losses.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include "common/error.hpp"
#include "dynamics/moving_mesh_build.hpp"

namespace sw {
namespace {

constexpr double kRadPerS_per_rpm = 2.0 * std::numbers::pi / 60.0;

}  // namespace

double LossSplit::input_torque_Nm() const {
  const double omega_in = input_speed_rpm * kRadPerS_per_rpm;
  return omega_in > 0 ? input_power_W() / omega_in : 0.0;
}

double damping_moment_Nm(const std::vector<double>& wave_energy_J, double loss_factor) {
  if (!(loss_factor >= 0 && loss_factor < 1)) {
    std::ostringstream os;
    os << "material.loss_factor = " << loss_factor << "; must be in [0, 1)";
    throw InputError(os.str());
  }
  double weighted = 0;
  for (std::size_t n = 0; n < wave_energy_J.size(); ++n) {
    if (!(wave_energy_J[n] >= 0)) throw InputError("damping torque: the wave's strain energy must be >= 0");
    weighted += static_cast<double>(n) * wave_energy_J[n];  // n = 0 is static in the turning body: no cycle
  }
  return 2 * loss_factor * weighted;
}

double damping_input_torque_Nm(const std::vector<double>& wave_energy_J, double loss_factor, int ratio) {
  const double moment = damping_moment_Nm(wave_energy_J, loss_factor);
  if (ratio < 1) throw InputError("damping torque: ratio " + std::to_string(ratio) + "; must be >= 1");
  return moment * (1.0 + 1.0 / ratio);
}

std::vector<double> flank_sliding_m_per_rad(const BacklashModel& model, const ContactAnalysis& contact) {
  std::vector<double> out;
  out.reserve(contact.flanks.size());
  for (const FlankContact& f : contact.flanks) {
    const PairClearance pc = pair_clearance(model, f.phi_rad, 0.0);
    out.push_back(flank_velocity(model, f.flank == Flank::Ccw ? pc.ccw : pc.cw, f.phi_rad).sliding_m_per_rad);
  }
  return out;
}

LossSplit drive_losses(const ContactAnalysis& contact, std::size_t step, const std::vector<double>& sliding,
                       const GeneratorBearing& bearing, const std::vector<double>& ball_loads_N, int ratio,
                       const LossConditions& c) {
  validate_lubricant(c.lubricant, "lubricant");
  validate_palmgren_coefficients(c.palmgren, "palmgren");
  if (!(c.flank_friction >= 0 && c.flank_friction <= 1)) {
    std::ostringstream os;
    os << "contact.friction_coefficient = " << c.flank_friction << "; must be in [0, 1]";
    throw InputError(os.str());
  }
  if (!(c.input_speed_rpm >= 0)) {
    std::ostringstream os;
    os << "input speed " << c.input_speed_rpm << " rpm; must be >= 0";
    throw InputError(os.str());
  }
  if (step >= contact.steps.size() || sliding.size() != contact.flanks.size() || ratio < 1)
    throw InputError("drive_losses: step, sliding or ratio does not match the contact");
  const TorqueStep& s = contact.steps[step];

  LossSplit out;
  out.output_torque_Nm = std::abs(s.torque_Nm);
  out.input_speed_rpm = c.input_speed_rpm;
  const double omega_in = c.input_speed_rpm * kRadPerS_per_rpm;
  // Circular spline fixed: the flexspline turns back at ω_in/ratio, so σ̇ = ω_w − ω_f = ω_in·(1 + 1/ratio), and the
  // bearing's rings turn against each other at the same rate.
  const double sigma_rate = omega_in * (1.0 + 1.0 / ratio);
  out.output_power_W = out.output_torque_Nm * omega_in / ratio;

  out.viscosity_mm2_s = kinematic_viscosity_mm2_s(c.lubricant, c.lubricant.temperature_C);
  const BearingFrictionMoment m = palmgren_friction_moment(bearing, ball_loads_N, sigma_rate / kRadPerS_per_rpm,
                                                           out.viscosity_mm2_s, c.palmgren);
  out.bearing_viscous_W = m.viscous_Nm * sigma_rate;
  out.bearing_load_W = m.load_Nm * sigma_rate;

  // The flank forces are per tooth; a half-turn pair is two teeth.
  const double teeth = contact.half_turn_pairs ? 2.0 : 1.0;
  double sliding_W = 0;
  for (std::size_t i = 0; i < contact.flanks.size(); ++i)
    sliding_W += c.flank_friction * s.flank_force_N[i] * teeth * std::abs(sliding[i]) * sigma_rate;
  out.flank_sliding_W = sliding_W;
  out.flexspline_damping_W = damping_input_torque_Nm(c.wave_energy_J, c.loss_factor, ratio) * omega_in;
  out.ring_slip_W = ring_on_bore_moment_Nm(c.ring, s.station_force_N) * sigma_rate;
  return out;
}

LossMap loss_map(const ContactAnalysis& contact, const LossAt& at, const LossConditions& base) {
  if (contact.steps.empty()) throw InputError("loss map: the contact has no torque steps");
  const double rated = contact.steps.back().torque_Nm;
  const auto step_at = [&](double torque_Nm) {
    std::size_t best = 0;
    for (std::size_t i = 0; i < contact.steps.size(); ++i)
      if (contact.steps[i].torque_Nm >= 0 &&
          std::abs(contact.steps[i].torque_Nm - torque_Nm) < std::abs(contact.steps[best].torque_Nm - torque_Nm))
        best = i;
    return best;
  };
  LossMap m;
  m.temperature_C = base.lubricant.temperature_C;
  LossConditions c = base;
  for (const double load : m.load_fractions) {
    const std::size_t step = step_at(load * rated);
    std::vector<double>& row = m.efficiency.emplace_back();
    for (const double rpm : m.speeds_rpm) {
      c.input_speed_rpm = rpm;
      row.push_back(at(step, c).efficiency());
    }
  }
  const std::size_t rated_step = step_at(rated), rest = step_at(0.0);
  for (const double t : m.temperatures_C) {
    c.lubricant.temperature_C = t;
    c.input_speed_rpm = m.rated_speed_rpm;
    m.efficiency_at_rated.push_back(at(rated_step, c).efficiency());
    std::vector<double>& row = m.no_load_torque_Nm.emplace_back();
    for (const double rpm : m.speeds_rpm) {
      c.input_speed_rpm = rpm;
      row.push_back(at(rest, c).input_torque_Nm());
    }
  }
  return m;
}

double starting_torque_Nm(const GeneratorBearing& bearing, const std::vector<double>& ball_loads_N, int ratio,
                          const PalmgrenCoefficients& palmgren, double rate_independent_Nm) {
  if (ratio < 1) throw InputError("starting torque: ratio " + std::to_string(ratio) + "; must be >= 1");
  return palmgren_breakaway_moment_Nm(bearing, ball_loads_N, palmgren) * (1.0 + 1.0 / ratio) + rate_independent_Nm;
}

double backdriving_torque_Nm(double starting_torque_Nm, const LossSplit& loaded, int ratio) {
  if (ratio < 1) throw InputError("backdriving torque: ratio " + std::to_string(ratio) + "; must be >= 1");
  const double omega_in = loaded.input_speed_rpm * 2 * std::numbers::pi / 60;
  if (!(std::abs(loaded.output_torque_Nm) > 0) || !(omega_in > 0))
    throw InputError("backdriving torque: the loaded state needs an output torque and an input speed > 0");
  const double k = loaded.flank_sliding_W / (std::abs(loaded.output_torque_Nm) * omega_in);
  const double reverse = 1 - ratio * k;
  return reverse > 0 ? ratio * starting_torque_Nm / reverse : std::numeric_limits<double>::infinity();
}

}  // namespace sw
