#include "dynamics/report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>

#include <nlohmann/json.hpp>

namespace sw {
namespace {

constexpr double kRpmPerRadS = 60.0 / (2.0 * std::numbers::pi);

std::vector<BodyId> reported_bodies(const DynamicsModel& m) {
  std::vector<BodyId> b{BodyId::WaveGenerator, BodyId::FlexsplineFlange, BodyId::CircularSpline};
  if (m.params.flexspline_compliance_rad_per_Nm > 0) b.insert(b.begin() + 1, BodyId::FlexsplineRim);
  return b;
}

void append(std::string& out, double v) {
  char buf[32];
  const int n = std::snprintf(buf, sizeof buf, "%.9g", v);
  out.append(buf, n);
}

// --- a minimal SVG plotter -------------------------------------------------------------------------------------------
struct Panel {
  double x, y, w, h;          // pixel box of the plot area
  double x0, x1, y0, y1;      // data range
  bool log_y = false;
  double px(double v) const { return x + (v - x0) / (x1 - x0) * w; }
  double py(double v) const {
    if (log_y) v = std::log10(std::max(v, std::pow(10.0, y0)));
    return y + h - (v - y0) / (y1 - y0) * h;
  }
};

double nice_step(double range, int target) {
  const double raw = range / target, mag = std::pow(10.0, std::floor(std::log10(raw)));
  for (double f : {1.0, 2.0, 2.5, 5.0, 10.0})
    if (raw <= f * mag) return f * mag;
  return 10.0 * mag;
}

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", std::abs(v) < 1e-12 ? 0.0 : v);
  return buf;
}

std::string escape(const std::string& s) {
  std::string o;
  for (char c : s) {
    if (c == '<') o += "&lt;";
    else if (c == '>') o += "&gt;";
    else if (c == '&') o += "&amp;";
    else o += c;
  }
  return o;
}

void frame(std::ostringstream& o, const Panel& p, const std::string& title, const std::string& xlabel,
           const std::string& ylabel) {
  o << "<rect x='" << p.x << "' y='" << p.y << "' width='" << p.w << "' height='" << p.h
    << "' fill='none' stroke='#444'/>\n";
  o << "<text x='" << p.x << "' y='" << p.y - 8 << "' font-size='14' font-weight='bold'>" << escape(title) << "</text>\n";
  o << "<text x='" << p.x + p.w / 2 << "' y='" << p.y + p.h + 34 << "' font-size='12' text-anchor='middle'>"
    << escape(xlabel) << "</text>\n";
  o << "<text transform='translate(" << p.x - 58 << "," << p.y + p.h / 2 << ") rotate(-90)' font-size='12' "
    << "text-anchor='middle'>" << escape(ylabel) << "</text>\n";
  const double sx = nice_step(p.x1 - p.x0, 8);
  for (double v = std::ceil(p.x0 / sx) * sx; v <= p.x1 + 1e-9 * sx; v += sx) {
    o << "<line x1='" << p.px(v) << "' x2='" << p.px(v) << "' y1='" << p.y << "' y2='" << p.y + p.h
      << "' stroke='#ddd'/><text x='" << p.px(v) << "' y='" << p.y + p.h + 16
      << "' font-size='11' text-anchor='middle'>" << fmt(v) << "</text>\n";
  }
  if (p.log_y) {
    for (int e = int(std::ceil(p.y0)); e <= int(std::floor(p.y1)); ++e)
      o << "<line x1='" << p.x << "' x2='" << p.x + p.w << "' y1='" << p.py(std::pow(10.0, e)) << "' y2='"
        << p.py(std::pow(10.0, e)) << "' stroke='#ddd'/><text x='" << p.x - 6 << "' y='" << p.py(std::pow(10.0, e)) + 4
        << "' font-size='11' text-anchor='end'>1e" << e << "</text>\n";
  } else {
    const double sy = nice_step(p.y1 - p.y0, 6);
    for (double v = std::ceil(p.y0 / sy) * sy; v <= p.y1 + 1e-9 * sy; v += sy)
      o << "<line x1='" << p.x << "' x2='" << p.x + p.w << "' y1='" << p.py(v) << "' y2='" << p.py(v)
        << "' stroke='#ddd'/><text x='" << p.x - 6 << "' y='" << p.py(v) + 4 << "' font-size='11' text-anchor='end'>"
        << fmt(v) << "</text>\n";
  }
}

/// Polyline of (x, y) with min/max decimation to about 2·buckets points, so narrow peaks survive.
void line(std::ostringstream& o, const Panel& p, const std::vector<double>& x, const std::vector<double>& y,
          const std::string& color, double width, std::size_t from = 0, int buckets = 700) {
  const std::size_t n = x.size();
  if (n <= from + 1) return;
  o << "<polyline fill='none' stroke='" << color << "' stroke-width='" << width << "' points='";
  const std::size_t per = std::max<std::size_t>(1, (n - from) / buckets);
  for (std::size_t i = from; i < n; i += per) {
    const std::size_t end = std::min(n, i + per);
    std::size_t lo = i, hi = i;
    for (std::size_t j = i; j < end; ++j) {
      if (y[j] < y[lo]) lo = j;
      if (y[j] > y[hi]) hi = j;
    }
    const std::size_t a = std::min(lo, hi), b = std::max(lo, hi);
    o << p.px(x[a]) << ',' << p.py(y[a]) << ' ';
    if (b != a) o << p.px(x[b]) << ',' << p.py(y[b]) << ' ';
  }
  o << "'/>\n";
}

void legend(std::ostringstream& o, const Panel& p, int row, const std::string& color, const std::string& text) {
  const double y = p.y + 16 + 16 * row;
  o << "<rect x='" << p.x + p.w - 256 << "' y='" << y - 12 << "' width='252' height='16' fill='white' "
    << "fill-opacity='0.85'/>\n";
  o << "<line x1='" << p.x + p.w - 250 << "' x2='" << p.x + p.w - 230 << "' y1='" << y - 4 << "' y2='" << y - 4
    << "' stroke='" << color << "' stroke-width='2'/><text x='" << p.x + p.w - 225 << "' y='" << y
    << "' font-size='11'>" << escape(text) << "</text>\n";
}

const char* kColors[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2", "#17becf"};

}  // namespace

std::string dynamics_csv(const DynamicsModel& m, const DynamicsSeries& s) {
  std::string out;
  const auto bodies = reported_bodies(m);
  out += "time_s";
  for (BodyId b : bodies) out += std::string(",") + body_name(b) + "_speed_rpm";
  for (std::size_t i = 0; i < m.pairs.size(); ++i) out += ",pair_" + std::to_string(i + 1) + "_force_N";
  out += ",total_force_N,mesh_torque_Nm,drive_torque_Nm,load_torque_Nm,stiffness_N_per_m\n";
  out.reserve(s.time_s.size() * (16 * (bodies.size() + m.pairs.size() + 6)));
  for (std::size_t j = 0; j < s.time_s.size(); ++j) {
    append(out, s.time_s[j]);
    for (BodyId b : bodies) { out += ','; append(out, s.speed_rad_s[int(b)][j] * kRpmPerRadS); }
    for (const auto& f : s.pair_force_N) { out += ','; append(out, f[j]); }
    for (const auto* v : {&s.total_force_N, &s.mesh_torque_Nm, &s.drive_torque_Nm, &s.load_torque_Nm,
                          &s.stiffness_N_per_m}) {
      out += ',';
      append(out, (*v)[j]);
    }
    out += '\n';
  }
  return out;
}

std::string dynamics_recording(const DynamicsModel& m, const DynamicsSeries& s,
                               const std::vector<std::string>& extra_metadata) {
  const SteadyState ss = steady_state(m);
  const auto& p = m.params;
  std::string out = "# strainwave-recording: 1\n# kind: dynamics\n";
  out += "# source: strainwave dynamics model (" + std::string(to_string(p.configuration)) + ")\n";
  out += "# teeth_flexspline: " + std::to_string(m.teeth_flexspline) + "\n";
  out += "# teeth_circular: " + std::to_string(m.teeth_circular) + "\n";
  out += "# output_body: " + std::string(body_name(ss.output)) + "\n";
  for (const auto& line : extra_metadata) out += "# " + line + "\n";
  out += "time_s,wg_speed_rpm,output_speed_rpm,mesh_force_N\n";
  const int wg = static_cast<int>(BodyId::WaveGenerator), o = static_cast<int>(ss.output);
  for (std::size_t j = 0; j < s.time_s.size(); ++j) {
    append(out, s.time_s[j]);
    out += ',';
    append(out, s.speed_rad_s[wg][j] * kRpmPerRadS);
    out += ',';
    append(out, s.speed_rad_s[o][j] * kRpmPerRadS);
    out += ',';
    append(out, s.total_force_N[j]);
    out += '\n';
  }
  return out;
}

std::string dynamics_json(const DynamicsModel& m, const DynamicsSeries& s, const DynamicsSummary& r,
                          const DynamicsReportInfo& info) {
  using nlohmann::json;
  const auto& p = m.params;
  json j;
  j["case"] = info.case_path;
  j["configuration"] = to_string(p.configuration);
  j["teeth"] = {{"flexspline", m.teeth_flexspline}, {"circular_spline", m.teeth_circular}};
  j["speeds"] = json::array();
  for (const auto& c : r.speeds)
    j["speeds"].push_back({{"body", c.body}, {"simulated_rpm", c.simulated_rpm}, {"theory_rpm", c.theory_rpm},
                           {"error_rel", c.error_rel}});
  j["max_speed_error_rel"] = r.max_speed_error_rel;
  j["pair_forces"] = json::array();
  for (const auto& c : r.pair_forces)
    j["pair_forces"].push_back({{"pair", c.pair}, {"angle_deg", c.angle_deg}, {"arm_m", c.arm_m},
                                {"mean_N", c.mean_N}, {"quasi_static_N", c.quasi_static_N}, {"error_rel", c.error_rel}});
  j["max_pair_force_error_rel"] = r.max_pair_force_error_rel;
  int interfering = 0;
  for (const auto& tp : m.pairs) interfering += (tp.clearance_drive_m < 0 || tp.clearance_coast_m < 0) ? 1 : 0;
  j["pairs_in_interference"] = interfering;  // negative clearance at rest: carried as contact preload
  j["total_force_at_rest_N"] = s.total_force_N.empty() ? 0.0 : s.total_force_N.front();
  j["mesh_torque_Nm"] = r.mesh_torque_Nm;
  j["mesh_torque_theory_Nm"] = r.theory.mesh_torque_Nm;
  j["load_torque_Nm"] = r.theory.load_torque_Nm;
  j["torque_balance_error_rel"] = r.torque_balance_error_rel;
  j["energy_error_rel"] = r.energy_error_rel;
  j["energy_J"] = {{"input", s.energy.input_J}, {"parametric", s.energy.parametric_J}, {"output", s.energy.output_J},
                   {"dissipated", s.energy.dissipated_J}, {"kinetic", s.energy.kinetic_J},
                   {"potential", s.energy.potential_J}};
  j["mesh_frequency_Hz"] = r.theory.mesh_frequency_Hz;
  j["mean_total_force_N"] = r.mean_total_force_N;
  j["force_fluctuation_N"] = r.force_fluctuation_N;
  j["spectrum_resolution_Hz"] = r.spectrum.resolution_Hz;
  j["spectral_lines"] = json::array();
  for (const auto& l : r.lines) j["spectral_lines"].push_back({{"frequency_Hz", l.frequency_Hz}, {"amplitude_N", l.amplitude_N}});
  j["steady_window_s"] = {r.window_start_s, p.duration_s};
  j["clearance_source"] = info.clearance_source;
  json inertia;
  for (int b = 0; b < kBodyCount; ++b) inertia[body_name(BodyId(b))] = m.inertia.kgm2[b];
  j["inertia_kgm2"] = inertia;
  j["parameters"] = {{"drive_speed_rpm", p.drive_speed_rpm}, {"drive_ramp_s", {p.drive_ramp_start_s, p.drive_ramp_end_s}},
                     {"load_torque_Nm", p.load_torque_Nm}, {"load_ramp_s", {p.load_ramp_start_s, p.load_ramp_end_s}},
                     {"ramp", to_string(p.ramp_shape)}, {"stiffness_N_per_m", p.stiffness_N_per_m},
                     {"stiffness_variation_N_per_m", p.stiffness_variation_N_per_m},
                     {"damping_Ns_per_m", p.damping_Ns_per_m},
                     {"exponents", {p.exponent_stiffness, p.exponent_damping, p.exponent_indentation}},
                     {"flexspline_compliance_rad_per_Nm", p.flexspline_compliance_rad_per_Nm},
                     {"output_step_s", p.output_step_s}, {"duration_s", p.duration_s},
                     {"relative_tolerance", p.relative_tolerance}};
  j["solver"] = {{"method", "CVODE BDF (SUNDIALS), dense Newton"}, {"steps", s.stats.steps},
                 {"rhs_evals", s.stats.rhs_evals}, {"jacobian_evals", s.stats.jac_evals},
                 {"error_test_fails", s.stats.error_test_fails}, {"newton_fails", s.stats.newton_fails}};
  j["timings_s"] = {{"simulate", info.simulate_time_s}, {"total", info.total_time_s}};
  j["real_time_factor"] = info.simulate_time_s > 0 ? p.duration_s / info.simulate_time_s : 0.0;
  return j.dump(2) + "\n";
}

std::string dynamics_svg(const DynamicsModel& m, const DynamicsSeries& s, const DynamicsSummary& r,
                         const DynamicsReportInfo& info) {
  const auto& p = m.params;
  std::ostringstream o;
  o.precision(5);
  const double W = 1000, H = 1240;
  o << "<svg xmlns='http://www.w3.org/2000/svg' width='" << W << "' height='" << H << "' viewBox='0 0 " << W << ' '
    << H << "' font-family='sans-serif'>\n<rect width='100%' height='100%' fill='white'/>\n";
  char head[512];
  std::snprintf(head, sizeof head, "strainwave dynamics: %s (z_f/z_c = %d/%d, %s, %zu tooth pairs)",
                info.case_path.c_str(), m.teeth_flexspline, m.teeth_circular, to_string(p.configuration),
                m.pairs.size());
  o << "<text x='20' y='24' font-size='15' font-weight='bold'>" << escape(head) << "</text>\n";
  std::snprintf(head, sizeof head,
                "drive %.0f rpm (ramp %g–%g s, %s STEP), load %g N·m (ramp %g–%g s); contact k = %.3g%s N/m, c = %.3g "
                "N·s/m, m1/m2/m3 = %g/%g/%g",
                p.drive_speed_rpm, p.drive_ramp_start_s, p.drive_ramp_end_s, to_string(p.ramp_shape), p.load_torque_Nm,
                p.load_ramp_start_s, p.load_ramp_end_s, p.stiffness_N_per_m,
                p.stiffness_variation_N_per_m > 0
                    ? (" ± " + fmt(p.stiffness_variation_N_per_m) + " sin(2π f_m t)").c_str() : "",
                p.damping_Ns_per_m, p.exponent_stiffness, p.exponent_damping, p.exponent_indentation);
  o << "<text x='20' y='42' font-size='11'>" << escape(head) << "</text>\n";
  std::snprintf(head, sizeof head,
                "steady window %g–%g s: speed error %.2e, pair forces vs quasi-static %.2e, torque balance %.2e, "
                "energy balance %.2e, f_m = %.2f Hz",
                r.window_start_s, p.duration_s, r.max_speed_error_rel, r.max_pair_force_error_rel,
                r.torque_balance_error_rel, r.energy_error_rel, r.theory.mesh_frequency_Hz);
  o << "<text x='20' y='58' font-size='11'>" << escape(head) << "</text>\n";
  const auto& t = s.time_s;
  const double tmax = t.empty() ? 1.0 : t.back();

  // 1. Speeds, each relative to its steady theory value, so a 1000 rpm input and a 10 rpm output share one axis.
  Panel sp{80, 90, 880, 220, 0, tmax, -0.1, 1.2};
  frame(o, sp, "Speeds (each divided by its steady kinematic value)", "time [s]", "speed / steady speed");
  int row = 0;
  std::ostringstream leg;  // legends go on top of the lines
  for (BodyId b : reported_bodies(m)) {
    const double th = r.theory.speed_rad_s[int(b)];
    if (th == 0.0) continue;
    std::vector<double> y(t.size());
    for (std::size_t j = 0; j < t.size(); ++j) y[j] = s.speed_rad_s[int(b)][j] / th;
    line(o, sp, t, y, kColors[row % 8], 1.5);
    legend(leg, sp, row, kColors[row % 8], std::string(body_name(b)) + " (steady " + fmt(th * kRpmPerRadS) + " rpm)");
    ++row;
  }
  o << leg.str();
  leg.str("");

  // 2. Pair forces.
  double fmax = 0.0, fmin = 0.0;
  for (const auto& f : s.pair_force_N)
    for (double v : f) { fmax = std::max(fmax, v); fmin = std::min(fmin, v); }
  Panel pf{80, 370, 880, 220, 0, tmax, fmin, fmax > fmin ? fmax * 1.08 : 1.0};
  frame(o, pf, "Tooth-pair forces (signed: drive flank positive), " + std::to_string(m.pairs.size()) + " pairs",
        "time [s]", "pair force [N]");
  // Strongest pairs in colour, the rest grey.
  std::vector<std::size_t> order(m.pairs.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](auto a, auto b) {
    return std::abs(r.pair_forces[a].mean_N) > std::abs(r.pair_forces[b].mean_N);
  });
  for (std::size_t k = order.size(); k-- > 0;) {
    const std::size_t i = order[k];
    const bool strong = k < 4;
    line(o, pf, t, s.pair_force_N[i], strong ? kColors[k] : "#bbb", strong ? 1.4 : 0.7);
    if (strong)
      legend(leg, pf, int(k), kColors[k], "pair " + std::to_string(i + 1) + " at " + fmt(std::round(r.pair_forces[i].angle_deg * 10) / 10) +
                                        "°: mean " + fmt(std::round(r.pair_forces[i].mean_N)) + " N");
  }

