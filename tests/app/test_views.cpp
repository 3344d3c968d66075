// The outputs as people look at them: a FEM result and the tooth profiles rendered by ParaView's pvbatch (headless,
// scripts/pvbatch.sh) to PNG, with what ParaView computed (warped bounds, field range in MPa) checked against the
// files read through VTK here; the reconcile page opened in headless Chromium (no console errors, not blank).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include "tests/cli.hpp"

namespace {

namespace fs = std::filesystem;
using namespace sw::testing;

/// A coarse seed cup run once for every test here (fem + backlash): the shipped case at 1.2 mm, one wall layer, no
/// corner grading.
const fs::path& coarse_seed_run() {
  static const fs::path out = [] {
    const fs::path dir = fs::temp_directory_path() / ("sw_views_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    std::ifstream in("cases/seed_190_192.toml");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (const auto& [from, to] : {std::pair<std::string, std::string>{"size_mm = 0.6", "size_mm = 1.2"},
                                   {"wall_layers = 2", "wall_layers = 1\ncorner_levels = 0"}})
      text.replace(text.find(from), from.size(), to);
    { std::ofstream(dir / "seed_coarse.toml") << text; }
    const CommandRun r = run_shell(strainwave_binary() + " run --quiet " + (dir / "seed_coarse.toml").string() +
                     " --out " + (dir / "out").string());
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return dir / "out";
  }();
  return out;
}

/// PNG written and not blank: a real render of a 1200 x 800 view is 17 kB (a few tooth outlines) to tens of kB; a
/// blank one (background and orientation axes) compresses to ~5 kB.
void expect_rendered(const fs::path& png) {
  ASSERT_TRUE(fs::exists(png));
  EXPECT_GT(fs::file_size(png), 12000u) << png;
}

