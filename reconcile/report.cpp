#include "reconcile/report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <fftw3.h>
#include <nlohmann/json.hpp>

#include "common/svg_plot.hpp"
#include "reconcile/catalog.hpp"

namespace sw::reconcile {

using Vec = Eigen::VectorXd;

namespace {

std::string num(double v, const char* f = "%.4g") {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

nlohmann::json location_json(const Location& l) {
  return {{"domain", l.domain}, {"description", l.description}, {"p_value", l.p_value}};
}

/// The response as people read it: angles in arcmin, the rest as recorded.
struct Display {
  double scale = 1.0;
  std::string label;  ///< e.g. "twist (arcmin)"
};

Display display_of(const Experiment& e) {
  std::string name = e.response_name.substr(0, e.response_name.rfind('_'));
  std::replace(name.begin(), name.end(), '_', ' ');
  if (e.response_unit == "rad") return {kArcminPerRad, name + " (arcmin)"};
  return {1.0, name + " (" + (e.response_unit == "um" ? std::string("µm") : e.response_unit) + ")"};
}

/// A series of the page's plots: a line, or the recording's samples as faint dots.
PlotSeries series(const std::string& label, const std::string& colour, const Vec& x, const Vec& y, double scale,
                  bool samples = false) {
  PlotSeries s;
  s.label = label;
  s.colour = colour;
  s.x.assign(x.data(), x.data() + x.size());
  for (Eigen::Index i = 0; i < y.size(); ++i) s.y.push_back(scale * y[i]);
  s.markers = samples;
  s.marker_radius = 1.2;
  s.opacity = samples ? 0.5 : 1.0;
  s.line_width = 1.2;
  return s;
}

std::string plot(const std::string& title, const std::string& x_label, const std::string& y_label,
                 std::vector<PlotSeries> lines, const std::vector<std::pair<double, double>>& bands = {}) {
  LinePlot p;
  p.title = title;
  p.x_label = x_label;
  p.y_label = y_label;
  p.series = std::move(lines);
  p.height = 300;
  p.x_bands = bands;
  return svg_line_plot(p);
}

nlohmann::json catalog_json(const CatalogFigures& c) {
  nlohmann::json j = {{"segments", c.segments},
                      {"K1_Nm_per_rad", c.k1},
                      {"K2_Nm_per_rad", c.k2},
                      {"K3_Nm_per_rad", c.k3},
                      {"T1_Nm", c.t1},
                      {"T2_Nm", c.t2},
                      {"rated_torque_Nm", c.rated_torque_Nm},
                      {"rated_torque_from", c.rated_from},
                      {"hysteresis_loss_arcmin", c.hysteresis_loss_arcmin},
                      {"play_width_arcmin", c.play_arcmin},
                      {"catalog_lost_motion_arcmin", c.catalog_lost_motion_arcmin},
                      {"note", "catalog_lost_motion_arcmin is the twist between -4 % and +4 % of rated torque on the "
                               "loop's middle line (it includes elastic twist); play_width_arcmin is the dead band of "
                               "the effect lost_motion (width_rad)"}};
  if (c.reference)
    j["reference"] = {{"size", c.reference->size},
                      {"K1_Nm_per_rad", c.reference->k1_Nm_per_rad},
                      {"K2_Nm_per_rad", c.reference->k2_Nm_per_rad},
                      {"K3_Nm_per_rad", c.reference->k3_Nm_per_rad},
                      {"T1_Nm", c.reference->t1_Nm},
                      {"T2_Nm", c.reference->t2_Nm},
                      {"rated_torque_Nm", c.reference->rated_torque_Nm},
                      {"hysteresis_loss_max_arcmin", 1.0},
                      {"lost_motion_max_arcmin", 1.0}};
  return j;
}

std::string catalog_html(const CatalogFigures& c) {
  const CatalogDrive* ref = c.reference;
  auto row = [&](const std::string& name, double v, const std::string& catalog) {
    return "<tr><td>" + name + "</td><td>" + num(v) + "</td><td>" + catalog + "</td></tr>";
  };
  std::string h = "<h2>In catalog terms</h2><table><tr><th>figure</th><th>fitted</th><th>catalog" +
                  (ref ? " (size " + std::to_string(ref->size) + ")" : std::string()) + "</th></tr>";
  h += row("K1 (N*m/rad)", c.k1, ref ? num(ref->k1_Nm_per_rad) : "");
  if (c.segments >= 2) h += row("T1 (N*m)", c.t1, ref ? num(ref->t1_Nm) : "");
  if (c.segments >= 2) h += row("K2 (N*m/rad)", c.k2, ref ? num(ref->k2_Nm_per_rad) : "");
  if (c.segments == 3) h += row("T2 (N*m)", c.t2, ref ? num(ref->t2_Nm) : "");
  if (c.segments == 3) h += row("K3 (N*m/rad)", c.k3, ref ? num(ref->k3_Nm_per_rad) : "");
  h += row("hysteresis loss at +-" + num(c.rated_torque_Nm) + " N*m (arcmin)", c.hysteresis_loss_arcmin,
           ref ? "< 1" : "");
  h += row("lost motion, catalog: twist between +-4 % rated on the middle line, elastic twist included (arcmin)",
           c.catalog_lost_motion_arcmin, ref ? "< 1" : "");
  h += row("play: dead band of the effect lost_motion (arcmin)", c.play_arcmin, "");
  h += "</table><p>Rated torque from " + html_escape(c.rated_from) + ".</p>";
  return h;
}

/// The baseline in words, for the page.
std::string baseline_description(const Experiment& e) {
  const std::string model = baseline_model(e);
  std::string d;
  if (model == "fem") d = "C_tau T, the flexspline body's torsional compliance (C_tau = " + num(e.model.compliance_rad_per_Nm) + " rad/(N*m))";
  else if (model == "contact") d = "the drive's torque-twist curve from the loaded tooth contact (middle line of its loop)";
  else if (model == "curve") d = "a torque-twist curve";
  else if (model == "ideal_ratio") d = "the ideal ratio, output = -wg (z_c - z_f)/z_f";
  else if (model == "kinematic") d = "the basic kinematic backlash model (phi0 = 0)";
  else if (model == "dynamics_model") d = "the dynamics model with constant mesh stiffness";
  else d = model;
  return d + (e.model.source.empty() ? "" : ", from " + e.model.source);
}


}  // namespace

Spectrum order_spectrum(const Vec& angle_rad, const Vec& y, double max_order) {
  Spectrum out;
  const int n = static_cast<int>(angle_rad.size());
  if (n < 8) return out;
  // Sort by angle (backlash rows repeat the angle at each torque level: use the first sweep only if not monotone).
  std::vector<int> idx;
  idx.push_back(0);
  for (int i = 1; i < n && angle_rad[i] > angle_rad[idx.back()]; ++i) idx.push_back(i);
  const int m = static_cast<int>(idx.size());
  if (m < 8) return out;
  const double a0 = angle_rad[idx.front()], a1 = angle_rad[idx.back()];
  const double revolutions = (a1 - a0) / (2.0 * M_PI);
  if (!(revolutions > 0.0)) return out;
  std::vector<double> u(m);
  int j = 0;
  for (int k = 0; k < m; ++k) {  // linear interpolation onto a uniform grid
    const double a = a0 + (a1 - a0) * k / (m - 1.0);
    while (j + 1 < m - 1 && angle_rad[idx[j + 1]] < a) ++j;
    const double xa = angle_rad[idx[j]], xb = angle_rad[idx[j + 1]];
    const double t = xb > xa ? (a - xa) / (xb - xa) : 0.0;
    u[k] = (1 - t) * y[idx[j]] + t * y[idx[j + 1]];
  }
  const int nc = m / 2 + 1;
  fftw_complex* c = fftw_alloc_complex(nc);
  fftw_plan plan = fftw_plan_dft_r2c_1d(m, u.data(), c, FFTW_ESTIMATE);
  fftw_execute(plan);
  for (int k = 0; k < nc; ++k) {
    const double order = k / revolutions;
    if (order > max_order) break;
    out.order.push_back(order);
    out.amplitude.push_back((k == 0 ? 1.0 : 2.0) * std::hypot(c[k][0], c[k][1]) / m);
  }
  fftw_destroy_plan(plan);
  fftw_free(c);
  return out;
}

std::string report_json(const Result& r) {
  nlohmann::json j;
  j["kind"] = kind_name(r.kind);
  j["samples"] = r.samples;
  j["baseline"] = {{"model", r.baseline_model}, {"rms", r.baseline_rms}, {"heldout_rms", r.baseline_heldout_rms}};
  if (!r.baseline_source.empty()) j["baseline"]["source"] = r.baseline_source;
  nlohmann::json locs = nlohmann::json::array();
  for (const auto& l : r.locations) locs.push_back(location_json(l));
  for (const auto& l : r.unexplained) {
    nlohmann::json u = location_json(l);
    u["description"] = "unexplained after the final model: " + l.description;
    locs.push_back(u);
  }
  j["mismatch"] = {{"significant", r.significant}, {"locations", locs}};
  nlohmann::json fx = nlohmann::json::array();
  for (const auto& e : r.effects) {
    nlohmann::json params = nlohmann::json::object(), ci = nlohmann::json::object();
    for (const auto& h : e.params) {
      if (h.name == "order") {
        params[h.name] = static_cast<int>(h.value);
        continue;
      }
      params[h.name] = h.value;
      ci[h.name] = {h.lo, h.hi};
    }
    fx.push_back({{"name", e.name}, {"physics", e.physics}, {"params", params}, {"ci95", ci},
                  {"delta_bic", e.delta_bic}, {"p_value", e.p_value}});
  }
  j["effects"] = fx;
  nlohmann::json rej = nlohmann::json::array();
  for (const auto& x : r.rejected) rej.push_back({{"name", x.name}, {"reason", x.reason}});
  j["rejected"] = rej;
  j["final"] = {{"rms", r.final_rms}, {"heldout_rms", r.final_heldout_rms}};
  if (r.catalog.valid) {
    j["catalog"] = catalog_json(r.catalog);
    // Identifiability of K1: the twist its segment spans over the final residual RMS (below ~10 the soft start is
    // hard to tell from the next segment).
    if (r.catalog.segments >= 2 && r.final_rms > 0.0)
      j["catalog"]["K1_segment_twist_over_noise"] = r.catalog.t1 / r.catalog.k1 / r.final_rms;
  }
  j["verdict"] = r.verdict;
  return j.dump(2) + "\n";
}

std::string report_summary(const Result& r) {
  std::string s = "reconcile (" + kind_name(r.kind) + ", " + std::to_string(r.samples) + " samples, baseline " +
                  r.baseline_model + "): " + r.verdict + "\n";
  for (const auto& l : r.locations) s += "  mismatch in " + l.domain + " (p " + num(l.p_value, "%.2g") + "): " + l.description + "\n";
  for (const auto& e : r.effects) {
    s += "  missing physics: " + e.name + " (dBIC " + num(e.delta_bic, "%.1f") + ", p " + num(e.p_value, "%.2g") + ")\n   ";
    for (const auto& h : e.params)
      s += h.name == "order" ? " order " + num(h.value, "%.0f")
                             : " " + h.name + " = " + num(h.value) + " [" + num(h.lo) + ", " + num(h.hi) + "]";
    s += "\n";
  }
  for (const auto& u : r.unexplained) s += "  still unexplained: " + u.description + "\n";
  if (r.catalog.valid && !r.effects.empty()) {
    const CatalogFigures& c = r.catalog;
    s += "  catalog terms: K1 " + num(c.k1) + (c.segments >= 2 ? ", K2 " + num(c.k2) : std::string()) +
         (c.segments == 3 ? ", K3 " + num(c.k3) : std::string()) + " N*m/rad";
    if (c.segments >= 2) s += ", T1 " + num(c.t1) + (c.segments == 3 ? ", T2 " + num(c.t2) : std::string()) + " N*m";
    s += "; hysteresis loss " + num(c.hysteresis_loss_arcmin) + " arcmin, catalog lost motion (+-4 % of " +
         num(c.rated_torque_Nm) + " N*m, elastic twist included) " + num(c.catalog_lost_motion_arcmin) +
         " arcmin, play " + num(c.play_arcmin) + " arcmin\n";
  }
  s += "  residual RMS " + num(r.baseline_rms) + " -> " + num(r.final_rms) + "; held-out (last " +
       std::to_string(r.heldout_rows) + " rows) " + num(r.baseline_heldout_rms) + " -> " + num(r.final_heldout_rms) + "\n";
  return s;
}

std::string report_html(const Experiment& e, const Recording& rec, const Result& r, const std::vector<std::string>& notes) {
  std::string h = "<!DOCTYPE html><html><head><meta charset='utf-8'><title>strainwave reconcile: " + html_escape(rec.path) +
                  "</title><style>body{font-family:sans-serif;max-width:820px;margin:2em auto;color:#222}"
                  "table{border-collapse:collapse}td,th{border:1px solid #ccc;padding:3px 8px;font-size:13px}"
                  ".v{font-size:20px;font-weight:bold}</style></head><body>";
  h += "<h1>Reconcile: " + html_escape(rec.path) + "</h1>";
  h += "<p class='v'>Verdict: " + html_escape(r.verdict) + "</p>";
  h += "<p>Baseline: " + html_escape(baseline_description(e)) + "</p>";
  for (const auto& n : notes) h += "<p style='color:#a40'>Note: " + html_escape(n) + "</p>";
  h += "<h2>Recording</h2><table>";
  for (const auto& [k, v] : rec.metadata) h += "<tr><td>" + html_escape(k) + "</td><td>" + html_escape(v) + "</td></tr>";
  h += "<tr><td>samples</td><td>" + std::to_string(r.samples) + "</td></tr>";
  h += "<tr><td>noise model (estimated)</td><td>AR(" + std::to_string(r.noise.order()) + "), sd " +
       num(r.noise.process_sd) + " " + e.response_unit + ", innovation sd " + num(r.noise.innovation_sd) + "</td></tr></table>";

  h += "<h2>Where the mismatch is</h2>";
  if (r.locations.empty()) h += "<p>No signature differs from the estimated noise.</p>";
  else {
    h += "<table><tr><th>domain</th><th>what</th><th>p (Bonferroni)</th></tr>";
    for (const auto& l : r.locations)
      h += "<tr><td>" + html_escape(l.domain) + "</td><td>" + html_escape(l.description) + "</td><td>" + num(l.p_value, "%.2g") + "</td></tr>";
    h += "</table>";
  }
  h += "<h2>Missing physics</h2>";
  if (r.effects.empty()) h += "<p>No catalog effect passed every test.</p>";
  for (const auto& f : r.effects) {
    h += "<h3>" + html_escape(f.name) + "</h3><p>" + html_escape(f.physics) + "</p><table><tr><th>parameter</th><th>value</th><th>95 % interval</th></tr>";
    for (const auto& p : f.params)
      h += "<tr><td>" + html_escape(p.name) + "</td><td>" + num(p.value) + "</td><td>" +
           (p.name == "order" ? std::string("exact") : "[" + num(p.lo) + ", " + num(p.hi) + "]") + "</td></tr>";
    h += "</table><p>BIC change " + num(f.delta_bic, "%.1f") + ", p = " + num(f.p_value, "%.3g") + " (" + html_escape(f.test) + ")</p>";
  }
  if (!r.unexplained.empty()) {
    h += "<p><b>Still unexplained:</b></p><ul>";
    for (const auto& u : r.unexplained) h += "<li>" + html_escape(u.description) + " (p " + num(u.p_value, "%.2g") + ")</li>";
    h += "</ul>";
  }
  if (!r.rejected.empty()) {
    h += "<h3>Considered and rejected</h3><ul>";
    for (const auto& x : r.rejected) h += "<li>" + html_escape(x.reason) + "</li>";
    h += "</ul>";
  }
  if (r.catalog.valid) h += catalog_html(r.catalog);
  h += "<h2>Fit on held-out data</h2><p>The last " + std::to_string(r.heldout_rows) +
       " rows were never used to fit the model that is scored on them.</p><table><tr><th></th><th>RMS (all)</th><th>RMS (held out)</th></tr>"
       "<tr><td>baseline</td><td>" + num(r.baseline_rms) + "</td><td>" + num(r.baseline_heldout_rms) + "</td></tr>"
       "<tr><td>reconciled</td><td>" + num(r.final_rms) + "</td><td>" + num(r.final_heldout_rms) + "</td></tr></table>";

  // Plots.
  const Display d = display_of(e);
  Vec x;
  std::string xl;
  if (e.kind == Kind::Torsion) { x = e.torque_Nm; xl = "torque (N·m)"; }
  else if (e.kind == Kind::Dynamics) { x = e.time; xl = "time (s)"; }
  else { x = e.wg_angle_rad * (180.0 / M_PI); xl = "wave-generator angle (deg)"; }
  std::vector<std::pair<double, double>> shade;
  for (const auto& l : r.locations)
    if (l.has_range && e.kind == Kind::Torsion && l.domain != "time") shade.emplace_back(l.lo, l.hi);
  h += "<h2>Plots</h2>";
  if (e.kind == Kind::Transmission) {
    // Transmission: the ideal line hides everything; show the transmission error instead.
    h += plot("transmission error: recording and models minus the ideal ratio", xl, d.label,
              {series("recording - ideal", "#888", x, e.measured - e.baseline, d.scale, true),
               series("baseline (offset, ratio)", "#36c", x, r.baseline_prediction - e.baseline, d.scale),
               series("reconciled", "#c33", x, r.final_prediction - e.baseline, d.scale)});
  } else {
    h += plot(e.kind == Kind::Torsion ? "torque-twist loop: recording, baseline (" +
                                            (e.model.twist_rad ? std::string("torque-twist curve") : "C_tau T") +
                                            ") and the fitted model"
                                      : "recording vs baseline vs reconciled model",
              xl, d.label,
              {series("recording", "#888", x, e.measured, d.scale, true),
               series("baseline", "#36c", x, r.baseline_prediction, d.scale),
               series("reconciled", "#c33", x, r.final_prediction, d.scale)},
              shade);
  }
  h += "<br>" + plot("residual before (baseline) and after (reconciled); shaded: located region", xl, d.label,
                     {series("before", "#36c", x, r.residual_before, d.scale, true),
                      series("after", "#c33", x, r.residual_after, d.scale, true)},
                     shade);
  h += "<br>" + plot("residual over the recording (time order)", e.has_time ? "time (s)" : "row", d.label,
                     {series("before", "#36c", e.time, r.residual_before, d.scale),
                      series("after", "#c33", e.time, r.residual_after, d.scale)});
  if (e.kind != Kind::Torsion && e.kind != Kind::Dynamics) {
    auto spectrum_plot = [&](const std::string& title, const std::string& axis, const Vec& angle) {
      const Spectrum a = order_spectrum(angle, r.residual_before, 6.0);
      const Spectrum b = order_spectrum(angle, r.residual_after, 6.0);
      auto ser = [&](const std::string& label, const std::string& colour, const Spectrum& sp) {
        return series(label, colour, Eigen::Map<const Vec>(sp.order.data(), sp.order.size()),
                      Eigen::Map<const Vec>(sp.amplitude.data(), sp.amplitude.size()), d.scale);
      };
      return "<br>" + plot(title, axis, "amplitude: " + d.label, {ser("before", "#36c", a), ser("after", "#c33", b)});
    };
    h += spectrum_plot("residual spectrum in wave-generator orders", "order (per wave-generator revolution)",
                       e.wg_angle_rad);
    if (e.kind == Kind::Transmission)
      h += spectrum_plot("residual spectrum in output orders", "order (per output revolution)", -e.output_angle_rad);
  }
  h += "<p style='font-size:11px;color:#777'>Tests: signatures by GLS F-tests under the estimated AR noise "
       "(Bonferroni over the kind's signatures). Effects enter one at a time (BIC lower by more than 10, held-out RMS "
       "lower, a signature removed) or, where overlapping effects only together remove their signatures, jointly; "
       "each is kept only if removing it costs significantly: BIC up by more than 10, a worse held-out RMS, and "
       "significant against the noise (F-test times the number of harmonic orders searched; for breakpoints and "
       "transitions the F-test Bonferroni-corrected for the search when decisive, else a parametric bootstrap). "
       "Intervals: Wald, delta method.</p></body></html>\n";
  return h;
}

}  // namespace sw::reconcile
