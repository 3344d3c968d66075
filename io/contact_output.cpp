#include "io/contact_output.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <map>
#include <numbers>
#include <sstream>
#include <utility>

#include <nlohmann/json.hpp>

#include "common/constants.hpp"
#include "common/error.hpp"
#include "common/svg_plot.hpp"
#include "io/json_file.hpp"

namespace sw {
namespace {


double law_twist(const CatalogLaw& k, double T) { return k.law().twist_rad(T); }

ContactResult::Catalog catalog_figures(const SegmentLaw& k) {
  return {k.t1_Nm, k.t2_Nm, k.k1_Nm_per_rad, k.k2_Nm_per_rad, k.k3_Nm_per_rad,
          k.breakpoints_fitted ? "fitted to the curve" : "the catalog's T1 and T2"};
}

ContactResult::CatalogReference reference_figures(const CatalogLaw& k, double rated_torque_Nm) {
  ContactResult::CatalogReference r{k.size, k.ratio, k.t1_Nm, k.t2_Nm, k.k1_Nm_per_rad, k.k2_Nm_per_rad, {},
                                    law_twist(k, k.t1_Nm), law_twist(k, k.t2_Nm), {}};
  if (k.k3_Nm_per_rad > 0) {
    r.K3_Nm_per_rad = k.k3_Nm_per_rad;
    r.twist_at_rated_rad = law_twist(k, rated_torque_Nm);
  }
  return r;
}

ContactResult::FaceSection face_section_figures(const FaceSection& f) {
  return {f.z_m * 1e3, f.w_major_m * 1e6, f.first_closing_rad * kArcmin, f.overlap_m * 1e6,
          f.overlap_phi_rad * 180 / std::numbers::pi};
}

ContactResult::ZoneEdges zone_edge_figures(const ContactAnalysis& a) {
  ContactResult::ZoneEdges z;
  z.hold = a.zone_edges_hold;
  for (const auto& e : a.edges)
    z.teeth.push_back({e.tooth, e.phi_rad * 180 / std::numbers::pi, e.engaged, e.candidate, e.overlap_at_rest_m * 1e6,
                       e.overlap_min_m * 1e6, e.overlap_max_m * 1e6, e.slips, e.enters});
  z.torque_share_at_rated = a.edge_teeth_torque_share;
  if (std::isfinite(a.twist_at_rated_without_edge_teeth_rad))
    z.twist_at_rated_without_them_arcmin = a.twist_at_rated_without_edge_teeth_rad * kArcmin;
  return z;
}

/// Each flank, with its force at −rated and +rated torque (the first and last step).
std::vector<ContactResult::Flank> flank_figures(const ContactAnalysis& a) {
  std::vector<ContactResult::Flank> out;
  const TorqueStep& neg = a.steps.front();
  const TorqueStep& pos = a.steps.back();
  for (std::size_t i = 0; i < a.flanks.size(); ++i) {
    const auto& f = a.flanks[i];
    out.push_back({f.tooth, f.slice, f.phi_rad * 180 / std::numbers::pi, f.flank == Flank::Ccw ? "ccw" : "cw",
                   std::string(part_name(f.part_f)) + " on " + part_name(f.part_c), f.beyond_tip_circle,
                   f.closing_angle_rad, f.lever_m, f.contact_radius_m, f.compliance_m_per_N, pos.flank_force_N[i],
                   neg.flank_force_N[i]});
  }
  return out;
}

}  // namespace

ContactResult contact_result(const ContactAnalysis& a, const Case& c, const std::optional<CatalogLaw>& reference) {
  ContactResult r;
  r.case_path = c.path;
  r.provenance = provenance_of(c);
  r.rated_torque_Nm = a.rated_torque_Nm;
  if (a.friction) {  // the loop's two branches, the loading one first
    for (const auto& s : a.friction->steps)
      r.torque_twist.push_back({s.torque_Nm, s.twist_rad, s.pairs_in_contact, s.max_pair_force_N, s.branch});
    r.friction = ContactResult::Friction{a.friction->friction_coefficient, a.friction->steps_per_quarter,
                                         a.friction->cycles};
    r.hysteresis_loss_arcmin = a.friction->hysteresis_loss_rad * kArcmin;
    r.rig_hysteresis_loss_arcmin = a.friction->rig_hysteresis_loss_rad * kArcmin;
    r.widest_loop_width_arcmin = a.friction->widest.width_rad * kArcmin;
    r.widest_loop_width_at_Nm = a.friction->widest.torque_Nm;
    r.dissipated_energy_J = a.friction->dissipated_energy_J;
    r.friction_work_J = a.friction->friction_work_J;
  } else {
    for (const auto& s : a.steps)
      r.torque_twist.push_back({s.torque_Nm, s.twist_rad, s.pairs_in_contact, s.max_pair_force_N, std::nullopt});
  }
  r.catalog = catalog_figures(a.catalog);
  if (reference) r.catalog_reference = reference_figures(*reference, a.rated_torque_Nm);
  r.lost_motion_arcmin = a.lost_motion_rad * kArcmin;
  r.play_arcmin = a.play_rad * kArcmin;
  r.overlap_at_rest_um = a.overlap_at_rest_m * 1e6;
  r.min_closing_angle_arcmin = a.min_closing_rad * kArcmin;
  r.face_slices = a.face_slices;
  for (const auto& f : a.face_sections) r.face_sections.push_back(face_section_figures(f));
  r.twist_at_rated_arcmin = a.curve.twist_rad.back() * kArcmin;
  r.torque_balance_error_rel = a.torque_balance_error_rel;
  r.fem_reaction_torque_Nm = a.fem_reaction_torque_Nm;
  r.compliance_split = {a.split.engagement, a.split.body, a.split.teeth, a.split.generator, a.split.circular_spline,
                        ContactResult::BodyParts{a.split.wall, a.split.rim, a.split.diaphragm, a.split.boss}};
  r.zone_edges = zone_edge_figures(a);
  r.generator_support = a.generator_support;
  r.solver.method = a.solver;
  r.half_turn_pairs = a.half_turn_pairs;
  r.flanks = flank_figures(a);
  r.timings_s = {a.setup_s, a.influence_s, a.contact_s, a.check_s};
  r.unknowns = a.unknowns;
  return r;
}

ContactResult::AccuracyBand accuracy_band_figures(const AccuracyBand& band) {
  ContactResult::AccuracyBand r;
  r.standard = "ISO 1328-1:2013";
  r.deviations = "each tooth's position uniform in +-f_pT/2 (single pitch within f_pT), a tooth's equal to its "
                 "half-turn partner's; runout, profile and helix deviations left out";
  r.tolerance_class = band.tolerance_class;
  r.drives = band.drives;
  r.single_pitch_tolerance_flexspline_um = band.flexspline.single_pitch_um;
  r.single_pitch_tolerance_circular_spline_um = band.circular_spline.single_pitch_um;
  r.outside_scope = band.outside_scope;
  const auto over = [&](auto figure, double scale) {
    std::vector<double> v;
    for (const AccuracyBand::Drive& d : band.drive) v.push_back(figure(d) * scale);
    return spread(v);
  };
  using D = AccuracyBand::Drive;
  r.K1_Nm_per_rad = over([](const D& d) { return d.k1_Nm_per_rad; }, 1);
  r.K2_Nm_per_rad = over([](const D& d) { return d.k2_Nm_per_rad; }, 1);
  r.K3_Nm_per_rad = over([](const D& d) { return d.k3_Nm_per_rad; }, 1);
  r.twist_at_rated_arcmin = over([](const D& d) { return d.twist_at_rated_rad; }, kArcmin);
  r.lost_motion_arcmin = over([](const D& d) { return d.lost_motion_rad; }, kArcmin);
  r.play_arcmin = over([](const D& d) { return d.play_rad; }, kArcmin);
  r.preload_overlap_at_rest_um = over([](const D& d) { return d.overlap_at_rest_m; }, 1e6);
  if (!band.drive.empty() && band.drive.front().hysteresis_rad)
    r.hysteresis_loss_arcmin = over([](const D& d) { return d.hysteresis_rad.value_or(0); }, kArcmin);
  return r;
}

// ---- contact.json's field tables: its keys, each with the member that holds it

static auto fields(std::type_identity<Spread>) {
  using T = Spread;
  return std::tuple{field("min", &T::min), field("median", &T::median), field("max", &T::max)};
}

static auto fields(std::type_identity<ContactResult::AccuracyBand>) {
  using T = ContactResult::AccuracyBand;
  return std::tuple{field("standard", &T::standard), field("tolerance_class", &T::tolerance_class),
                    field("drives", &T::drives), field("deviations", &T::deviations),
                    field("single_pitch_tolerance_flexspline_um", &T::single_pitch_tolerance_flexspline_um),
                    field("single_pitch_tolerance_circular_spline_um", &T::single_pitch_tolerance_circular_spline_um),
                    null_when_absent("outside_scope", &T::outside_scope),
                    field("K1_Nm_per_rad", &T::K1_Nm_per_rad), field("K2_Nm_per_rad", &T::K2_Nm_per_rad),
                    field("K3_Nm_per_rad", &T::K3_Nm_per_rad), field("twist_at_rated_arcmin", &T::twist_at_rated_arcmin),
                    field("lost_motion_arcmin", &T::lost_motion_arcmin), field("play_arcmin", &T::play_arcmin),
                    field("preload_overlap_at_rest_um", &T::preload_overlap_at_rest_um),
                    field("hysteresis_loss_arcmin", &T::hysteresis_loss_arcmin)};
}

static auto fields(std::type_identity<ContactResult::Step>) {
  using T = ContactResult::Step;
  return std::tuple{field("torque_Nm", &T::torque_Nm), field("twist_rad", &T::twist_rad),
                    field("pairs_in_contact", &T::pairs_in_contact), field("max_pair_force_N", &T::max_pair_force_N),
                    field("branch", &T::branch)};
}

static auto fields(std::type_identity<ContactResult::Friction>) {
  using T = ContactResult::Friction;
  return std::tuple{field("friction_coefficient", &T::friction_coefficient),
                    field("steps_per_quarter", &T::steps_per_quarter), field("cycles", &T::cycles)};
}

static auto fields(std::type_identity<ContactResult::Catalog>) {
  using T = ContactResult::Catalog;
  return std::tuple{field("T1_Nm", &T::T1_Nm), field("T2_Nm", &T::T2_Nm), field("K1_Nm_per_rad", &T::K1_Nm_per_rad),
                    field("K2_Nm_per_rad", &T::K2_Nm_per_rad), field("K3_Nm_per_rad", &T::K3_Nm_per_rad),
                    field("breakpoints", &T::breakpoints)};
}

static auto fields(std::type_identity<ContactResult::CatalogReference>) {
  using T = ContactResult::CatalogReference;
  return std::tuple{field("size", &T::size), field("ratio", &T::ratio), field("T1_Nm", &T::T1_Nm),
                    field("T2_Nm", &T::T2_Nm), field("K1_Nm_per_rad", &T::K1_Nm_per_rad),
                    field("K2_Nm_per_rad", &T::K2_Nm_per_rad), field("K3_Nm_per_rad", &T::K3_Nm_per_rad),
                    field("twist_at_T1_rad", &T::twist_at_T1_rad),
                    field("twist_at_T2_rad", &T::twist_at_T2_rad), field("twist_at_rated_rad", &T::twist_at_rated_rad)};
}

static auto fields(std::type_identity<ContactResult::FaceSection>) {
  using T = ContactResult::FaceSection;
  return std::tuple{field("z_mm", &T::z_mm), field("w_major_um", &T::w_major_um),
                    field("first_closing_arcmin", &T::first_closing_arcmin),
                    field("overlap_at_rest_um", &T::overlap_at_rest_um),
                    field("overlap_angle_deg", &T::overlap_angle_deg)};
}

static auto fields(std::type_identity<ContactResult::BodyParts>) {
  using T = ContactResult::BodyParts;
  return std::tuple{field("wall", &T::wall), field("rim", &T::rim), field("diaphragm", &T::diaphragm),
                    field("boss", &T::boss)};
}

static auto fields(std::type_identity<ContactResult::Split>) {
  using T = ContactResult::Split;
  return std::tuple{field("engagement", &T::engagement), field("body", &T::body), field("teeth", &T::teeth),
                    field("generator", &T::generator), field("circular_spline", &T::circular_spline),
                    field("body_parts", &T::body_parts)};
}

static auto fields(std::type_identity<ContactResult::EdgeTooth>) {
  using T = ContactResult::EdgeTooth;
  return std::tuple{field("tooth", &T::tooth), field("angle_deg", &T::angle_deg),
                    field("engaged_at_rest", &T::engaged_at_rest), field("contact_candidate", &T::contact_candidate),
                    field("radial_overlap_at_rest_um", &T::radial_overlap_at_rest_um),
                    field("radial_overlap_min_um", &T::radial_overlap_min_um),
                    field("radial_overlap_max_um", &T::radial_overlap_max_um),
                    field("slips_over_the_tip", &T::slips_over_the_tip), field("comes_into_mesh", &T::comes_into_mesh)};
}

static auto fields(std::type_identity<ContactResult::ZoneEdges>) {
  using T = ContactResult::ZoneEdges;
  return std::tuple{field("hold", &T::hold), field("teeth", &T::teeth),
                    field("torque_share_at_rated", &T::torque_share_at_rated),
                    null_when_absent("twist_at_rated_without_them_arcmin", &T::twist_at_rated_without_them_arcmin)};
}

static auto fields(std::type_identity<ContactResult::Flank>) {
  using T = ContactResult::Flank;
  return std::tuple{field("tooth", &T::tooth), field("slice", &T::slice), field("angle_deg", &T::angle_deg),
                    field("flank", &T::flank), field("touching", &T::touching),
                    field("beyond_tip_circle_at_rest", &T::beyond_tip_circle_at_rest),
                    field("closing_angle_rad", &T::closing_angle_rad), field("lever_m", &T::lever_m),
                    field("contact_radius_m", &T::contact_radius_m),
                    field("tooth_pair_compliance_m_per_N", &T::tooth_pair_compliance_m_per_N),
                    field("force_at_plus_rated_N", &T::force_at_plus_rated_N),
                    field("force_at_minus_rated_N", &T::force_at_minus_rated_N)};
}

static auto fields(std::type_identity<ContactResult::Timings>) {
  using T = ContactResult::Timings;
  return std::tuple{field("setup", &T::setup), field("influence", &T::influence), field("contact", &T::contact),
                    field("check", &T::check)};
}

static auto fields(std::type_identity<ContactResult::Solver>) {
  return std::tuple{field("method", &ContactResult::Solver::method)};
}

static auto fields(std::type_identity<ContactResult>) {
  using T = ContactResult;
  return std::tuple{field("rated_torque_Nm", &T::rated_torque_Nm),
                    field("torque_twist", &T::torque_twist), field("catalog", &T::catalog),
                    field("catalog_reference", &T::catalog_reference),
                    field("lost_motion_arcmin", &T::lost_motion_arcmin), field("play_arcmin", &T::play_arcmin),
                    field("overlap_at_rest_um", &T::overlap_at_rest_um),
                    field("min_closing_angle_arcmin", &T::min_closing_angle_arcmin),
                    field("face_slices", &T::face_slices), field("face_sections", &T::face_sections),
                    field("twist_at_rated_arcmin", &T::twist_at_rated_arcmin),
                    field("torque_balance_error_rel", &T::torque_balance_error_rel),
                    field("fem_reaction_torque_Nm", &T::fem_reaction_torque_Nm),
                    field("compliance_split", &T::compliance_split), field("zone_edges", &T::zone_edges),
                    field("generator_support", &T::generator_support), field("half_turn_pairs", &T::half_turn_pairs),
                    field("flanks", &T::flanks), field("timings_s", &T::timings_s), field("unknowns", &T::unknowns),
                    field("solver", &T::solver), field("friction", &T::friction),
                    field("hysteresis_loss_arcmin", &T::hysteresis_loss_arcmin),
                    field("rig_hysteresis_loss_arcmin", &T::rig_hysteresis_loss_arcmin),
                    field("widest_loop_width_arcmin", &T::widest_loop_width_arcmin),
                    field("widest_loop_width_at_Nm", &T::widest_loop_width_at_Nm),
                    field("dissipated_energy_J", &T::dissipated_energy_J), field("friction_work_J", &T::friction_work_J),
                    field("accuracy_band", &T::accuracy_band), field("case_file", &T::case_path), flattened(&T::provenance)};
}

std::string contact_json(const ContactResult& r) { return to_json_object(r).dump(2) + "\n"; }

namespace {
constexpr const char* kContactCannotOpen =
    "cannot be read; give the contact.json written by `strainwave contact CASE.toml` (or `strainwave run`)";
constexpr const char* kContactExpected = "the contact.json of `strainwave contact`";
}  // namespace

ContactResult read_contact_result(const std::filesystem::path& path) {
  return read_object<ContactResult>(JsonIn::open(path, kContactCannotOpen, kContactExpected));
}

namespace {

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

/// The points of `torque_twist` in the file's order.
TorqueTwist read_points(const JsonIn& list) {
  const std::vector<JsonIn> points = list.elements();
  if (points.size() < 2)
    list.fail("a list of 2 or more {torque_Nm, twist_rad} from -rated to +rated torque (and back)");
  TorqueTwist loop;
  for (const JsonIn& p : points) {
    loop.torque_Nm.push_back(p["torque_Nm"].finite());
    loop.twist_rad.push_back(p["twist_rad"].finite());
  }
  return loop;
}

/// The loop's loading branch (torque rising to the largest) and unloading branch (falling back from there), both
/// with ascending torque; InputError naming the point where the torque goes the wrong way. Both hold the largest
/// torque, so where both span a torque range, the ranges overlap.
std::pair<TorqueTwist, TorqueTwist> branches(const TorqueTwist& loop, const std::string& file) {
  const auto& t = loop.torque_Nm;
  const auto& phi = loop.twist_rad;
  const std::size_t n = t.size();
  std::size_t top = 0;
  while (top + 1 < n && t[top + 1] >= t[top]) ++top;
  auto wrong = [&](std::size_t i, const std::string& what) {
    return InputError(file + ": torque_twist[" + std::to_string(i) + "].torque_Nm = " + num(t[i]) + " after " +
                      num(t[i - 1]) + " " + what + "; expected torque rising from -rated to +rated (the loading "
                      "branch), then optionally falling back (the unloading branch)");
  };
  if (top == 0) throw wrong(1, "falls at the start");
  for (std::size_t i = top + 1; i < n; ++i)
    if (t[i] > t[i - 1]) throw wrong(i, "rises again on the unloading branch");
  TorqueTwist load{{t.begin(), t.begin() + top + 1}, {phi.begin(), phi.begin() + top + 1}};
  TorqueTwist unload{{t.rbegin(), t.rend() - top}, {phi.rbegin(), phi.rend() - top}};  // ascending
  return {load, unload};
}

}  // namespace

namespace {

ContactCurve contact_curve(const JsonIn& j) {
  const std::string& file = j.file();
  ContactCurve c;
  const JsonIn rated = j["rated_torque_Nm"];
  c.rated_torque_Nm = rated.finite();
  if (!(c.rated_torque_Nm > 0.0)) rated.fail("a rated torque > 0");
  if (const auto k = j.find("catalog")) {
    c.catalog_t1_Nm = (*k)["T1_Nm"].finite();
    c.catalog_t2_Nm = (*k)["T2_Nm"].finite();
  }
  const auto [load, unload] = branches(read_points(j["torque_twist"]), file);
  if (!spans_torque(load))
    throw InputError(file + ": torque_twist: torque_Nm = " + num(load.torque_Nm.front()) + " at every point; expected "
                     "a curve from -rated to +rated torque");
  c.middle_line = middle_line(load, unload);
  if (spans_torque(unload)) c.loop = TorqueLoop{load, unload};
  return c;
}

}  // namespace

ContactCurve read_contact_curve(const std::filesystem::path& path) {
  return contact_curve(JsonIn::open(path, kContactCannotOpen, kContactExpected));
}

ContactCurve parse_contact_curve(const std::string& contact_json_text, const std::string& name) {
  return contact_curve(JsonIn::parse(contact_json_text, name, kContactExpected));
}

std::string torque_twist_csv(const ContactAnalysis& a) {
  std::ostringstream s;
  s << "torque_Nm,twist_rad,twist_arcmin,pairs_in_contact,max_pair_force_N\n";
  char line[160];
  for (const auto& t : a.steps) {
    std::snprintf(line, sizeof line, "%.9g,%.9e,%.6f,%d,%.6g\n", t.torque_Nm, t.twist_rad, t.twist_rad * kArcmin,
                  t.pairs_in_contact, t.max_pair_force_N);
    s << line;
  }
  return s.str();
}

namespace {

/// The steps whose flank forces the panel draws at −rated and +rated: the curve's ends, or with friction the loop's
/// bottom (reached on unloading) and its top (the loading branch's end).
std::pair<const TorqueStep*, const TorqueStep*> steps_at_rated(const ContactAnalysis& a) {
  if (!a.friction) return {&a.steps.front(), &a.steps.back()};
  const std::vector<TorqueStep>& loop = a.friction->steps;
  const auto top = std::find_if(loop.begin(), loop.end(), [](const TorqueStep& s) { return s.branch == "unloading"; });
  return {&loop.front(), &*std::prev(top)};
}

/// The normal force on each flank at ±rated torque, summed over the face's slices (one slice: the flank's own).
LinePlot flank_force_panel(const ContactAnalysis& a) {
  LinePlot pf;
  pf.title = std::string(a.friction ? "normal force on each flank at ± rated torque on the loop"
                                     : "force on each flank at ± rated torque") +
             " (both teeth of a half-turn pair alike)";
  pf.x_label = "tooth angle from the major axis (deg)";
  pf.y_label = "flank force (N)";
  PlotSeries plus{a.friction ? "+rated (the loop's top), ccw flanks" : "+rated, ccw flanks", {}, {}, "#1f77b4", false,
                  true};
  PlotSeries minus{a.friction ? "−rated (the loop's bottom), cw flanks" : "−rated, cw flanks", {}, {}, "#ff7f0e", false,
                   true};
  const auto [at_minus, at_plus] = steps_at_rated(a);
  std::map<std::pair<int, bool>, std::pair<double, double>> per_flank;  // (tooth, ccw) → (angle in deg, force)
  for (std::size_t i = 0; i < a.flanks.size(); ++i) {
    const bool ccw = a.flanks[i].flank == Flank::Ccw;
    auto& [deg, force] = per_flank[{a.flanks[i].tooth, ccw}];
    deg = a.flanks[i].phi_rad * 180 / std::numbers::pi;
    force += ccw ? at_plus->flank_force_N[i] : at_minus->flank_force_N[i];
  }
  for (const auto& [key, at] : per_flank) {
    PlotSeries& s = key.second ? plus : minus;
    s.x.push_back(at.first);
    s.y.push_back(at.second);
  }
  pf.series = {plus, minus};
  return pf;
}

}  // namespace

std::string contact_svg(const ContactAnalysis& a, const std::optional<CatalogLaw>& reference) {
  LinePlot tt;
  tt.title = "torque–twist of the drive (generator locked, output turned against the circular spline)";
  tt.x_label = "torque (N·m)";
  tt.y_label = "twist (arcmin)";
  PlotSeries curve{a.friction ? "computed loop (friction on the flanks)" : "computed", {}, {}, "#1f77b4"};
  for (const TorqueStep& s : a.friction ? a.friction->steps : a.steps) {
    curve.x.push_back(s.torque_Nm);
    curve.y.push_back(s.twist_rad * kArcmin);
  }
  tt.series.push_back(curve);
  PlotSeries law{"three segments of the computed curve", {}, {}, "#2ca02c", true};
  PlotSeries cat{"catalog", {}, {}, "#d62728", true};
  for (int i = -100; i <= 100; ++i) {
    const double T = a.rated_torque_Nm * i / 100.0;
    law.x.push_back(T);
    law.y.push_back(a.catalog.twist_rad(T) * kArcmin);
    if (reference && std::isfinite(law_twist(*reference, T))) {  // a row without K3 ends at ±T2
      cat.x.push_back(T);
      cat.y.push_back(law_twist(*reference, T) * kArcmin);
    }
  }
  tt.series.push_back(law);
  if (reference) {
    cat.label = "catalog size " + std::to_string(reference->size);
    tt.series.push_back(cat);
  }
  const LinePlot pf = flank_force_panel(a);
  const std::string top = svg_line_plot(tt), bottom = svg_line_plot(pf);
  std::ostringstream s;
  s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << tt.width << "\" height=\"" << tt.height + pf.height
    << "\">\n<g>" << top << "</g>\n<g transform=\"translate(0," << tt.height << ")\">" << bottom << "</g>\n</svg>\n";
  return s.str();
}

}  // namespace sw
