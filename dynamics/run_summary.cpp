#include "dynamics/run_summary.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>

#include "common/constants.hpp"
#include "common/svg_plot.hpp"

namespace sw {
namespace {


void append(std::string& out, double v) {
  char buf[32];
  const int n = std::snprintf(buf, sizeof buf, "%.9g", v);
  out.append(buf, n);
}

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", std::abs(v) < 1e-12 ? 0.0 : v);
  return buf;
}

const char* kColors[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2", "#17becf"};

PlotSeries line(const std::vector<double>& x, const std::vector<double>& y, const std::string& colour, double width,
                const std::string& label = "") {
  PlotSeries s;
  s.label = label;
  s.x = x;
  s.y = y;
  s.colour = colour;
  s.line_width = width;
  return s;
}

LinePlot panel(const std::string& title, const std::string& x_label, const std::string& y_label) {
  LinePlot p;
  p.title = title;
  p.x_label = x_label;
  p.y_label = y_label;
  p.width = 1000;
  p.height = 290;
  return p;
}

}  // namespace

std::string dynamics_csv(const DynamicsModel& m, const DynamicsSeries& s) {
  std::string out;
  const auto bodies = reported_bodies(m.params);
  out += "time_s";
  for (BodyId b : bodies) out += std::string(",") + body_name(b) + "_speed_rpm";
  for (std::size_t i = 0; i < s.pair_force_N.size(); ++i)
    out += s.per_tooth ? ",tooth_" + std::to_string(i) + "_force_N" : ",pair_" + std::to_string(i + 1) + "_force_N";
  out += ",total_force_N,mesh_torque_Nm,drive_torque_Nm,load_torque_Nm,stiffness_N_per_m,mesh_deflection_rad,"
         "transmission_error_rad,flanks_in_contact,max_pair_force_N\n";
  out.reserve(s.time_s.size() * (16 * (bodies.size() + s.pair_force_N.size() + 10)));
  for (std::size_t j = 0; j < s.time_s.size(); ++j) {
    append(out, s.time_s[j]);
    for (BodyId b : bodies) { out += ','; append(out, s.speed_rad_s[int(b)][j] * kRpmPerRadS); }
    for (const auto& f : s.pair_force_N) { out += ','; append(out, f[j]); }
    for (const auto* v : {&s.total_force_N, &s.mesh_torque_Nm, &s.drive_torque_Nm, &s.load_torque_Nm,
                          &s.stiffness_N_per_m, &s.deflection_rad, &s.transmission_error_rad, &s.flanks_in_contact,
                          &s.max_pair_force_N}) {
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

namespace {

/// Frequencies of the lines in orders of f_m and f_g.
std::vector<OrderLine> in_orders(const std::vector<SpectralLine>& lines, double fm, double fg) {
  std::vector<OrderLine> out;
  for (const auto& l : lines)
    out.push_back({l.frequency_Hz, l.amplitude_N, fm > 0 ? l.frequency_Hz / fm : 0.0,
                   fg > 0 ? l.frequency_Hz / fg : 0.0});
  return out;
}

}  // namespace

DynamicsResult dynamics_result(const DynamicsModel& m, const DynamicsSeries& s, const DynamicsSummary& r,
                               const DynamicsReportInfo& info) {
  const auto& p = m.params;
  DynamicsResult d;
  d.case_path = info.case_path;
  d.configuration = p.configuration;
  d.teeth_flexspline = m.teeth_flexspline;
  d.teeth_circular = m.teeth_circular;
  d.pairs = m.moving ? PairMotion::Moving : PairMotion::Frozen;
  d.clearance_source = info.clearance_source;
  d.bearing_source = info.bearing_source;
  d.speeds = r.speeds;
  d.max_speed_error_rel = r.max_speed_error_rel;
  d.pair_forces = r.pair_forces;
  if (!m.moving) d.max_pair_force_error_rel = r.max_pair_force_error_rel;  // frozen pairs only: see summarize()
  for (const auto& tp : m.pairs)
    d.pairs_in_interference += (tp.clearance_drive_m < 0 || tp.clearance_coast_m < 0) ? 1 : 0;
  d.total_force_at_rest_N = s.total_force_N.empty() ? 0.0 : s.total_force_N.front();
  d.mesh_torque_Nm = r.mesh_torque_Nm;
  d.mesh_torque_theory_Nm = r.theory.mesh_torque_Nm;
  d.load_torque_Nm = r.theory.load_torque_Nm;
  d.torque_balance_error_rel = r.torque_balance_error_rel;
  d.energy_error_rel = r.energy_error_rel;
  d.energy = s.energy;
  d.steady_power = r.power;
  d.mesh_frequency_Hz = r.theory.mesh_frequency_Hz;
  d.generator_frequency_Hz = r.generator_frequency_Hz;
  d.mean_total_force_N = r.mean_total_force_N;
  d.force_fluctuation_N = r.force_fluctuation_N;
  d.spectrum_resolution_Hz = r.spectrum.resolution_Hz;
  d.spectral_lines = r.lines;
  d.force_noise_floor_N = r.noise_floor_N;
  d.transmission_error_noise_floor_rad = r.te_noise_floor_rad;
  d.force_lines_in_orders = in_orders(r.lines, r.theory.mesh_frequency_Hz, r.generator_frequency_Hz);
  d.transmission_error_lines_in_orders = in_orders(r.te_lines, r.theory.mesh_frequency_Hz, r.generator_frequency_Hz);
  d.steady_window_start_s = r.window_start_s;
  d.steady_window_end_s = p.duration_s;
  d.mesh_deflection_min_rad = r.deflection_min_rad;
  d.mesh_deflection_max_rad = r.deflection_max_rad;
  d.max_pair_force_N = r.max_pair_force_N;
  d.flanks_in_contact_min = r.flanks_in_contact_min;
  d.flanks_in_contact_max = r.flanks_in_contact_max;
  d.transmission_error_peak_to_peak_rad = r.te_peak_to_peak_rad;
  d.oversampling = p.oversampling;
  d.output_filter = "Blackman-windowed sinc, flat to 0.4/output_step_s, >= 74 dB from 0.5/output_step_s";
  d.inertia = m.inertia;
  d.parameters = p;
  d.solver_method = "CVODE BDF (SUNDIALS), dense Newton";
  d.solver = s.stats;
  d.simulate_time_s = info.simulate_time_s;
  d.total_time_s = info.total_time_s;
  d.real_time_factor = info.simulate_time_s > 0 ? p.duration_s / info.simulate_time_s : 0.0;
  return d;
}

namespace {

/// The figure's title line, the drive, load and contact law, and the checks over the steady window.
std::vector<std::string> svg_header(const DynamicsModel& m, const DynamicsSummary& r, const DynamicsReportInfo& info) {
  const auto& p = m.params;
  std::vector<std::string> lines;
  char head[512];
  const std::string pairs = m.moving ? std::to_string(m.moving->key_period()) + " teeth travelling"
                                     : std::to_string(m.pairs.size()) + " tooth pairs";
  std::snprintf(head, sizeof head, "strainwave dynamics: %s (z_f/z_c = %d/%d, %s, %s)", info.case_path.c_str(),
                m.teeth_flexspline, m.teeth_circular, to_string(p.configuration), pairs.c_str());
  lines.push_back(head);
  std::snprintf(head, sizeof head,
                "drive %.0f rpm (ramp %g–%g s, %s STEP), load %g N·m (ramp %g–%g s); contact k = %.3g%s N/m, c = %.3g "
                "N·s/m, m1/m2/m3 = %g/%g/%g",
                p.drive_speed_rpm, p.drive_ramp_start_s, p.drive_ramp_end_s, to_string(p.ramp_shape), p.load_torque_Nm,
                p.load_ramp_start_s, p.load_ramp_end_s, p.stiffness_N_per_m,
                p.stiffness_variation_N_per_m > 0
                    ? (" ± " + fmt(p.stiffness_variation_N_per_m) + " sin(2π f_m t)").c_str() : "",
                p.damping_Ns_per_m, p.exponent_stiffness, p.exponent_damping, p.exponent_indentation);
  lines.push_back(head);
  char quasi_static[64] = "";  // frozen pairs only: moving pairs meet the loaded contact in a slow run (tests)
  if (!m.moving) std::snprintf(quasi_static, sizeof quasi_static, "pair forces vs quasi-static %.2e, ", r.max_pair_force_error_rel);
  std::snprintf(head, sizeof head,
                "steady window %g–%g s: speed error %.2e, %storque balance %.2e, energy balance %.2e, f_m = %.2f Hz",
                r.window_start_s, p.duration_s, r.max_speed_error_rel, quasi_static, r.torque_balance_error_rel,
                r.energy_error_rel, r.theory.mesh_frequency_Hz);
  lines.push_back(head);
  return lines;
}

/// A panel over the run's time.
LinePlot time_panel(const std::string& title, const std::string& y_label, const DynamicsSeries& s) {
  LinePlot p = panel(title, "time (s)", y_label);
  p.x_range = {0.0, s.time_s.empty() ? 1.0 : s.time_s.back()};
  return p;
}

/// Speeds, each relative to its steady theory value, so a 1000 rpm input and a 10 rpm output share one axis.
LinePlot speeds_panel(const DynamicsModel& m, const DynamicsSeries& s, const DynamicsSummary& r) {
  LinePlot sp = time_panel("Speeds (each divided by its steady kinematic value)", "speed / steady speed", s);
  sp.y_range = {-0.1, 1.2};
  const auto& t = s.time_s;
  int row = 0;
  for (BodyId b : reported_bodies(m.params)) {
    const double th = r.theory.speed_rad_s[int(b)];
    if (th == 0.0) continue;
    std::vector<double> y(t.size());
    for (std::size_t j = 0; j < t.size(); ++j) y[j] = s.speed_rad_s[int(b)][j] / th;
    sp.series.push_back(line(t, y, kColors[row % 8], 1.5,
                             std::string(body_name(b)) + " (steady " + fmt(th * kRpmPerRadS) + " rpm)"));
    ++row;
  }
  return sp;
}

/// Pair forces: the strongest four in colour, the rest grey beneath them; moving pairs: every tooth's force as it
/// travels through the zones.
LinePlot pair_forces_panel(const DynamicsModel& m, const DynamicsSeries& s, const DynamicsSummary& r) {
  LinePlot pf = time_panel(
      "Tooth-pair forces (signed: drive flank positive), " + std::to_string(m.pairs.size()) + " pairs",
      "pair force (N)", s);
  const auto& t = s.time_s;
  std::vector<std::size_t> order(m.pairs.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](auto a, auto b) {
    return std::abs(r.pair_forces[a].mean_N) > std::abs(r.pair_forces[b].mean_N);
  });
  for (std::size_t k = order.size(); k-- > 0;) {
    const std::size_t i = order[k];
    if (k >= 4) { pf.series.push_back(line(t, s.pair_force_N[i], "#bbb", 0.7)); continue; }
    pf.series.push_back(line(t, s.pair_force_N[i], kColors[k], 1.4,
                             "pair " + std::to_string(i + 1) + " at " +
                                 fmt(std::round(r.pair_forces[i].angle_deg * 10) / 10) + "°: mean " +
                                 fmt(std::round(r.pair_forces[i].mean_N)) + " N"));
  }
  if (!s.per_tooth) return pf;
  for (std::size_t i = 0; i < s.pair_force_N.size(); ++i)
    pf.series.push_back(line(t, s.pair_force_N[i], i % 8 == 0 ? kColors[(i / 8) % 8] : "#bbb", i % 8 == 0 ? 1.2 : 0.6,
                             i % 8 == 0 && i < 32 ? "tooth " + std::to_string(i) : ""));
  pf.title =
      "Tooth forces (signed: ccw flank positive), " + std::to_string(s.pair_force_N.size()) + " teeth travelling";
  return pf;
}

LinePlot transmission_error_panel(const DynamicsSeries& s) {
  LinePlot te = time_panel("Transmission error (output angle minus the kinematic one) and flanks in contact",
                           "transmission error (µrad)", s);
  std::vector<double> y(s.time_s.size());
  for (std::size_t j = 0; j < y.size(); ++j) y[j] = s.transmission_error_rad[j] * 1e6;
  te.series.push_back(line(s.time_s, y, "#2ca02c", 1.2, "transmission error"));
  return te;
}

LinePlot flanks_panel(const DynamicsSeries& s) {
  LinePlot nc = time_panel("Tooth flanks in contact", "flanks", s);
  nc.series.push_back(line(s.time_s, s.flanks_in_contact, "#9467bd", 1.2));
  return nc;
}

LinePlot total_force_panel(const DynamicsSeries& s, const DynamicsSummary& r) {
  LinePlot tf = time_panel("Total meshing force Σ|F_i| (mean in the steady window " +
                               fmt(std::round(r.mean_total_force_N)) + " N, rms fluctuation " +
                               fmt(r.force_fluctuation_N) + " N)",
                           "total force (N)", s);
  tf.series.push_back(line(s.time_s, s.total_force_N, "#1f77b4", 1.2));
  return tf;
}

/// Spectrum of the total force in the steady window, eight decades below its strongest line, with f_m and its
/// harmonics marked and the three strongest lines in the legend.
LinePlot spectrum_panel(const DynamicsSummary& r) {
  const auto& sa = r.spectrum.amplitude_N;
  double amax = 1e-300;
  for (std::size_t k = 1; k < sa.size(); ++k) amax = std::max(amax, sa[k]);
  const double top = std::ceil(std::log10(amax) + 0.3);
  const double fmax_plot = std::min(r.spectrum.frequency_Hz.empty() ? 1.0 : r.spectrum.frequency_Hz.back(),
                                    std::max(5.0 * r.theory.mesh_frequency_Hz, 1000.0));
  LinePlot fs = panel("Spectrum of the total meshing force (steady window, Hann), f_m and its harmonics dashed",
                      "frequency (Hz)", "amplitude (N)");
  fs.log_y = true;
  fs.x_range = {0.0, fmax_plot};
  fs.y_range = {std::pow(10.0, top - 8), std::pow(10.0, top)};
  std::vector<double> fx, fy;
  for (std::size_t k = 1; k < sa.size() && r.spectrum.frequency_Hz[k] <= fmax_plot; ++k) {
    fx.push_back(r.spectrum.frequency_Hz[k]);
    fy.push_back(sa[k]);
  }
  fs.series.push_back(line(fx, fy, "#d62728", 1.0));
  for (std::size_t k = 0; k < r.lines.size() && k < 3; ++k)
    fs.series.push_back(line({}, {}, "#d62728", 1.0, fmt(std::round(r.lines[k].frequency_Hz * 10) / 10) + " Hz: " +
                                                        fmt(r.lines[k].amplitude_N) + " N"));
  for (int h = 1; h * r.theory.mesh_frequency_Hz <= fmax_plot; ++h) fs.x_marks.push_back(h * r.theory.mesh_frequency_Hz);
  return fs;
}

}  // namespace

std::string dynamics_svg(const DynamicsModel& m, const DynamicsSeries& s, const DynamicsSummary& r,
                         const DynamicsReportInfo& info) {
  Figure fig;
  fig.header = svg_header(m, r, info);
  fig.panels.push_back(speeds_panel(m, s, r));
  fig.panels.push_back(pair_forces_panel(m, s, r));
  if (s.per_tooth) {
    fig.panels.push_back(transmission_error_panel(s));
    fig.panels.push_back(flanks_panel(s));
  }
  fig.panels.push_back(total_force_panel(s, r));
  fig.panels.push_back(spectrum_panel(r));
  std::ostringstream foot;
  foot << "clearances: " << info.clearance_source << "; integrator CVODE BDF, " << s.stats.steps
       << " steps; wall time " << fmt(info.simulate_time_s) << " s";
  fig.footer.push_back(foot.str());
  return svg_figure(fig);
}

}  // namespace sw