  o << leg.str();
  leg.str("");

  // 3. Total meshing force.
  double tmin = 0, tmx = 0;
  for (double v : s.total_force_N) tmx = std::max(tmx, v);
  Panel tf{80, 650, 880, 220, 0, tmax, tmin, tmx > 0 ? tmx * 1.08 : 1.0};
  frame(o, tf, "Total meshing force Σ|F_i| (mean in the steady window " + fmt(std::round(r.mean_total_force_N)) +
               " N, rms fluctuation " + fmt(r.force_fluctuation_N) + " N)", "time [s]", "total force [N]");
  line(o, tf, t, s.total_force_N, "#1f77b4", 1.2);

  // 4. Spectrum of the total force in the steady window.
  const auto& sa = r.spectrum.amplitude_N;
  double amax = 1e-300;
  for (std::size_t k = 1; k < sa.size(); ++k) amax = std::max(amax, sa[k]);
  const double top = std::ceil(std::log10(amax) + 0.3), fmax_plot = std::min(r.spectrum.frequency_Hz.empty() ? 1.0 : r.spectrum.frequency_Hz.back(),
                                                                            std::max(5.0 * r.theory.mesh_frequency_Hz, 1000.0));
  Panel fs{80, 930, 880, 240, 0, fmax_plot, top - 8, top, true};
  frame(o, fs, "Spectrum of the total meshing force (steady window, Hann), f_m dashed", "frequency [Hz]",
        "amplitude [N]");
  std::vector<double> fx, fy;
  for (std::size_t k = 1; k < sa.size() && r.spectrum.frequency_Hz[k] <= fmax_plot; ++k) {
    fx.push_back(r.spectrum.frequency_Hz[k]);
    fy.push_back(sa[k]);
  }
  line(o, fs, fx, fy, "#d62728", 1.0, 0, 2000);
  for (int h = 1; h * r.theory.mesh_frequency_Hz <= fmax_plot; ++h)
    o << "<line x1='" << fs.px(h * r.theory.mesh_frequency_Hz) << "' x2='" << fs.px(h * r.theory.mesh_frequency_Hz)
      << "' y1='" << fs.y << "' y2='" << fs.y + fs.h << "' stroke='#555' stroke-dasharray='4,4'/>\n";
  for (std::size_t k = 0; k < r.lines.size() && k < 3; ++k)
    legend(o, fs, int(k), "#d62728", fmt(std::round(r.lines[k].frequency_Hz * 10) / 10) + " Hz: " +
                                       fmt(r.lines[k].amplitude_N) + " N");
  o << "<text x='20' y='" << H - 20 << "' font-size='11'>clearances: " << escape(info.clearance_source)
    << "; integrator CVODE BDF, " << s.stats.steps << " steps; wall time " << fmt(info.simulate_time_s) << " s</text>\n";
  o << "</svg>\n";
  return o.str();
}

}  // namespace sw
