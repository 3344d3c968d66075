#include "io/run_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <sstream>

#include "common/constants.hpp"
#include "common/error.hpp"
#include "common/svg_plot.hpp"
#include "contact/contact_params.hpp"
#include "io/provenance.hpp"
#include "io/backlash_output.hpp"
#include "io/contact_output.hpp"
#include "io/fem_output.hpp"

namespace sw {

namespace {

namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  return {std::istreambuf_iterator<char>(in), {}};
}

std::string fmt(const char* f, double v) {
  std::string buf(static_cast<std::size_t>(std::snprintf(nullptr, 0, f, v)), '\0');
  std::snprintf(buf.data(), buf.size() + 1, f, v);
  return buf;
}

class Table {
 public:
  void row(const std::string& what, const std::string& value, const std::string& note = "") {
    s_ << "<tr><td>" << html_escape(what) << "</td><td class='v'>" << html_escape(value) << "</td><td class='n'>"
       << html_escape(note) << "</td></tr>\n";
  }
  std::string html() const { return "<table>\n" + s_.str() + "</table>\n"; }

 private:
  std::ostringstream s_;
};

/// φ₀ and C_τ, against the closed form, and the torque balance.
void add_wind_up_rows(Table& t, const FemResult& r) {
  const double phi0 = r.phi0_rad, theory = r.phi0_theory_cup_rad;
  t.row("flexspline body wind-up φ₀ at the case torque", fmt("%.4e rad", phi0),
        fmt("%.4g N·m; least-squares rigid rotation of the rim's neutral circle", r.torque_Nm));
  t.row("flexspline body torsional stiffness 1/C_τ", fmt("%.4g N·m/rad", 1.0 / r.compliance_rad_per_Nm),
        "the body alone: teeth, generator bearing and circular spline are not in it");
  if (std::isfinite(theory))
    t.row("closed form (body wall + diaphragm + rim)", fmt("%.4e rad", theory), fmt("FEM / closed form = %.4f", phi0 / theory));
  t.row("mean rotation over the engagement zones", fmt("%.4e rad", r.phi0_engaged_rad), "what the teeth in mesh turn");
  t.row("reaction torque (clamp and generator) vs applied",
        fmt("%.9g N·m", r.reaction_torque_Nm) + " vs " + fmt("%.9g N·m", r.applied_torque_Nm),
        fmt("balance error %.1e", r.torque_balance_error_rel));
}

/// The model's size, its solve and what the run took.
void add_model_rows(Table& t, const FemResult& r) {
  if (const auto* m = std::get_if<TetMeshFigures>(&r.mesh))
    t.row("mesh", fmt("%.0f nodes, ", m->nodes) + fmt("%.0f TET10", m->elements),
          fmt("smallest dihedral angle %.1f°", m->min_dihedral_deg));
  if (const auto* m = std::get_if<SectionMeshFigures>(&r.mesh))
    t.row("mesh", fmt("%.0f nodes, ", m->nodes) + fmt("%.0f 6-node triangles", m->elements),
          "meridian section of the harmonic solver");
  t.row("solver", fmt("%.0f equations", r.solver.equations),
        fmt("factor %.3g GF", r.solver.factor_gflop) + fmt(" in %.1f s", r.timings_s.factor));
  t.row("run time, peak memory", fmt("%.1f s", r.timings_s.total), fmt("%.0f MB", r.peak_rss_bytes / 1e6));
}

void add_generator_rows(Table& t, const FemResult::Generator& g) {
  std::string zones;
  for (const auto& z : g.contact_zones_deg) zones += fmt(" [%.0f°, ", z[0]) + fmt("%.0f°]", z[1]);
  t.row("wave generator", g.model, g.idealisation);
  t.row("generator: total radial force", fmt("%.1f N", g.total_radial_force_N), "contact zones:" + zones);
  t.row("w at the major / minor axis",
        fmt("%+.4f mm", g.w_major_axis_mm) + " / " + fmt("%+.4f mm", g.w_minor_axis_mm), "");
}

void add_hoop_rows(Table& t, const FemResult::HoopStressMPa& h) {
  t.row("nominal hoop bending stress", fmt("%+.0f MPa", h.nominal_bending),
        fmt("away from load application, %.0f° from the major axis; ", h.nominal_angle_deg) +
            fmt("thin-ring theory %+.0f MPa", h.ring_theory_bending));
  t.row("local hoop stress peaks", fmt("%+.0f", h.local_peak_tensile) + fmt(" / %+.0f MPa", h.local_peak_compressive),
        "where the generator touches: a local effect of concentrated contact, not the part's nominal stress");
}

/// The Goodman safety factor at the rim's and the diaphragm's worst point over a generator revolution.
void add_fatigue_rows(Table& t, const FemResult::Fatigue& f) {
  std::vector<const FemResult::FatiguePoint*> points{&f.rim};
  if (f.diaphragm) points.push_back(&*f.diaphragm);
  for (const FemResult::FatiguePoint* p : points) {
    if (p->goodman_safety_factor)
      t.row("fatigue safety factor, " + p->place, fmt("%.2f", *p->goodman_safety_factor),
            f.criterion + "; over a generator revolution (" + f.case_name + " case)");
    else
      t.row("fatigue safety factor, " + p->place, "not computed",
            "needs [material] fatigue_limit_MPa and ultimate_strength_MPa");
  }
}

std::string fem_section(const FemResult& r) {
  Table t;
  add_wind_up_rows(t, r);
  add_model_rows(t, r);
  if (r.generator) add_generator_rows(t, *r.generator);
  add_hoop_rows(t, r.hoop_stress_MPa);
  if (r.fatigue) add_fatigue_rows(t, *r.fatigue);
  return t.html();
}

std::string neutral_curve_plot(const RunReportInputs& in) {
  const fs::path csv = in.out_dir / "neutral_curve.csv";
  if (!fs::exists(csv)) return "";
  const NeutralCurveSamples nc = read_neutral_curve_csv(csv);
  LinePlot p;
  p.title = "Radial displacement of the rim's neutral circle under the generator";
  p.x_label = "angle from the major axis (deg)";
  p.y_label = "w (µm)";
  PlotSeries fem{"FEM", {}, {}, "#1f77b4"}, th{in.theory_label, {}, {}, "#d62728", true};
  std::vector<std::pair<double, double>> pts;  // (−180°, 180°], the theory curve's range
  for (size_t i = 0; i < nc.phi_rad.size(); ++i)
    pts.emplace_back(std::remainder(nc.phi_rad[i], 2.0 * std::numbers::pi) * kDeg, nc.w_wg_m[i] * 1e6);
  std::sort(pts.begin(), pts.end());
  for (const auto& [x, y] : pts) {
    fem.x.push_back(x);
    fem.y.push_back(y);
  }
  for (size_t i = 0; i < in.theory_phi_rad.size(); ++i) {
    th.x.push_back(in.theory_phi_rad[i] * kDeg);
    th.y.push_back(in.theory_w_m[i] * 1e6);
  }
  p.series = {fem};
  if (!th.x.empty()) p.series.push_back(th);
  return svg_line_plot(p);
}

std::string hoop_plot(const FemResult& r) {
  const FemResult::HoopStressProfile& h = r.hoop_stress_profile;
  LinePlot p;
  p.title = "Hoop stress around the rim at z = " + fmt("%.1f mm", h.z_mm) + " (" + r.hoop_stress_case + " case)";
  p.x_label = "angle from the major axis (deg)";
  p.y_label = "hoop stress (MPa)";
  PlotSeries inner{"inner wall", {}, {}, "#1f77b4", false, false}, outer{"outer wall", {}, {}, "#d62728", true, false};
  for (size_t i = 0; i < h.angle_deg.size(); ++i) {
    inner.x.push_back(h.angle_deg[i]);
    outer.x.push_back(h.angle_deg[i]);
    inner.y.push_back(h.inner_Pa[i] / 1e6);
    outer.y.push_back(h.outer_Pa[i] / 1e6);
  }
  p.series = {inner, outer};
  return svg_line_plot(p);
}

/// The output's geometric angular play over one pitch of the generator.
std::string angular_play_plot(const BacklashResult& b) {
  LinePlot p;
  p.title = "Geometric angular play of the output over one circular-spline pitch of the generator";
  p.x_label = "wave-generator angle (deg)";
  p.y_label = "angular play (arcmin)";
  PlotSeries ser{"angular play", {}, {}, "#1f77b4"};
  for (const auto& st : b.revolution.period_basic) {
    ser.x.push_back(st.wg_deg);
    ser.y.push_back(st.angular_play_arcmin);
  }
  p.series = {ser};
  p.zero_line = false;
  return svg_line_plot(p);
}

std::string backlash_section(const fs::path& dir) {
  if (!fs::exists(dir / "backlash.json")) return "";
  const BacklashResult b = read_backlash_result(dir / "backlash.json");
  std::ostringstream s;
  s << "<h2>Backlash</h2>\n<p>Neutral curve used: " << html_escape(b.neutral_curve) << ".</p>\n";
  Table t;
  const BacklashResult::Geometry& g = b.geometry_check;
  t.row("interference at rest", g.interference_at_rest ? "yes" : "no",
        fmt("smallest clearance %.2f µm", g.smallest_clearance_um));
  t.row("working depth at the major axis", fmt("%.3f mm", g.working_depth_mm), fmt("against 2·w0 = %.3f mm", g.two_w0_mm));
  t.row("major-axis pair: dead band", fmt("%.3f arcmin", g.major_axis_play_arcmin), "output rotation between the two flank contacts");
  const BacklashResult::AngularPlay& play = b.angular_play_arcmin;
  t.row("geometric angular play over a revolution", fmt("%.3f", play.min) + fmt(" … %.3f arcmin", play.max),
        "teeth and rim rigid; not the catalog's lost motion, which includes elastic twist at ±4 % of rated torque");
  t.row("smallest clearance over a revolution (basic, with φ₀)",
        fmt("%.2f µm", b.min_backlash_basic_mm * 1e3) + fmt(" / %.2f µm", b.min_backlash_compensated_mm * 1e3),
        "with φ₀ at or below zero: the loaded flank in contact, not interference");
  s << t.html();
  s << "<div class='fig'>" << angular_play_plot(b) << "</div>\n";
  if (fs::exists(dir / "backlash.svg")) s << "<div class='fig'>" << slurp(dir / "backlash.svg") << "</div>\n";
  return s.str();
}

/// The drive's twist, its three segments, lost motion and play.
void add_twist_rows(Table& t, const ContactResult& a) {
  const ContactResult::Catalog& k = a.catalog;
  t.row("twist at rated torque", fmt("%.3f arcmin", a.twist_at_rated_arcmin), fmt("at %.4g N·m", a.rated_torque_Nm));
  // As contact's summary says it: straight teeth in too few sections leave the start of the curve unresolved.
  const std::string unresolved =
      face_slices_leave_k1_unresolved(a.face_slices)
          ? "; the face in " + std::to_string(a.face_slices) +
                " sections does not resolve the curve below T1 along the face, which takes about " +
                std::to_string(kFaceSlicesResolvingK1) + " ([contact] face_slices)"
          : "";
  t.row("three segments", fmt("K1 %.4g", k.K1_Nm_per_rad) + fmt(", K2 %.4g", k.K2_Nm_per_rad) +
        fmt(", K3 %.4g N·m/rad", k.K3_Nm_per_rad),
        fmt("T1 %.3g N·m", k.T1_Nm) + fmt(", T2 %.3g N·m (", k.T2_Nm) + k.breakpoints + ")" + unresolved);
  t.row("lost motion", fmt("%.3f arcmin", a.lost_motion_arcmin),
        "twist between ±4 % of rated torque on the middle line (includes the elastic twist)" + unresolved);
  t.row("play", fmt("%.3f arcmin", a.play_arcmin), "jump of the curve at zero torque");
  if (a.overlap_at_rest_um > 0)
    t.row("overlap at rest", fmt("%.2f µm", a.overlap_at_rest_um),
          "the teeth overlap on the FEM's neutral curve: part of the curve is a preload from that interference");
}

/// Where the twist at rated torque comes from, and the checks of the solve.
void add_split_and_check_rows(Table& t, const ContactResult& a) {
  const ContactResult::Split& sp = a.compliance_split;
  const std::string parts =
      sp.body_parts ? fmt(" (rim %.0f", 100 * sp.body_parts->rim) + fmt(", wall %.0f", 100 * sp.body_parts->wall) +
                          fmt(", diaphragm %.0f", 100 * sp.body_parts->diaphragm) +
                          fmt(", boss %.0f)", 100 * sp.body_parts->boss)
                    : "";
  t.row("twist at rated, by part", fmt("body %.0f %%", 100 * sp.body) + parts + fmt(", teeth %.0f %%", 100 * sp.teeth) +
        fmt(", generator %.0f %%", 100 * sp.generator) + fmt(", circular spline %.0f %%", 100 * sp.circular_spline) +
        fmt(", tangent's intercept %.0f %%", 100 * sp.engagement),
        std::string("the tangent at rated torque split by energy; ") +
            (sp.engagement >= 0 ? "its intercept is the engagement (play, pairs engaging)"
                                : "its intercept is below the origin: the curve softens toward rated torque") +
            "; the generator: " + generator_share_meaning(sp.generator));
  t.row("checks", fmt("balance %.1e", a.torque_balance_error_rel),
        fmt("clamp reaction in a direct FEM solve %.6g N·m", a.fem_reaction_torque_Nm));
}

std::string contact_section(const fs::path& dir) {
  if (!fs::exists(dir / "contact.json")) return "";
  const ContactResult a = read_contact_result(dir / "contact.json");
  std::ostringstream s;
  s << "<h2>Whole drive under load (tooth contact)</h2>\n<p>Generator locked, the output turned against the circular "
       "spline; "
    << html_escape(a.generator_support) << ". "
    << (a.friction ? fmt("Friction on the flanks (μ = %.3g): the load cycle 0 → +rated → −rated → +rated run to a "
                         "steady loop, its loading and unloading branches drawn.", a.friction->friction_coefficient)
                   : std::string("No friction: loading and unloading coincide."))
    << "</p>\n";
  Table t;
  add_twist_rows(t, a);
  if (a.friction)
    t.row("hysteresis loss", fmt("%.3f arcmin", a.hysteresis_loss_arcmin.value_or(0)),
          fmt("the branches' gap at zero torque; the loop dissipates %.3g J a cycle", a.dissipated_energy_J.value_or(0)) +
              fmt(" (friction work %.3g J)", a.friction_work_J.value_or(0)));
  add_split_and_check_rows(t, a);
  s << t.html();
  if (fs::exists(dir / "contact.svg")) s << "<div class='fig'>" << slurp(dir / "contact.svg") << "</div>\n";
  return s.str();
}

}  // namespace

