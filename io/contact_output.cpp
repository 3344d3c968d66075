#include "io/contact_output.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "common/svg_plot.hpp"

namespace sw {
namespace {

constexpr double kArcmin = 10800.0 / std::numbers::pi;

double law_twist(const CatalogLaw& k, double T) { return k.law().twist_rad(T); }

}  // namespace

std::string contact_json(const ContactAnalysis& a, const std::string& case_path,
                         const std::optional<CatalogLaw>& reference) {
  using nlohmann::json;
  json j;
  j["case"] = case_path;
  j["rated_torque_Nm"] = a.rated_torque_Nm;
  json tt = json::array();
  for (const auto& s : a.steps)
    tt.push_back({{"torque_Nm", s.torque_Nm}, {"twist_rad", s.twist_rad}, {"pairs_in_contact", s.pairs_in_contact},
                  {"max_pair_force_N", s.max_pair_force_N}});
  j["torque_twist"] = tt;
  const SegmentLaw& k = a.catalog;
  j["catalog"] = {{"T1_Nm", k.t1_Nm}, {"T2_Nm", k.t2_Nm}, {"K1_Nm_per_rad", k.k1_Nm_per_rad},
                  {"K2_Nm_per_rad", k.k2_Nm_per_rad}, {"K3_Nm_per_rad", k.k3_Nm_per_rad},
                  {"breakpoints", k.breakpoints_fitted ? "fitted to the curve" : "the catalog's T1 and T2"}};
  if (reference)
    j["catalog_reference"] = {{"size", reference->size},
                              {"T1_Nm", reference->t1_Nm},
                              {"T2_Nm", reference->t2_Nm},
                              {"K1_Nm_per_rad", reference->k1_Nm_per_rad},
                              {"K2_Nm_per_rad", reference->k2_Nm_per_rad},
                              {"K3_Nm_per_rad", reference->k3_Nm_per_rad},
                              {"twist_at_T1_rad", law_twist(*reference, reference->t1_Nm)},
                              {"twist_at_T2_rad", law_twist(*reference, reference->t2_Nm)},
                              {"twist_at_rated_rad", law_twist(*reference, a.rated_torque_Nm)}};
  j["lost_motion_arcmin"] = a.lost_motion_rad * kArcmin;
  j["play_arcmin"] = a.play_rad * kArcmin;
  j["overlap_at_rest_um"] = a.overlap_at_rest_m * 1e6;
  j["min_closing_angle_arcmin"] = a.min_closing_rad * kArcmin;
  j["face_slices"] = a.face_slices;
  json sections = json::array();
  for (const auto& f : a.face_sections)
    sections.push_back({{"z_mm", f.z_m * 1e3}, {"w_major_um", f.w_major_m * 1e6},
                        {"first_closing_arcmin", f.first_closing_rad * kArcmin}, {"overlap_at_rest_um", f.overlap_m * 1e6},
                        {"overlap_angle_deg", f.overlap_phi_rad * 180 / std::numbers::pi}});
  j["face_sections"] = sections;
  j["twist_at_rated_arcmin"] = a.curve.twist_rad.back() * kArcmin;
  j["torque_balance_error_rel"] = a.torque_balance_error_rel;
  j["fem_reaction_torque_Nm"] = a.fem_reaction_torque_Nm;
  j["compliance_split"] = {{"engagement", a.split.engagement}, {"body", a.split.body}, {"teeth", a.split.teeth},
                           {"generator", a.split.generator}, {"circular_spline", a.split.circular_spline}};
  json edges = json::array();
  for (const auto& e : a.edges)
    edges.push_back({{"tooth", e.tooth}, {"angle_deg", e.phi_rad * 180 / std::numbers::pi}, {"engaged_at_rest", e.engaged}, {"contact_candidate", e.candidate},
                     {"radial_overlap_at_rest_um", e.overlap_at_rest_m * 1e6},
                     {"radial_overlap_min_um", e.overlap_min_m * 1e6}, {"radial_overlap_max_um", e.overlap_max_m * 1e6},
                     {"slips_over_the_tip", e.slips}, {"comes_into_mesh", e.enters}});
  j["zone_edges"] = {{"hold", a.zone_edges_hold}, {"teeth", edges},
                     {"torque_share_at_rated", a.edge_teeth_torque_share},
                     {"twist_at_rated_without_them_arcmin", std::isfinite(a.twist_at_rated_without_edge_teeth_rad)
                                                                ? json(a.twist_at_rated_without_edge_teeth_rad * kArcmin)
                                                                : json(nullptr)}};
  j["generator_support"] = a.generator_support;
  j["half_turn_pairs"] = a.half_turn_pairs;
  json flanks = json::array();
  const TorqueStep& neg = a.steps.front();
  const TorqueStep& pos = a.steps.back();
  for (std::size_t i = 0; i < a.flanks.size(); ++i) {
    const auto& f = a.flanks[i];
    flanks.push_back({{"tooth", f.tooth},
                      {"slice", f.slice},
                      {"angle_deg", f.phi_rad * 180 / std::numbers::pi},
                      {"flank", f.flank == Flank::Ccw ? "ccw" : "cw"},
                      {"touching", std::string(part_name(f.part_f)) + " on " + part_name(f.part_c)},
                      {"beyond_tip_circle_at_rest", f.beyond_tip_circle},
                      {"closing_angle_rad", f.closing_angle_rad},
                      {"lever_m", f.lever_m},
                      {"contact_radius_m", f.contact_radius_m},
                      {"tooth_pair_compliance_m_per_N", f.compliance_m_per_N},
                      {"force_at_plus_rated_N", pos.flank_force_N[i]},
                      {"force_at_minus_rated_N", neg.flank_force_N[i]}});
  }
  j["flanks"] = flanks;
  j["timings_s"] = {{"setup", a.setup_s}, {"influence", a.influence_s}, {"contact", a.contact_s}, {"check", a.check_s}};
  j["unknowns"] = a.unknowns;
  return j.dump(2) + "\n";
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

std::string contact_svg(const ContactAnalysis& a, const std::optional<CatalogLaw>& reference) {
  LinePlot tt;
  tt.title = "torque–twist of the drive (generator locked, output turned against the circular spline)";
  tt.x_label = "torque (N·m)";
  tt.y_label = "twist (arcmin)";
  PlotSeries curve{"computed", {}, {}, "#1f77b4"};
  for (std::size_t i = 0; i < a.steps.size(); ++i) {
    curve.x.push_back(a.steps[i].torque_Nm);
    curve.y.push_back(a.steps[i].twist_rad * kArcmin);
  }
  tt.series.push_back(curve);
  PlotSeries law{"three segments of the computed curve", {}, {}, "#2ca02c", true};
  PlotSeries cat{"catalog", {}, {}, "#d62728", true};
  for (int i = -100; i <= 100; ++i) {
    const double T = a.rated_torque_Nm * i / 100.0;
    law.x.push_back(T);
    law.y.push_back(a.catalog.twist_rad(T) * kArcmin);
    if (reference) {
      cat.x.push_back(T);
      cat.y.push_back(law_twist(*reference, T) * kArcmin);
    }
  }
  tt.series.push_back(law);
  if (reference) {
    cat.label = "catalog size " + std::to_string(reference->size);
    tt.series.push_back(cat);
  }
  LinePlot pf;
  pf.title = "force on each flank at ± rated torque (both teeth of a half-turn pair alike)";
  pf.x_label = "tooth angle from the major axis (deg)";
  pf.y_label = "flank force (N)";
  PlotSeries plus{"+rated, ccw flanks", {}, {}, "#1f77b4", false, true};
  PlotSeries minus{"−rated, cw flanks", {}, {}, "#ff7f0e", false, true};
  // A flank's force summed over the face's slices (one slice: the flank's own).
  std::map<std::pair<int, bool>, std::pair<double, double>> per_flank;  // (tooth, ccw) → (angle in deg, force)
  for (std::size_t i = 0; i < a.flanks.size(); ++i) {
    const bool ccw = a.flanks[i].flank == Flank::Ccw;
    auto& [deg, force] = per_flank[{a.flanks[i].tooth, ccw}];
    deg = a.flanks[i].phi_rad * 180 / std::numbers::pi;
    force += ccw ? a.steps.back().flank_force_N[i] : a.steps.front().flank_force_N[i];
  }
  for (const auto& [key, at] : per_flank) {
    PlotSeries& s = key.second ? plus : minus;
    s.x.push_back(at.first);
    s.y.push_back(at.second);
  }
  pf.series = {plus, minus};
  const std::string top = svg_line_plot(tt), bottom = svg_line_plot(pf);
  std::ostringstream s;
  s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << tt.width << "\" height=\"" << tt.height + pf.height
    << "\">\n<g>" << top << "</g>\n<g transform=\"translate(0," << tt.height << ")\">" << bottom << "</g>\n</svg>\n";
  return s.str();
}

}  // namespace sw
