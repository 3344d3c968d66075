#include "io/dynamics_output.hpp"

#include <fstream>
#include <iterator>
#include <optional>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "common/error.hpp"
#include "io/json_file.hpp"

namespace sw {
namespace {

using nlohmann::json;

// Each struct's fields are listed once, as (JSON pointer, member) pairs, in a function that takes either a writer or
// a reader: the writer puts every field at its pointer, the reader takes it from there. The two cannot disagree on a
// key. Pointers are relative to the struct's own object.

/// Puts values into a JSON object (objects' keys come out sorted).
class Writer {
public:
  explicit Writer(json& j) : j_(j) {}
  template <class V>
  void operator()(const std::string& pointer, const V& v) { j_[json::json_pointer(pointer)] = v; }
  /// An enum as its case-file spelling.
  template <class E>
  void spelling(const std::string& pointer, const E& e, std::optional<E> (*)(const std::string&)) {
    (*this)(pointer, std::string(to_string(e)));
  }
  /// No key where there is no value.
  template <class V>
  void optional(const std::string& pointer, const std::optional<V>& v) {
    if (v) (*this)(pointer, *v);
  }
  /// A group of keys written by `fields` where there is a value, none where there is none (`marker`: its first key).
  template <class S, class Fields>
  void group(const std::string& /*marker*/, const std::optional<S>& v, Fields fields) {
    if (v) fields(*this, *v);
  }
  /// An array of objects, each written by `fields`.
  template <class S, class Fields>
  void array(const std::string& pointer, const std::vector<S>& items, Fields fields) {
    json a = json::array();
    for (const S& item : items) {
      json e;
      Writer w(e);
      fields(w, item);
      a.push_back(e);
    }
    (*this)(pointer, a);
  }

private:
  json& j_;
};

/// Takes values out of a JSON object; throws nlohmann's out_of_range naming a missing key, std::invalid_argument
/// naming a key of the wrong type or an unknown spelling.
class Reader {
public:
  explicit Reader(const json& j) : j_(j) {}
  template <class V>
  void operator()(const std::string& pointer, V& v) const {
    const json& at = j_.at(json::json_pointer(pointer));
    try {
      at.get_to(v);
    } catch (const json::type_error& e) {
      throw std::invalid_argument(pointer.substr(1) + ": " + e.what());
    }
  }
  template <class E>
  void spelling(const std::string& pointer, E& e, std::optional<E> (*parse)(const std::string&)) const {
    std::string text;
    (*this)(pointer, text);
    const std::optional<E> parsed = parse(text);
    if (!parsed) throw std::invalid_argument(pointer.substr(1) + " = \"" + text + "\" is not one of its spellings");
    e = *parsed;
  }
  template <class V>
  void optional(const std::string& pointer, std::optional<V>& v) const {
    v.reset();
    if (!j_.contains(json::json_pointer(pointer))) return;
    V value{};
    (*this)(pointer, value);
    v = value;
  }
  /// The group read by `fields` where its first key `marker` is, no value where it is not.
  template <class S, class Fields>
  void group(const std::string& marker, std::optional<S>& v, Fields fields) const {
    v.reset();
    if (!j_.contains(json::json_pointer(marker))) return;
    S value{};
    fields(*this, value);
    v = value;
  }
  template <class S, class Fields>
  void array(const std::string& pointer, std::vector<S>& items, Fields fields) const {
    items.clear();
    for (const json& e : j_.at(json::json_pointer(pointer))) {
      S item{};
      Reader r(e);
      fields(r, item);
      items.push_back(item);
    }
  }

private:
  const json& j_;
};

std::optional<PairMotion> parse_pair_motion(const std::string& s) {
  for (PairMotion m : {PairMotion::Frozen, PairMotion::Moving})
    if (s == to_string(m)) return m;
  return std::nullopt;
}

// The field lists. `C` is the struct, const for the writer.

template <class Io, class C>
void speed_check_fields(Io& io, C& c) {
  io("/body", c.body);
  io("/simulated_rpm", c.simulated_rpm);
  io("/theory_rpm", c.theory_rpm);
  io("/error_rel", c.error_rel);
}

template <class Io, class C>
void pair_force_check_fields(Io& io, C& c) {
  io("/pair", c.pair);
  io("/angle_deg", c.angle_deg);
  io("/arm_m", c.arm_m);
  io("/mean_N", c.mean_N);
  io("/quasi_static_N", c.quasi_static_N);
  io("/error_rel", c.error_rel);
}

template <class Io, class C>
void spectral_line_fields(Io& io, C& l) {
  io("/frequency_Hz", l.frequency_Hz);
  io("/amplitude_N", l.amplitude_N);
}

template <class Io, class C>
void order_line_fields(Io& io, C& l) {
  io("/frequency_Hz", l.frequency_Hz);
  io("/amplitude", l.amplitude);
  io("/mesh_order", l.mesh_order);
  io("/generator_order", l.generator_order);
}

/// The run's identity, its checks against kinematics and statics, and its balances.
template <class Io, class R>
void check_fields(Io& io, R& r) {
  io("/case_file", r.case_path);
  io.spelling("/configuration", r.configuration, parse_configuration);
  io("/teeth/flexspline", r.teeth_flexspline);
  io("/teeth/circular_spline", r.teeth_circular);
  io.spelling("/pairs", r.pairs, parse_pair_motion);
  io("/clearance_source", r.clearance_source);
  io.array("/speeds", r.speeds, [](auto& sub, auto& c) { speed_check_fields(sub, c); });
  io("/max_speed_error_rel", r.max_speed_error_rel);
  io.array("/pair_forces", r.pair_forces, [](auto& sub, auto& c) { pair_force_check_fields(sub, c); });
  io.optional("/max_pair_force_error_rel", r.max_pair_force_error_rel);
  io("/pairs_in_interference", r.pairs_in_interference);
  io("/total_force_at_rest_N", r.total_force_at_rest_N);
  io("/mesh_torque_Nm", r.mesh_torque_Nm);
  io("/mesh_torque_theory_Nm", r.mesh_torque_theory_Nm);
  io("/load_torque_Nm", r.load_torque_Nm);
  io("/torque_balance_error_rel", r.torque_balance_error_rel);
  io("/energy_error_rel", r.energy_error_rel);
  io("/energy_J/input", r.energy.input_J);
  io("/energy_J/parametric", r.energy.parametric_J);
  io("/energy_J/output", r.energy.output_J);
  io("/energy_J/dissipated", r.energy.dissipated_J);
  io("/energy_J/kinetic", r.energy.kinetic_J);
  io("/energy_J/potential", r.energy.potential_J);
}

/// The steady window's powers, the efficiency and the run's friction work (the flanks' and the generator bearing's).
template <class Io, class R>
void power_fields(Io& io, R& r) {
  io.group("/efficiency", r.steady_power, [&r](auto& sub, auto& p) {
    sub("/efficiency", p.efficiency);
    sub("/power_W/input", p.input_W);
    sub("/power_W/output", p.output_W);
    sub("/power_W/friction", p.friction_W);
    sub("/power_W/generator_bearing", p.bearing_W);
    sub("/power_W/dissipated", p.dissipated_W);
    sub("/power_W/stored", p.stored_W);
    sub("/power_balance_error_rel", p.balance_error_rel);
    sub("/contact_damping_exceeds_output", p.damping_exceeds_output);
    sub("/energy_J/friction", r.energy.friction_J);
    sub("/energy_J/generator_bearing", r.energy.bearing_J);
    sub("/generator_bearing_friction", r.bearing_source);
  });
}

/// The steady window: the total force, its spectrum and lines, the mesh's extremes.
template <class Io, class R>
void steady_window_fields(Io& io, R& r) {
  io("/steady_window_s/0", r.steady_window_start_s);
  io("/steady_window_s/1", r.steady_window_end_s);
  io("/mesh_frequency_Hz", r.mesh_frequency_Hz);
  io("/generator_frequency_Hz", r.generator_frequency_Hz);
  io("/mean_total_force_N", r.mean_total_force_N);
  io("/force_fluctuation_N", r.force_fluctuation_N);
  io("/spectrum_resolution_Hz", r.spectrum_resolution_Hz);
  io.array("/spectral_lines", r.spectral_lines, [](auto& sub, auto& l) { spectral_line_fields(sub, l); });
  io("/force_noise_floor_N", r.force_noise_floor_N);
  io("/transmission_error_noise_floor_rad", r.transmission_error_noise_floor_rad);
  const auto order_line = [](auto& sub, auto& l) { order_line_fields(sub, l); };
  io.array("/force_lines_in_orders", r.force_lines_in_orders, order_line);
  io.array("/transmission_error_lines_in_orders", r.transmission_error_lines_in_orders, order_line);
  io("/mesh_deflection_rad/min", r.mesh_deflection_min_rad);
  io("/mesh_deflection_rad/max", r.mesh_deflection_max_rad);
  io("/max_pair_force_N", r.max_pair_force_N);
  io("/flanks_in_contact/min", r.flanks_in_contact_min);
  io("/flanks_in_contact/max", r.flanks_in_contact_max);
  io("/transmission_error_peak_to_peak_rad", r.transmission_error_peak_to_peak_rad);
}

template <class Io, class P>
void parameter_fields(Io& io, P& p) {
  io("/parameters/drive_speed_rpm", p.drive_speed_rpm);
  io("/parameters/drive_ramp_s/0", p.drive_ramp_start_s);
  io("/parameters/drive_ramp_s/1", p.drive_ramp_end_s);
  io("/parameters/load_torque_Nm", p.load_torque_Nm);
  io("/parameters/load_ramp_s/0", p.load_ramp_start_s);
  io("/parameters/load_ramp_s/1", p.load_ramp_end_s);
  io.spelling("/parameters/ramp", p.ramp_shape, parse_ramp_shape);
  io("/parameters/stiffness_N_per_m", p.stiffness_N_per_m);
  io("/parameters/stiffness_variation_N_per_m", p.stiffness_variation_N_per_m);
  io("/parameters/damping_Ns_per_m", p.damping_Ns_per_m);
  io("/parameters/exponents/0", p.exponent_stiffness);
  io("/parameters/exponents/1", p.exponent_damping);
  io("/parameters/exponents/2", p.exponent_indentation);
  io("/parameters/flexspline_compliance_rad_per_Nm", p.flexspline_compliance_rad_per_Nm);
  io("/parameters/output_step_s", p.output_step_s);
  io("/parameters/duration_s", p.duration_s);
  io("/parameters/relative_tolerance", p.relative_tolerance);
}

/// The model's inertias and parameters, the output sampling, the integrator and the wall clock.
template <class Io, class R>
void run_fields(Io& io, R& r) {
  io("/output_sampling/oversampling", r.oversampling);
  io("/output_sampling/filter", r.output_filter);
  for (int b = 0; b < kBodyCount; ++b) io(std::string("/inertia_kgm2/") + body_name(BodyId(b)), r.inertia.kgm2[b]);
  parameter_fields(io, r.parameters);
  io("/solver/method", r.solver_method);
  io("/solver/steps", r.solver.steps);
  io("/solver/rhs_evals", r.solver.rhs_evals);
  io("/solver/jacobian_evals", r.solver.jac_evals);
  io("/solver/error_test_fails", r.solver.error_test_fails);
  io("/solver/newton_fails", r.solver.newton_fails);
  io("/timings_s/simulate", r.simulate_time_s);
  io("/timings_s/total", r.total_time_s);
  io("/real_time_factor", r.real_time_factor);
}

template <class Io, class R>
void result_fields(Io& io, R& r) {
  check_fields(io, r);
  power_fields(io, r);
  steady_window_fields(io, r);
  run_fields(io, r);
}

}  // namespace

std::string dynamics_json(const DynamicsResult& r, const std::optional<Provenance>& provenance) {
  json j;
  Writer w(j);
  result_fields(w, r);
  if (provenance) j.update(to_json_object(*provenance));
  return j.dump(2) + "\n";
}

DynamicsResult parse_dynamics_json(const std::string& text, const std::string& source) {
  try {
    const json j = json::parse(text);
    DynamicsResult r;
    Reader reader(j);
    result_fields(reader, r);
    return r;
  } catch (const json::exception& e) {
    throw InputError(source + ": not a dynamics.json of this version (" + e.what() +
                     "); write it again with `strainwave dynamics`");
  } catch (const std::invalid_argument& e) {
    throw InputError(source + ": " + e.what() + "; write it again with `strainwave dynamics`");
  }
}

DynamicsResult read_dynamics_json(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path.string() + ": cannot be read; expected a dynamics.json of `strainwave dynamics`");
  return parse_dynamics_json({std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()}, path.string());
}

}  // namespace sw