std::string run_report_html(const RunReportInputs& in) {
  const FemResult r = read_fem_result(in.out_dir / "result.json");
  std::ostringstream s;
  s << "<!DOCTYPE html>\n<html lang='en'><head><meta charset='utf-8'><title>strainwave: "
    << html_escape(in.case_path) << "</title>\n<style>body{font-family:sans-serif;max-width:1000px;margin:2em auto;"
    << "color:#222}table{border-collapse:collapse;margin:1em 0}td{border-bottom:1px solid #ddd;padding:4px 10px;"
    << "vertical-align:top}td.v{font-family:monospace}td.n{color:#555;font-size:90%;min-width:16em}"
    << "pre{background:#f6f6f6;padding:1em;font-size:85%;overflow:auto}.fig{margin:1em 0}</style></head><body>\n";
  s << "<h1>strainwave run: " << html_escape(in.case_path) << "</h1>\n<p>strainwave " << html_escape(tool_version())
    << "</p>\n";
  s << "<h2>Flexspline (FEM)</h2>\n" << fem_section(r);
  s << "<div class='fig'>" << neutral_curve_plot(in) << "</div>\n";
  s << "<div class='fig'>" << hoop_plot(r) << "</div>\n";
  s << backlash_section(in.out_dir);
  s << contact_section(in.out_dir);
  s << "<h2>Not computed</h2>\n<ul>";
  if (!fs::exists(in.out_dir / "contact.json"))
    s << "<li>the whole drive's twist (the tooth contact needs [gear], [wave_generator] and teeth = \"ring\" or "
         "\"none\")</li>";
  if (!fs::exists(in.out_dir / "contact.json") || !read_contact_result(in.out_dir / "contact.json").friction)
    s << "<li>friction in the tooth contacts (the loop: [contact] friction_coefficient)</li>";
  s << "<li>the limits (buckling, ratcheting, strength) and the wave-generator bearing's life: "
       "<code>strainwave datasheet</code></li></ul>\n";
  s << "<h2>3-D results</h2>\n<p><a href='flexspline.pvd'>flexspline.pvd</a> (one .vtu per load case):";
  for (const auto& lc : r.load_cases) {
    const std::string f = "flexspline_" + lc.name + ".vtu";
    s << " <a href='" << html_escape(f) << "'>" << html_escape(f) << "</a>";
  }
  s << ". In ParaView open the .pvd, apply Warp By Vector (the displacement is the active vector) and colour by "
       "stress_hoop; or render headless:</p>\n<pre>scripts/pvbatch.sh cases/view_flexspline.py "
    << html_escape((in.shown_dir.empty() ? in.out_dir : in.shown_dir).string())
    << " --case generator --field stress_hoop --png view.png</pre>\n";
  s << "<h2>Case</h2>\n<pre>" << html_escape(in.case_text) << "</pre>\n</body></html>\n";
  return s.str();
}

}  // namespace sw
