#include "reconcile/verdict.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <fftw3.h>

#include "common/svg_plot.hpp"
#include "reconcile/effects.hpp"

namespace sw::reconcile {

using Vec = Eigen::VectorXd;

namespace {

std::string num(double v, const char* f = "%.4g") {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

/// The response as people read it: angles in arcmin, the rest as recorded.
struct Display {
  double scale = 1.0;
  std::string label;  ///< e.g. "twist (arcmin)"
};

Display display_of(const Experiment& e) {
  std::string name = e.response_name.substr(0, e.response_name.rfind('_'));
  std::replace(name.begin(), name.end(), '_', ' ');
  if (e.response_unit == "rad") return {kArcmin, name + " (arcmin)"};
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

/// The catalog's limits of hysteresis loss and lost motion, arcmin.
constexpr double kCatalogLossMaxArcmin = 1.0, kCatalogLostMotionMaxArcmin = 1.0;

ReportCatalogReference reference_of(const CatalogDrive& d) {
  return {d.size, d.k1_Nm_per_rad, d.k2_Nm_per_rad, d.k3_Nm_per_rad, d.t1_Nm, d.t2_Nm, d.rated_torque_Nm,
          kCatalogLossMaxArcmin, kCatalogLostMotionMaxArcmin};
}

ReportCatalog catalog_of(const CatalogFigures& c, double final_rms) {
  ReportCatalog k{.segments = c.segments,
                  .k1_Nm_per_rad = c.k1,
                  .k2_Nm_per_rad = c.k2,
                  .k3_Nm_per_rad = c.k3,
                  .t1_Nm = c.t1,
                  .t2_Nm = c.t2,
                  .rated_torque_Nm = c.rated_torque_Nm,
                  .rated_torque_from = c.rated_from,
                  .hysteresis_loss_arcmin = c.hysteresis_loss_arcmin,
                  .play_width_arcmin = c.play_arcmin,
                  .catalog_lost_motion_arcmin = c.catalog_lost_motion_arcmin,
                  .note = "catalog_lost_motion_arcmin is the twist between -4 % and +4 % of rated torque on the "
                          "loop's middle line (it includes elastic twist); play_width_arcmin is the dead band of the "
                          "effect lost_motion (width_rad)"};
  if (c.reference) k.reference = reference_of(*c.reference);
  // Identifiability of K1: the twist its segment spans over the final residual RMS.
  if (c.segments >= 2 && final_rms > 0.0) k.k1_segment_twist_over_noise = c.t1 / c.k1 / final_rms;
  return k;
}

/// A headline's 95 % interval as the report prints it: "[lo, hi]", "exact" for a harmonic's order, or where a held
/// parameter is read.
std::string interval(const Headline& h) {
  if (h.name == "order") return "exact";
  if (h.fixed()) return "fixed (from " + h.fixed_from + ")";
  return (std::isinf(h.lo) ? "(-inf" : "[" + num(h.lo)) + ", " + (std::isinf(h.hi) ? "inf)" : num(h.hi) + "]");
}

ReportEffect effect_of(const AcceptedEffect& e) {
  ReportEffect x{e.name, e.physics, std::nullopt, {}, {}, {}, e.delta_bic, e.p_value, e.meaning, e.model_discrepancy,
                 e.model_runs};
  for (const auto& h : e.params) {
    if (h.name == "order") {
      x.order = static_cast<int>(h.value);
      continue;
    }
    x.params[h.name] = h.value;
    if (h.fixed()) x.fixed[h.name] = h.fixed_from;
    else x.ci95[h.name] = {h.lo, h.hi};
  }
  return x;
}

/// The refit of a dynamics effect on re-runs of the model, in words.
std::string rerun_words(double discrepancy, int runs) {
  return "refitted on " + std::to_string(runs) + " re-runs of the model: at their own estimate the columns "
         "from the baseline's runs missed the model by " + num(100.0 * discrepancy, "%.3g") +
         " % of its response; the values and intervals are the re-runs'";
}

/// The play effect's width in words: a negative width is play the model has and the drive lacks.
std::string play_words(double play_arcmin) {
  if (play_arcmin < 0.0) return "play: the model has " + num(-play_arcmin) + " arcmin more play than the drive";
  return "play " + num(play_arcmin) + " arcmin";
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
  h += "<tr><td>play: dead band of the effect lost_motion</td><td colspan='2'>" + html_escape(play_words(c.play_arcmin)) +
       "</td></tr>";
  h += "</table><p>Rated torque from " + html_escape(c.rated_from) + ".</p>";
  return h;
}

/// The baseline in words, for the page.
std::string described(const Experiment& e, const TorsionExperiment& t) {
  if (e.baseline_model == "fem")
    return "C_tau T, the flexspline body's torsional compliance (C_tau = " + num(t.model.compliance_rad_per_Nm) +
           " rad/(N*m))";
  if (e.baseline_model == "contact")
    return "the drive's torque-twist curve from the loaded tooth contact (middle line of its loop)";
  if (e.baseline_model == "curve") return "a torque-twist curve";
  return e.baseline_model;
}
std::string described(const Experiment& e, const TransmissionExperiment&) {
  return e.baseline_model == "ideal_ratio" ? "the ideal ratio, output = -wg (z_c - z_f)/z_f" : e.baseline_model;
}
std::string described(const Experiment& e, const BacklashExperiment&) {
  return e.baseline_model == "kinematic" ? "the basic kinematic backlash model (phi0 = 0)" : e.baseline_model;
}
std::string described(const Experiment& e, const DynamicsExperiment&) {
  return e.baseline_model == "dynamics_model" ? "the dynamics model with constant mesh stiffness" : e.baseline_model;
}

std::string baseline_description(const Experiment& e) {
  const std::string d = std::visit([&](const auto& k) { return described(e, k); }, e.data);
  return d + (e.baseline_source.empty() ? "" : ", from " + e.baseline_source);
}

// ---- the page ---------------------------------------------------------------------------------------------------

/// What the page's plots share: the experiment, its result, the response's display and the abscissa of the
/// response plots (torsion: shaded where a signature located the mismatch in torque).
struct Page {
  const Experiment& e;
  const Result& r;
  Display d;
  Vec x;
  std::string x_label;
  std::vector<std::pair<double, double>> shade;
};

void set_abscissa(Page& p, const TorsionExperiment& t) {
  p.x = t.torque_Nm;
  p.x_label = "torque (N·m)";
  for (const auto& l : p.r.locations)
    if (l.has_range && l.domain != "time") p.shade.emplace_back(l.lo, l.hi);
}
void set_abscissa(Page& p, const TransmissionExperiment& t) {
  p.x = t.wg_angle_rad * (180.0 / M_PI);
  p.x_label = "wave-generator angle (deg)";
}
void set_abscissa(Page& p, const BacklashExperiment& b) {
  p.x = b.wg_angle_rad * (180.0 / M_PI);
  p.x_label = "wave-generator angle (deg)";
}
void set_abscissa(Page& p, const DynamicsExperiment&) {
  p.x = p.e.time;
  p.x_label = "time (s)";
}

/// Recording, baseline and reconciled model against the abscissa (and the model re-run with the fitted case keys).
std::string response_plot(const Page& p, const std::string& title) {
  std::vector<PlotSeries> lines{series("recording", "#888", p.x, p.e.measured, p.d.scale, true),
                                series("baseline", "#36c", p.x, p.r.baseline_prediction, p.d.scale),
                                series("reconciled", "#c33", p.x, p.r.final_prediction, p.d.scale)};
  if (p.r.refitted) lines.push_back(series("model refitted (re-run)", "#2a2", p.x, p.r.refit_prediction, p.d.scale));
  return plot(title, p.x_label, p.d.label, lines, p.shade);
}

std::string main_plot(const Page& p, const TorsionExperiment& t) {
  return response_plot(p, "torque-twist loop: recording, baseline (" +
                              (t.model.twist_rad ? std::string("torque-twist curve") : "C_tau T") +
                              ") and the fitted model");
}
std::string main_plot(const Page& p, const TransmissionExperiment&) {
  // The ideal line hides everything; show the transmission error instead.
  const Experiment& e = p.e;
  return plot("transmission error: recording and models minus the ideal ratio", p.x_label, p.d.label,
              {series("recording - ideal", "#888", p.x, e.measured - e.baseline, p.d.scale, true),
               series("baseline (offset, ratio)", "#36c", p.x, p.r.baseline_prediction - e.baseline, p.d.scale),
               series("reconciled", "#c33", p.x, p.r.final_prediction - e.baseline, p.d.scale)});
}
std::string main_plot(const Page& p, const BacklashExperiment&) {
  return response_plot(p, "recording vs baseline vs reconciled model");
}
std::string main_plot(const Page& p, const DynamicsExperiment&) {
  return response_plot(p, "recording vs baseline vs reconciled model");
}

/// The residual's amplitude spectrum before and after in the orders of an angle.
std::string spectrum_plot(const Page& p, const std::string& title, const std::string& axis, const Vec& angle) {
  const Spectrum a = order_spectrum(angle, p.r.residual_before, 6.0);
  const Spectrum b = order_spectrum(angle, p.r.residual_after, 6.0);
  auto ser = [&](const std::string& label, const std::string& colour, const Spectrum& sp) {
    return series(label, colour, Eigen::Map<const Vec>(sp.order.data(), sp.order.size()),
                  Eigen::Map<const Vec>(sp.amplitude.data(), sp.amplitude.size()), p.d.scale);
  };
  return "<br>" + plot(title, axis, "amplitude: " + p.d.label, {ser("before", "#36c", a), ser("after", "#c33", b)});
}

const char* kWgOrders = "order (per wave-generator revolution)";

std::string spectra(const Page&, const TorsionExperiment&) { return ""; }
std::string spectra(const Page& p, const TransmissionExperiment& t) {
  return spectrum_plot(p, "residual spectrum in wave-generator orders", kWgOrders, t.wg_angle_rad) +
         spectrum_plot(p, "residual spectrum in output orders", "order (per output revolution)", -t.output_angle_rad);
}
std::string spectra(const Page& p, const BacklashExperiment& b) {
  return spectrum_plot(p, "residual spectrum in wave-generator orders", kWgOrders, b.wg_angle_rad);
}
std::string spectra(const Page&, const DynamicsExperiment&) { return ""; }

std::string plots_html(const Experiment& e, const Result& r) {
  Page p{e, r, display_of(e), {}, {}, {}};
  std::visit([&](const auto& k) { set_abscissa(p, k); }, e.data);
  std::string h = "<h2>Plots</h2>";
  h += std::visit([&](const auto& k) { return main_plot(p, k); }, e.data);
  h += "<br>" + plot("residual before (baseline) and after (reconciled); shaded: located region", p.x_label, p.d.label,
                     {series("before", "#36c", p.x, r.residual_before, p.d.scale, true),
                      series("after", "#c33", p.x, r.residual_after, p.d.scale, true)},
                     p.shade);
  h += "<br>" + plot("residual over the recording (time order)", e.has_time ? "time (s)" : "row", p.d.label,
                     {series("before", "#36c", e.time, r.residual_before, p.d.scale),
                      series("after", "#c33", e.time, r.residual_after, p.d.scale)});
  return h + std::visit([&](const auto& k) { return spectra(p, k); }, e.data);
}

std::string page_head(const Experiment& e, const Recording& rec, const Result& r,
                      const std::vector<std::string>& notes) {
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
  return h;
}

std::string mismatch_html(const Result& r) {
  std::string h = "<h2>Where the mismatch is</h2>";
  if (r.locations.empty()) return h + "<p>No signature differs from the estimated noise.</p>";
  h += "<table><tr><th>domain</th><th>what</th><th>p (Bonferroni)</th></tr>";
  for (const auto& l : r.locations)
    h += "<tr><td>" + html_escape(l.domain) + "</td><td>" + html_escape(l.description) + "</td><td>" + num(l.p_value, "%.2g") + "</td></tr>";
  return h + "</table>";
}

std::string effects_html(const Result& r) {
  std::string h = "<h2>Missing physics</h2>";
  if (r.effects.empty()) h += "<p>No catalog effect passed every test.</p>";
  for (const auto& f : r.effects) {
    h += "<h3>" + html_escape(f.name) + "</h3><p>" + html_escape(f.physics) + "</p>";
    if (!f.meaning.empty()) h += "<p><b>For the drive:</b> " + html_escape(f.meaning) + "</p>";
    if (f.model_runs > 0) h += "<p>" + html_escape(rerun_words(f.model_discrepancy, f.model_runs)) + "</p>";
    h += "<table><tr><th>parameter</th><th>value</th><th>95 % interval</th></tr>";
    for (const auto& p : f.params)
      h += "<tr><td>" + html_escape(p.name) + "</td><td>" + num(p.value) + "</td><td>" + html_escape(interval(p)) +
           "</td></tr>";
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
  return h;
}

std::string heldout_html(const Result& r) {
  return "<h2>Fit on held-out data</h2><p>The last " + std::to_string(r.heldout_rows) +
         " rows were never used to fit the model that is scored on them.</p><table><tr><th></th><th>RMS (all)</th><th>RMS (held out)</th></tr>"
         "<tr><td>baseline</td><td>" + num(r.baseline_rms) + "</td><td>" + num(r.baseline_heldout_rms) + "</td></tr>"
         "<tr><td>reconciled</td><td>" + num(r.final_rms) + "</td><td>" + num(r.final_heldout_rms) + "</td></tr>" +
         (r.refitted ? "<tr><td>model re-run with the fitted values</td><td>" + num(r.refit_rms) + "</td><td>" +
                           num(r.refit_heldout_rms) + "</td></tr>"
                     : std::string()) +
         "</table>";
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

Report report_of(const Result& r) {
  Report rep{.kind = r.kind,
             .samples = r.samples,
             .baseline_model = r.baseline_model,
             .baseline_source = r.baseline_source,
             .baseline_rms = r.baseline_rms,
             .baseline_heldout_rms = r.baseline_heldout_rms,
             .significant = r.significant,
             .rejected = r.rejected,
             .final_rms = r.final_rms,
             .final_heldout_rms = r.final_heldout_rms,
             .verdict = r.verdict};
  for (const auto& l : r.locations) rep.locations.push_back({l.domain, l.description, l.p_value});
  for (const auto& l : r.unexplained)
    rep.locations.push_back({l.domain, "unexplained after the final model: " + l.description, l.p_value});
  for (const auto& e : r.effects) rep.effects.push_back(effect_of(e));
  if (r.catalog) rep.catalog = catalog_of(*r.catalog, r.final_rms);
  if (r.refitted) rep.refit = ReportRefit{r.refit_rms, r.refit_heldout_rms};
  return rep;
}

std::string report_summary(const Result& r) {
  std::string s = "reconcile (" + kind_name(r.kind) + ", " + std::to_string(r.samples) + " samples, baseline " +
                  r.baseline_model + "): " + r.verdict + "\n";
  for (const auto& l : r.locations) s += "  mismatch in " + l.domain + " (p " + num(l.p_value, "%.2g") + "): " + l.description + "\n";
  for (const auto& e : r.effects) {
    s += "  missing physics: " + e.name + " (dBIC " + num(e.delta_bic, "%.1f") + ", p " + num(e.p_value, "%.2g") + ")\n   ";
    for (const auto& h : e.params)
      s += h.name == "order" ? " order " + num(h.value, "%.0f") : " " + h.name + " = " + num(h.value) + " " + interval(h);
    s += "\n";
    if (!e.meaning.empty()) s += "    for the drive: " + e.meaning + "\n";
    if (e.model_runs > 0) s += "    " + rerun_words(e.model_discrepancy, e.model_runs) + "\n";
  }
  for (const auto& u : r.unexplained) s += "  still unexplained: " + u.description + "\n";
  if (r.catalog && !r.effects.empty()) {
    const CatalogFigures& c = *r.catalog;
    s += "  catalog terms: K1 " + num(c.k1) + (c.segments >= 2 ? ", K2 " + num(c.k2) : std::string()) +
         (c.segments == 3 ? ", K3 " + num(c.k3) : std::string()) + " N*m/rad";
    if (c.segments >= 2) s += ", T1 " + num(c.t1) + (c.segments == 3 ? ", T2 " + num(c.t2) : std::string()) + " N*m";
    s += "; hysteresis loss " + num(c.hysteresis_loss_arcmin) + " arcmin, catalog lost motion (+-4 % of " +
         num(c.rated_torque_Nm) + " N*m, elastic twist included) " + num(c.catalog_lost_motion_arcmin) +
         " arcmin, " + play_words(c.play_arcmin) + "\n";
  }
  s += "  residual RMS " + num(r.baseline_rms) + " -> " + num(r.final_rms) + "; held-out (last " +
       std::to_string(r.heldout_rows) + " rows) " + num(r.baseline_heldout_rms) + " -> " + num(r.final_heldout_rms) + "\n";
  if (r.refitted)
    s += "  the model re-run with the fitted values: RMS " + num(r.refit_rms) + ", held-out " +
         num(r.refit_heldout_rms) + " (noise sd " + num(r.noise.process_sd) + ")\n";
  return s;
}

std::string report_html(const Experiment& e, const Recording& rec, const Result& r, const std::vector<std::string>& notes) {
  std::string h = page_head(e, rec, r, notes) + mismatch_html(r) + effects_html(r);
  if (r.catalog) h += catalog_html(*r.catalog);
  h += heldout_html(r) + plots_html(e, r);
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
