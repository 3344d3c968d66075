// bench_drive_split: the whole drive's twist and its split on the harmonic solver, with the circular spline rigid,
// held on its outside and bolted on a face, for each case (default: the seed cup and the designed sizes 14, 17, 20),
// beside the catalog's law where the case names a size. One harmonic pass per case; the three contacts on it.
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/contact_job.hpp"
#include "common/progress.hpp"
#include "contact/harmonic_body.hpp"
#include "contact/loaded_contact.hpp"
#include "design/catalog.hpp"
#include "fem/fourier_analysis.hpp"
#include "fem/fourier_solver.hpp"
#include "io/case.hpp"
#include "io/contact_output.hpp"

namespace {

constexpr double kArcmin = 10800.0 / 3.141592653589793;

void one_case(const std::string& path) {
  using namespace sw;
  Case c = load_case(path);
  const FlexsplineModel m = flexspline_model(c);
  Stopwatch clock;
  const FourierSolution fourier = analyse_flexspline_fourier(m, contact_band_request(m, c.contact.face_slices));
  const HarmonicBody body(m, fourier);
  const double t_fem = clock.lap();
  const CatalogDrive* catalog = c.catalog_size ? catalog_drive(*c.catalog_size) : nullptr;
  std::printf("%s (harmonic pass %.2f s)%s\n", path.c_str(), t_fem,
              catalog ? (" vs catalog size " + std::to_string(catalog->size)).c_str() : "");
  for (const char* support : {"rigid", "outer", "bolted_face"}) {
    Case v = c;
    if (std::string(support) == "outer") v.circular_spline->mounting = CircularSplineMounting::Outer;
    if (std::string(support) == "bolted_face") v.circular_spline->mounting = CircularSplineMounting::BoltedFace;
    ContactOptions o;
    o.rated_torque_Nm = v.load.rated_torque_Nm.value_or(v.load.torque_Nm);
    o.series = app::series_parts(v);
    if (std::string(support) == "rigid") o.series.circular_spline = {};
    if (catalog) {
      o.catalog_t1_Nm = catalog->t1_Nm;
      o.catalog_t2_Nm = catalog->t2_Nm;
    }
    const ContactAnalysis a = analyse_contact(m, body, fem_readout(fourier.figures), o);
    const double t = clock.lap();
    const double T1 = a.catalog.t1_Nm, T2 = a.catalog.t2_Nm, TR = a.rated_torque_Nm;
    std::printf("  %-11s twist at T1 %.3g / T2 %.3g / rated %.3g N·m: %.3f / %.3f / %.3f arcmin; split body %.1f %%, "
                "teeth %.1f %%, generator %.1f %%, circular spline %.1f %%, engagement %.1f %%; lost motion %.3f, play "
                "%.3f arcmin (%.2f s)\n", support, T1, T2, TR, twist_at(a.curve, T1) * kArcmin,
                twist_at(a.curve, T2) * kArcmin, twist_at(a.curve, TR) * kArcmin, 100 * a.split.body,
                100 * a.split.teeth, 100 * a.split.generator, 100 * a.split.circular_spline,
                100 * a.split.engagement, a.lost_motion_rad * kArcmin, a.play_rad * kArcmin, t);
  }
  if (catalog && catalog->has_stiffness()) {
    const CatalogLaw law{catalog->size, 100, catalog->t1_Nm, catalog->t2_Nm, catalog->k1_Nm_per_rad, catalog->k2_Nm_per_rad,
                         catalog->k3_Nm_per_rad};
    const SegmentLaw s = law.law();
    std::printf("  %-11s twist at T1 / T2 / rated: %.3f / %.3f / %.3f arcmin\n", "catalog",
                s.twist_rad(catalog->t1_Nm) * kArcmin, s.twist_rad(catalog->t2_Nm) * kArcmin,
                s.twist_rad(c.load.rated_torque_Nm.value_or(c.load.torque_Nm)) * kArcmin);
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"bench_drive_split: the drive's twist and split with the circular spline rigid, held outside, bolted"};
  std::vector<std::string> cases = {"cases/seed_190_192.toml", "cases/cup_size14.toml", "cases/cup_size17.toml",
                                    "cases/cup_size20.toml"};
  app.add_option("cases", cases, "case files (TOML)");
  CLI11_PARSE(app, argc, argv);
  try {
    sw::quiet_progress() = true;
    for (const std::string& c : cases) one_case(c);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_drive_split: %s\n", e.what());
    return 1;
  }
  return 0;
}
