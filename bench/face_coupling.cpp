// bench_face_coupling: the solid flexspline tooth across the face (contact/tooth_fem.hpp face_coupling) of a case's
// gear, at n face sections and several slab resolutions (points per flank): its centre band against the plane-strain
// tooth of flexspline_tooth_fem at the same resolution (plane strain should hold there on a long face), the shape's
// diagonal against the springs' 1/w_j, its first off-diagonal, the slabs' size and time (the coupling's convergence);
// then, at the finest resolution, the fast model's loaded contact (harmonic solver) with the sections' springs side by
// side and with the flanks of one tooth coupled by the shape (SeriesParts::face_shape): what the coupling changes in
// the drive's twist at T1 / T2 / rated torque.
#include <array>
#include <cstdio>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/contact_job.hpp"
#include "common/progress.hpp"
#include "contact/contact_body.hpp"
#include "contact/harmonic_body.hpp"
#include "contact/loaded_contact.hpp"
#include "contact/tooth_fem.hpp"
#include "contact/torque_twist.hpp"
#include "fem/fourier_analysis.hpp"
#include "gear/tooth_profile.hpp"
#include "io/case.hpp"
#include "mesh/flexspline_sizes.hpp"

int main(int argc, char** argv) {
  CLI::App app{"bench_face_coupling: the solid tooth across the face against the plane-strain tooth"};
  std::string path;
  std::vector<int> sections{3, 8}, points{8, 12};
  app.add_option("case", path, "case file with a [gear]")->required();
  app.add_option("--sections", sections, "face sections");
  app.add_option("--points", points, "points per flank of the slabs");
  CLI11_PARSE(app, argc, argv);
  using namespace sw;
  const Case c = load_case(path);
  if (!c.gear) { std::fprintf(stderr, "%s: no [gear]\n", path.c_str()); return 2; }
  const GearParams& g = *c.gear;
  const double bore = c.flexspline.inner_radius_m, outer = rim_outer_radius(c.flexspline, c.gear);
  const double face = c.flexspline.rim_width_m;
  const GearRadii r = gear_radii(g);
  std::printf("%s: face %.2f mm, tooth height %.3f mm, bore %.3f mm\n", path.c_str(), face * 1e3,
              (r.tip_f - r.root_f) * 1e3, bore * 1e3);
  quiet_progress() = true;
  for (const int n : sections) {
    FaceCoupling finest;
    for (const int p : points) {
      const FaceCoupling f = face_coupling(g, c.material, bore, outer, face, n, p);
      const FlexsplineToothFem plane = flexspline_tooth_fem(g, c.material, bore, outer, 9, p);
      std::printf("  n %d, %d points a flank: centre band %.4e, uniform %.4e, plane strain %.4e m2/N (centre %+.1f %%); "
                  "%zu nodes, %.1f s\n    G/(1/w_j) diagonal:", n, p, f.interior_m2_per_N, f.uniform_m2_per_N,
                  plane(f.radius_m), 100 * (f.interior_m2_per_N / plane(f.radius_m) - 1), f.nodes, f.seconds);
      for (int j = 0; j < n; ++j) std::printf(" %.3f", f.shape(j, j) * face_slice(j, n).width());
      std::printf("; next section G(j, j+1)/G(j, j):");
      for (int j = 0; j + 1 < n; ++j) std::printf(" %.3f", f.shape(j, j + 1) / f.shape(j, j));
      std::printf("\n");
      finest = f;
    }
    Case cn = c;
    cn.contact.face_slices = n;
    const FlexsplineModel m = flexspline_model(cn);
    const FourierSolution fourier = analyse_flexspline_fourier(m, contact_band_request(m, n));
    const HarmonicBody body(m, fourier);
    ContactOptions o = app::contact_options(cn, app::series_parts(cn));
    auto twists = [&](const ContactOptions& opt) {
      const ContactAnalysis a = analyse_contact(m, body, fem_readout(fourier.figures), opt);
      return std::array<double, 3>{twist_at(a.curve, a.catalog.t1_Nm), twist_at(a.curve, a.catalog.t2_Nm),
                                   twist_at(a.curve, a.rated_torque_Nm)};
    };
    const auto springs = twists(o);
    o.series.flexspline_tooth_m_per_N = tooth_pair_compliance_of(m).flexspline_tooth_m_per_N;
    o.series.face_shape = [&](int) { return finest.shape; };
    const auto solid = twists(o);
    constexpr double kArcmin = 10800.0 / 3.141592653589793;
    std::printf("  the drive at n %d (harmonic fast model), twist at T1 / T2 / rated: springs side by side %.3f / %.3f / "
                "%.3f arcmin, one solid tooth %.3f / %.3f / %.3f (%+.1f / %+.1f / %+.1f %%)\n", n,
                springs[0] * kArcmin, springs[1] * kArcmin, springs[2] * kArcmin, solid[0] * kArcmin,
                solid[1] * kArcmin, solid[2] * kArcmin, 100 * (solid[0] / springs[0] - 1),
                100 * (solid[1] / springs[1] - 1), 100 * (solid[2] / springs[2] - 1));
  }
  return 0;
}