TEST(ParaView, RendersTheWarpedGeneratorCaseAndComputesWhatTheFileHolds) {
  const fs::path out = coarse_seed_run();
  const fs::path png = out / "generator.png", probe = out / "generator_probe.json";
  const double scale = 20.0;
  const CommandRun r = run_shell("scripts/pvbatch.sh cases/view_flexspline.py " + out.string() +
                   " --case generator --field stress_hoop --scale 20 --png " + png.string() + " --probe " +
                   probe.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  expect_rendered(png);
  std::ifstream pin(probe);
  const auto p = nlohmann::json::parse(pin);
  EXPECT_EQ(p["field"], "stress_hoop_MPa");
  // The same quantities from the .vtu through VTK's reader: bounds of x + scale·u and the range of stress_hoop/1e6.
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName((out / "flexspline_generator.vtu").c_str());
  reader->Update();
  vtkUnstructuredGrid* grid = reader->GetOutput();
  vtkDataArray* u = grid->GetPointData()->GetArray("displacement");
  vtkDataArray* hoop = grid->GetPointData()->GetArray("stress_hoop");
  ASSERT_NE(u, nullptr);
  ASSERT_NE(hoop, nullptr);
  std::array<double, 6> b = {1e30, -1e30, 1e30, -1e30, 1e30, -1e30};
  double lo = 1e30, hi = -1e30;
  for (vtkIdType i = 0; i < grid->GetNumberOfPoints(); ++i) {
    double x[3];
    grid->GetPoint(i, x);
    for (int k = 0; k < 3; ++k) {
      const double w = x[k] + scale * u->GetComponent(i, k);
      b[2 * k] = std::min(b[2 * k], w);
      b[2 * k + 1] = std::max(b[2 * k + 1], w);
    }
    lo = std::min(lo, hoop->GetTuple1(i) / 1e6);
    hi = std::max(hi, hoop->GetTuple1(i) / 1e6);
  }
  for (int k = 0; k < 6; ++k) EXPECT_NEAR(p["bounds"][k].get<double>(), b[k], 1e-9 * std::max(1.0, std::abs(b[k]))) << k;
  EXPECT_NEAR(p["range"][0].get<double>(), lo, 1e-6 * std::abs(lo));
  EXPECT_NEAR(p["range"][1].get<double>(), hi, 1e-6 * std::abs(hi));
  // And the picture shows the physics: the major axis (x) warped out by at least scale·w0/2 beyond the rim's outer
  // radius (~19.27 mm; w0 = 0.2 mm at the neutral circle, more at the open end and under the four force patches).
  const double w0 = 0.2e-3, r_out = 19.27e-3;
  EXPECT_GT(p["bounds"][1].get<double>(), r_out + 0.5 * scale * w0);
}

TEST(ParaView, RendersTheToothProfiles) {
  const fs::path out = coarse_seed_run();
  const fs::path png = out / "profiles.png", probe = out / "profiles_probe.json";
  const CommandRun r = run_shell("scripts/pvbatch.sh cases/view_flexspline.py " + (out / "profiles.vtp").string() + " --png " +
                   png.string() + " --probe " + probe.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  expect_rendered(png);
  std::ifstream pin(probe);
  const auto p = nlohmann::json::parse(pin);
  EXPECT_EQ(p["range"][0].get<double>(), 0.0);  // flexspline basic, compensated, circular spline
  EXPECT_EQ(p["range"][1].get<double>(), 2.0);
  EXPECT_NEAR(p["bounds"][1].get<double>(), 19.7, 0.5);  // mm: the circular spline's root circle
}

TEST(ParaView, ScriptRefusesAnUnknownLoadCaseByName) {
  const fs::path out = coarse_seed_run();
  const CommandRun r = run_shell("scripts/pvbatch.sh cases/view_flexspline.py " + out.string() + " --case nonsense");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("no load case 'nonsense'"), std::string::npos) << r.output;
}

/// Opens a page in headless Chromium, takes a screenshot, returns Chromium's log (console messages included).
CommandRun open_in_chromium(const fs::path& page, const fs::path& png) {
  const fs::path profile = fs::temp_directory_path() / ("sw_chromium_" + std::to_string(::getpid()));
  fs::remove_all(profile);
  const std::string cmd =
      "chromium --headless=new --no-sandbox --disable-gpu --disable-quic --no-first-run "
      "--disable-background-networking --disable-component-update --disable-sync --user-data-dir=" + profile.string() +
      " --enable-logging=stderr --v=0 --window-size=1200,1600 --screenshot=" + png.string() + " file://" +
      fs::absolute(page).string();
  CommandRun r = run_shell(cmd);
  fs::remove_all(profile);
  return r;
}

TEST(Browser, ReconcilePageRendersWithoutConsoleErrors) {
  const fs::path dir = fs::temp_directory_path() / ("sw_browser_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string bin = strainwave_binary();
  ASSERT_EQ(run_shell(bin + " --quiet synth --kind transmission --case cases/seed_190_192.toml --effect wg_harmonic:order=2 "
                     "--concealment 1 --seed 5 --out " + (dir / "rec.csv").string()).exit_code, 0);
  const CommandRun rec = run_shell(bin + " --quiet reconcile cases/seed_190_192.toml " + (dir / "rec.csv").string() + " --out " +
                     (dir / "out").string());
  ASSERT_EQ(rec.exit_code, 0) << rec.output;
  const fs::path png = dir / "reconcile.png";
  const CommandRun r = open_in_chromium(dir / "out" / "reconcile.html", png);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  expect_rendered(png);
  EXPECT_EQ(r.output.find("Uncaught"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find(":ERROR:CONSOLE"), std::string::npos) << r.output;
  fs::remove_all(dir);
}

TEST(Browser, RunReportRendersWithoutConsoleErrorsAndHoldsTheRunsFigures) {
  const fs::path out = coarse_seed_run();
  const fs::path page = out / "report.html";
  ASSERT_TRUE(fs::exists(page));
  std::ifstream in(page);
  const std::string html((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (const char* must : {"<svg", "flexspline.pvd", "Not computed", "geometric angular play", "FEM neutral curve",
                           "nominal hoop bending stress", "local hoop stress peaks"})
    EXPECT_NE(html.find(must), std::string::npos) << must;
  EXPECT_EQ(html.find("http://"), html.find("http://www.w3.org"));  // no network resources, only the SVG namespace
  EXPECT_EQ(html.find("<script"), std::string::npos);
  const fs::path png = out / "report.png";
  const CommandRun r = open_in_chromium(page, png);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  expect_rendered(png);
  EXPECT_EQ(r.output.find(":ERROR:CONSOLE"), std::string::npos) << r.output;
}

}  // namespace
