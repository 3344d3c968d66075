// bench_teeth_reference: the 3-D reference of the flexspline's teeth against the fast model on one drive. For each
// TET10 mesh: the loaded contact on the bare rim with the tooth in series (the fast model's teeth, TET10 body) and on
// explicit teeth (flexspline.teeth = "explicit": the teeth solids on the cup, each flank's force on its own flank);
// beside them the harmonic solver's fast model at the case's own settings, on the bare rim and with the teeth as a
// layer of ribs along the face (teeth = "none" and "layer", the tooth in series on both). Twist at T1, T2 and rated torque (from the
// dead band's edge too, as the two rims at rest keep different play), the split, the wall times; the machine's DGEMM
// rate in the same run.
#include <cstdio>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/contact_job.hpp"
#include "bench_util.hpp"
#include "common/progress.hpp"
#include "contact/harmonic_body.hpp"
#include "contact/loaded_contact.hpp"
#include "contact/tet10_body.hpp"
#include "contact/torque_twist.hpp"
#include "design/proportions.hpp"
#include "dgemm.hpp"
#include "fem/flexspline_analysis.hpp"
#include "fem/flexspline_system.hpp"
#include "fem/fourier_analysis.hpp"
#include "fem/fourier_solver.hpp"
#include "io/case.hpp"

namespace {

constexpr double kArcmin = 10800.0 / 3.141592653589793;

sw::ContactOptions options(const sw::Case& c) { return sw::app::contact_options(c, sw::app::series_parts(c)); }

void print(const char* what, const sw::ContactAnalysis& a, double seconds) {
  const double T1 = a.catalog.t1_Nm, T2 = a.catalog.t2_Nm, TR = a.rated_torque_Nm;
  const double edge = sw::twist_limits(a.curve, 0.0).second;
  const auto at = [&](double T) { return sw::twist_at(a.curve, T) * kArcmin; };
  const auto from_edge = [&](double T) { return (sw::twist_at(a.curve, T) - edge) * kArcmin; };
  std::printf("  %-26s twist at T1/T2/rated %.3f / %.3f / %.3f arcmin, from the dead band's edge %.3f / %.3f / %.3f; "
              "play %.3f; split body %.1f %%, teeth %.1f %%, generator %.1f %%, circular spline %.1f %%, engagement "
              "%.1f %%; %.1f s\n", what, at(T1), at(T2), at(TR), from_edge(T1), from_edge(T2), from_edge(TR),
              a.play_rad * kArcmin, 100 * a.split.body, 100 * a.split.teeth, 100 * a.split.generator,
              100 * a.split.circular_spline, 100 * a.split.engagement, seconds);
}

void on_tet10(sw::Case c, sw::TeethModel teeth, const sw::bench::MeshSpec& spec) {
  using namespace sw;
  c.flexspline.teeth = teeth;
  c.solver.method = SolverMethod::Tet10;
  c.mesh.size_m = spec.size_mm * 1e-3;
  c.mesh.wall_layers = spec.layers;
  if (spec.corner_levels >= 0) c.mesh.corner_levels = spec.corner_levels;
  const FlexsplineModel m = flexspline_model(c);
  Stopwatch clock;
  const TetMesh mesh = bench::mesh_for_bench(c);
  const FlexsplineSystem system = assemble_and_factorise(m, mesh);
  const FlexsplineSolution fem = analyse_flexspline(m, mesh, system);
  const FemReadout readout = fem_readout(fem);
  const ContactAnalysis a = analyse_contact(m, mesh, system, readout, options(c));
  const std::string what = std::string(teeth == TeethModel::Explicit ? "explicit teeth" : "bare rim + tooth slabs") +
                           ", " + std::to_string(mesh.n_nodes() / 1000) + "k nodes";
  print(what.c_str(), a, clock.lap());
  if (teeth != TeethModel::Explicit) return;
  // The design's zero-backlash cut is set on the harmonic solver's bare rim; the toothed rim deforms to another shape
  // and keeps play there. The same cut on this rim's own sections (design/proportions.hpp zero_backlash) separates
  // the deformed shape from the rest of what the two bodies differ in.
  const Tet10Body body(m, mesh, system, readout.generator_u);
  const int n = c.contact.face_slices;
  std::vector<double> z;
  for (int j = 0; j < n; ++j) z.push_back(face_section_z_m(readout.neutral_curve.z_m, c.flexspline.rim_width_m, j, n));
  std::vector<NeutralCurve> sections;
  for (const NeutralCurveSamples& s : body.generator_curves_at(z)) sections.push_back(fem_neutral_curve(s));
  const ZeroBacklash cut = zero_backlash(*m.gear, sections, "the explicit teeth's rim");
  Case own = c;  // the circular spline's shift alone changes: the flexspline's mesh and factor stand
  own.gear->profile_shift_circular = own.gear->profile_shift_flexspline + cut.shift_difference;
  std::printf("  zero backlash on the explicit rim's own %d sections: x_c - x_f = %.8f (the design's %.8f)\n", n,
              cut.shift_difference, m.gear->profile_shift_circular - m.gear->profile_shift_flexspline);
  const FlexsplineModel mo = flexspline_model(own);
  print("explicit teeth, own cut", analyse_contact(mo, Tet10Body(mo, mesh, system, readout.generator_u), readout,
                                                   options(own)), clock.lap());
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"bench_teeth_reference: the loaded contact on explicit teeth (TET10) against the fast model"};
  std::string path, meshes = "1.0/1";
  app.add_option("case", path, "case file (a designed drive: teeth = \"layer\" or \"none\")")->required();
  app.add_option("--mesh", meshes, "TET10 meshes, comma-separated SIZE_MM/LAYERS[/CORNER_LEVELS] (default 1.0/1)");
  CLI11_PARSE(app, argc, argv);
  try {
    using namespace sw;
    const std::vector<bench::MeshSpec> specs = bench::parse_mesh_specs(meshes, "--mesh", true);
    quiet_progress() = true;
    const Case c = load_case(path);
    if (!c.gear || (c.flexspline.teeth != TeethModel::None && c.flexspline.teeth != TeethModel::Layer))
      throw InputError(path + ": flexspline.teeth = \"layer\" or \"none\" with a [gear] expected (a case from "
                              "strainwave design)");
    std::printf("DGEMM (n = 2000): %.1f GF/s\n", bench::dgemm_gflops(2000, 3));
    std::printf("%s: z_f = %d, m = %.4g mm\n", path.c_str(), c.gear->teeth_flexspline, c.gear->module_m * 1e3);
    for (const TeethModel teeth : {TeethModel::None, TeethModel::Layer}) {
      Stopwatch clock;
      Case h = c;
      h.flexspline.teeth = teeth;
      const FlexsplineModel m = flexspline_model(h);
      const FourierSolution fourier = analyse_flexspline_fourier(m, contact_band_request(m, h.contact.face_slices));
      const ContactAnalysis a = analyse_contact(m, HarmonicBody(m, fourier), fem_readout(fourier.figures), options(h));
      print(teeth == TeethModel::None ? "harmonic, bare rim" : "harmonic, tooth layer", a, clock.lap());
    }
    for (const bench::MeshSpec& s : specs) {
      std::printf(" TET10 at mesh.size_mm %.3g, wall_layers %d:\n", s.size_mm, s.layers);
      on_tet10(c, TeethModel::None, s);
      on_tet10(c, TeethModel::Explicit, s);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_teeth_reference: %s\n", e.what());
    return 1;
  }
}
