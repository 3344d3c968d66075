// report.html against the typed results it reads: every figure the page shows for result.json, backlash.json and
// contact.json stands in its row (a row dropped from the page, or one reading a key the writer does not write, fails
// here), and a section whose file is missing is left out.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "common/error.hpp"
#include "common/svg_plot.hpp"
#include "io/run_report.hpp"
#include "tests/io/output_samples.hpp"

namespace {

namespace fs = std::filesystem;
using namespace sw::testing;

std::string fmt(const char* format, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

using Rows = std::vector<std::pair<std::string, std::string>>;  ///< (what, value)

/// The page of a run folder holding the given files.
std::string page_of(const fs::path& dir, const sw::FemResult& fem, const sw::BacklashResult* backlash,
                    const sw::ContactResult* contact) {
  std::ofstream(dir / "result.json") << sw::fem_result_json(fem);
  if (backlash) std::ofstream(dir / "backlash.json") << sw::backlash_json(*backlash);
  if (contact) std::ofstream(dir / "contact.json") << sw::contact_json(*contact);
  sw::RunReportInputs in;
  in.out_dir = dir;
  in.case_path = fem.case_path;
  in.case_text = "[flexspline]";
  return sw::run_report_html(in);
}

void expect_rows(const std::string& page, const Rows& rows) {
  for (const auto& [what, value] : rows)
    EXPECT_NE(page.find("<tr><td>" + sw::html_escape(what) + "</td><td class='v'>" + sw::html_escape(value) + "</td>"),
              std::string::npos)
        << "no row `" << what << "` = `" << value << "`";
}

Rows fem_rows(const sw::FemResult& r) {
  const auto& mesh = std::get<sw::TetMeshFigures>(r.mesh);
  const auto& g = *r.generator;
  const auto& h = r.hoop_stress_MPa;
  return {{"flexspline body wind-up φ₀ at the case torque", fmt("%.4e rad", r.phi0_rad)},
          {"flexspline body torsional stiffness 1/C_τ", fmt("%.4g N·m/rad", 1.0 / r.compliance_rad_per_Nm)},
          {"closed form (body wall + diaphragm + rim)", fmt("%.4e rad", r.phi0_theory_cup_rad)},
          {"mean rotation over the engagement zones", fmt("%.4e rad", r.phi0_engaged_rad)},
          {"reaction torque (clamp and generator) vs applied",
           fmt("%.9g N·m", r.reaction_torque_Nm) + " vs " + fmt("%.9g N·m", r.applied_torque_Nm)},
          {"mesh", fmt("%.0f nodes, ", mesh.nodes) + fmt("%.0f TET10", mesh.elements)},
          {"solver", fmt("%.0f equations", r.solver.equations)},
          {"run time, peak memory", fmt("%.1f s", r.timings_s.total)},
          {"wave generator", g.model},
          {"generator: total radial force", fmt("%.1f N", g.total_radial_force_N)},
          {"w at the major / minor axis", fmt("%+.4f mm", g.w_major_axis_mm) + " / " + fmt("%+.4f mm", g.w_minor_axis_mm)},
          {"nominal hoop bending stress", fmt("%+.0f MPa", h.nominal_bending)},
          {"local hoop stress peaks", fmt("%+.0f", h.local_peak_tensile) + fmt(" / %+.0f MPa", h.local_peak_compressive)},
          {"fatigue safety factor, " + r.fatigue->rim.place, fmt("%.2f", *r.fatigue->rim.goodman_safety_factor)},
          {"fatigue safety factor, " + r.fatigue->diaphragm->place, "not computed"}};
}

Rows backlash_rows(const sw::BacklashResult& b) {
  const auto& g = b.geometry_check;
  return {{"interference at rest", g.interference_at_rest ? "yes" : "no"},
          {"working depth at the major axis", fmt("%.3f mm", g.working_depth_mm)},
          {"major-axis pair: dead band", fmt("%.3f arcmin", g.major_axis_play_arcmin)},
          {"geometric angular play over a revolution",
           fmt("%.3f", b.angular_play_arcmin.min) + fmt(" … %.3f arcmin", b.angular_play_arcmin.max)},
          {"smallest clearance over a revolution (basic, with φ₀)",
           fmt("%.2f µm", b.min_backlash_basic_mm * 1e3) + fmt(" / %.2f µm", b.min_backlash_compensated_mm * 1e3)}};
}

Rows contact_rows(const sw::ContactResult& a) {
  const auto& k = a.catalog;
  const auto& s = a.compliance_split;
  return {{"twist at rated torque", fmt("%.3f arcmin", a.twist_at_rated_arcmin)},
          {"three segments",
           fmt("K1 %.4g", k.K1_Nm_per_rad) + fmt(", K2 %.4g", k.K2_Nm_per_rad) + fmt(", K3 %.4g N·m/rad", k.K3_Nm_per_rad)},
          {"lost motion", fmt("%.3f arcmin", a.lost_motion_arcmin)},
          {"play", fmt("%.3f arcmin", a.play_arcmin)},
          {"overlap at rest", fmt("%.2f µm", a.overlap_at_rest_um)},
          {"twist at rated, by part",
           fmt("body %.0f %%", 100 * s.body) + fmt(" (rim %.0f", 100 * s.body_parts->rim) +
               fmt(", wall %.0f", 100 * s.body_parts->wall) + fmt(", diaphragm %.0f", 100 * s.body_parts->diaphragm) +
               fmt(", boss %.0f)", 100 * s.body_parts->boss) + fmt(", teeth %.0f %%", 100 * s.teeth) +
               fmt(", generator %.0f %%", 100 * s.generator) + fmt(", circular spline %.0f %%", 100 * s.circular_spline) +
               fmt(", tangent's intercept %.0f %%", 100 * s.engagement)},
          {"checks", fmt("balance %.1e", a.torque_balance_error_rel)}};
}

TEST(RunReport, EveryFigureOfTheThreeResultsStandsInItsRow) {
  const fs::path d = scratch_dir("report_rows");
  const sw::FemResult fem = sample_fem_result();
  const sw::BacklashResult backlash = sample_backlash_result();
  const sw::ContactResult contact = sample_contact_result();
  const std::string page = page_of(d, fem, &backlash, &contact);
  expect_rows(page, fem_rows(fem));
  expect_rows(page, backlash_rows(backlash));
  expect_rows(page, contact_rows(contact));
  fs::remove_all(d);
}

TEST(RunReport, TheSplitSaysWhatItsGeneratorCountsOrThatItIsRigid) {
  const fs::path d = scratch_dir("report_generator_share");
  sw::ContactResult contact = sample_contact_result();
  ASSERT_GT(contact.compliance_split.generator, 0);
  const std::string balls = sw::html_escape("the generator: its balls' Hertzian contacts");
  const std::string rigid = sw::html_escape("the generator: rigid: the case's generator has no bearing compliance");
  std::string page = page_of(d, sample_fem_result(), nullptr, &contact);
  EXPECT_NE(page.find(balls), std::string::npos);
  EXPECT_EQ(page.find(rigid), std::string::npos);
  contact.compliance_split.engagement += contact.compliance_split.generator;
  contact.compliance_split.generator = 0;  // a rigid cam, or the band held at the given forces
  page = page_of(d, sample_fem_result(), nullptr, &contact);
  EXPECT_EQ(page.find(balls), std::string::npos);
  EXPECT_NE(page.find(rigid), std::string::npos);
  fs::remove_all(d);
}

// K1 and the lost motion say, as contact's summary does, when the face's sections leave them unresolved along the
// face (fewer than 12 sections of straight teeth), and nothing of it with enough sections or one (the relieved face).
TEST(RunReport, TheCurveBelowT1SaysWhenTheFaceIsNotResolved) {
  const fs::path d = scratch_dir("report_face_sections");
  sw::ContactResult contact = sample_contact_result();
  ASSERT_EQ(contact.face_slices, 3);
  const std::string caveat = sw::html_escape(
      "the face in 3 sections does not resolve the curve below T1 along the face, which takes about 12");
  std::string page = page_of(d, sample_fem_result(), nullptr, &contact);
  const std::size_t first = page.find(caveat);
  ASSERT_NE(first, std::string::npos);
  EXPECT_NE(page.find(caveat, first + 1), std::string::npos) << "the K1 row and the lost motion row both say it";
  for (int n : {1, 12}) {
    contact.face_slices = n;
    page = page_of(d, sample_fem_result(), nullptr, &contact);
    EXPECT_EQ(page.find("does not resolve the curve below T1"), std::string::npos) << n << " sections";
  }
  fs::remove_all(d);
}

TEST(RunReport, AHarmonicRunShowsItsSectionAndNoMissingSections) {
  const fs::path d = scratch_dir("report_fourier");
  const sw::FemResult fem = sample_fourier_result();
  const std::string page = page_of(d, fem, nullptr, nullptr);
  expect_rows(page, {{"mesh", "947 nodes, 418 6-node triangles"}});
  EXPECT_EQ(page.find("fatigue"), std::string::npos);
  EXPECT_EQ(page.find("<h2>Backlash</h2>"), std::string::npos);
  EXPECT_EQ(page.find("tooth contact)</h2>"), std::string::npos);
  fs::remove_all(d);
}

TEST(RunReport, ABacklashJsonOfAnotherShapeIsRefusedNamingTheFile) {
  const fs::path d = scratch_dir("report_bad_backlash");
  std::ofstream(d / "backlash.json") << R"({"case": "x.toml"})";
  try {
    (void)page_of(d, sample_fem_result(), nullptr, nullptr);
    FAIL() << "no error";
  } catch (const sw::InputError& e) {
    EXPECT_NE(std::string(e.what()).find((d / "backlash.json").string() + ": neutral_curve is missing"),
              std::string::npos) << e.what();
  }
  fs::remove_all(d);
}

}  // namespace
