// bench_fourier_vs_tet10: one flexspline (a body of revolution: teeth "ring" or "none"; the TET10 peer has no tooth layer) through the harmonic solver,
// the tet10 solver and CalculiX in one run, each converged on its own:
//   1. DGEMM rate of the loaded BLAS (the reference for the tet10 factor's efficiency).
//   2. fourier, harmonic convergence on the case's section: N = 8 … 128 (φ₀, w, v on the neutral circle, hoop stress),
//      differences against the largest N.
//   3. fourier, section convergence at the largest N: the case's mesh keys refined by 1, 2, 4 (size / k, layers × k;
//      the section is graded toward the cup's singular boss corner), Richardson extrapolation with the observed order,
//      every row against the extrapolated values.
//   4. tet10 at the case's mesh and --tet10-meshes SIZE/LAYERS,... (coarsest first for the extrapolation): time,
//      factor GF and GF/s against DGEMM, φ₀; with three meshes, Richardson with the observed order. Each tet10 run
//      against the extrapolated fourier values: φ₀, max |Δw| and |Δv| over the neutral circle ÷ w0, the nominal hoop
//      stress (outer wall at the minor axis, generator plane), and the speed ratio tet10 ÷ fourier end to end (mesh +
//      every load case + figures, no output files: both sides alike).
//   5. CalculiX (--ccx; its deck holds the clamp and the torque, no generator) on the case's tet10 mesh: time and φ₀
//      of the torque alone, beside tet10's torque alone on the same factor and fourier's torque alone.
// Wall clock; on a shared machine the ratio is noisy (say so with the figures).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "bench_util.hpp"
#include "ccx.hpp"
#include "common/error.hpp"
#include "common/progress.hpp"
#include "dgemm.hpp"
#include "fem/flexspline_analysis.hpp"
#include "fem/fourier_analysis.hpp"
#include "fem/fourier_solver.hpp"
#include "io/case.hpp"
#include "io/inp.hpp"
#include "mesh/flexspline.hpp"

namespace sw::bench {
namespace {

struct Figures {
  std::string label;
  double seconds = 0, phi0 = 0, hoop90_outer = 0, hoop_max = 0, gflop = 0, factor_s = 0;
  long long size = 0;  // nodes (tet10) or section nodes (fourier)
  long long equations = 0;
  std::vector<double> w, v;
  double w0 = 0;
};

Figures from(const FlexsplineSolution& s) {
  Figures f;
  f.phi0 = s.phi0_rad;
  f.hoop90_outer = s.hoop.outer_Pa.empty() ? 0 : s.hoop.outer_Pa[90];
  f.hoop_max = s.hoop.max_tensile_Pa;
  f.gflop = s.timings.factor.factor_gflop;
  f.factor_s = s.timings.factor.factor_s;
  if (s.neutral_curve) {
    f.w = s.neutral_curve->w_wg_m;
    f.v = s.neutral_curve->v_wg_m;
  }
  f.w0 = s.generator_w0_m;
  return f;
}

Figures run_fourier(Case c, int harmonics, double size_m, int layers) {
  c.solver.method = SolverMethod::Fourier;
  c.solver.harmonics = harmonics;
  // The corner grading refines with the section: a level more per doubling of the layers keeps the corner cell ∝ h².
  c.mesh.corner_levels = corner_levels(c.flexspline, c.mesh) +
                         static_cast<int>(std::lround(std::log2(static_cast<double>(layers) / c.mesh.wall_layers)));
  c.mesh.size_m = size_m;
  c.mesh.wall_layers = layers;
  Stopwatch clock;
  const FourierSolution s = analyse_flexspline_fourier(flexspline_model(c));
  const double t = clock.lap();
  Figures f = from(s.figures);
  f.seconds = t;
  f.size = static_cast<long long>(s.section.n_nodes());
  for (const auto& h : s.harmonics) f.equations += h.equations;
  char label[64];
  std::snprintf(label, sizeof label, "N=%d, %.3g mm/%d", harmonics, size_m * 1e3, layers);
  f.label = label;
  return f;
}

/// CalculiX on the tet10 mesh (torque alone) beside tet10's torque alone on the same factor.
struct TorqueAlone {
  double tet10_phi0 = 0, ccx_phi0 = 0, ccx_s = 0;
  long long ccx_equations = -1;
  std::string ccx_summary;
};

/// A tet10 mesh of the series: size, wall layers, corner levels (-1: the default).
struct Tet10Mesh {
  double size_m = 0;
  int layers = 0, corner_levels = -1;
};

/// The case's mesh keys with this mesh's size, layers and corner levels.
MeshParams mesh_params(MeshParams p, const Tet10Mesh& m) {
  p.size_m = m.size_m;
  p.wall_layers = m.layers;
  p.corner_levels = m.corner_levels;
  return p;
}

Figures run_tet10(Case c, const Tet10Mesh& m, TorqueAlone* alone, int ccx_threads) {
  c.solver.method = SolverMethod::Tet10;
  c.mesh = mesh_params(c.mesh, m);
  Stopwatch clock;
  const TetMesh mesh = mesh_for_bench(c);
  Figures f;
  {
    const FlexsplineModel model = flexspline_model(c);
    const FlexsplineSystem system = assemble_and_factorise(model, mesh);
    const FlexsplineSolution s = analyse_flexspline(model, mesh, system);
    const double t = clock.lap();
    f = from(s);
    f.seconds = t;
    f.size = static_cast<long long>(mesh.n_nodes());
    f.equations = s.timings.factor.equations;
    if (alone) {
      Case ct = c;
      ct.wave_generator.reset();
      alone->tet10_phi0 = analyse_flexspline(flexspline_model(ct), mesh, system).phi0_rad;
    }
  }  // the factor is freed before ccx runs
  if (alone) {
    Case ct = c;
    ct.wave_generator.reset();
    const std::string ccx = ensure_ccx();
    TempDir tmp("sw_fourier_ccx_");
    const FlexsplineModel model = flexspline_model(ct);
    write_inp_deck(tmp.path() / "job.inp", ct, mesh, clamped_nodes(mesh), torque_load_vector(model, mesh, ct.load.torque_Nm),
                   "bench_fourier_vs_tet10");
    progress("ccx on " + std::to_string(mesh.n_nodes()) + " nodes");
    alone->ccx_s = run_ccx(ccx, tmp.path(), ccx_threads);
    alone->ccx_phi0 = reading_rotation(model, mesh, read_frd_displacements(tmp.path() / "job.frd", mesh.n_nodes()));
    const CcxLog log = read_ccx_log(tmp.path() / "ccx.log");
    alone->ccx_equations = log.equations;
    alone->ccx_summary = log.summary;
  }
  char label[64];
  std::snprintf(label, sizeof label, "tet10 %.3g mm/%d/%d", m.size_m * 1e3, m.layers,
                corner_levels(c.flexspline, c.mesh));
  f.label = label;
  return f;
}

/// Richardson extrapolation of three values on meshes refined by a constant ratio r (coarsest first): the observed
/// order p = ln((f1 − f2)/(f2 − f3))/ln r and f3 + (f3 − f2)/(r^p − 1). Not monotone: no extrapolation (p = NaN,
/// the finest value stands).
struct Extrapolated {
  double value = 0, order = std::nan("");
};
Extrapolated richardson(double f1, double f2, double f3, double r) {
  Extrapolated e;
  e.value = f3;
  const double q = (f1 - f2) / (f2 - f3);
  if (!(q > 1.0)) return e;
  e.order = std::log(q) / std::log(r);
  e.value = f3 + (f3 - f2) / (q - 1);
  return e;
}

/// The extrapolated figures of three runs: φ₀, nominal hoop stress, and the neutral curve point by point with the
/// order observed on its largest differences.
Figures extrapolate(const std::vector<Figures>& f, double r, std::string label) {
  Figures e = f[2];
  e.label = std::move(label);
  const Extrapolated phi = richardson(f[0].phi0, f[1].phi0, f[2].phi0, r);
  const Extrapolated hoop = richardson(f[0].hoop90_outer, f[1].hoop90_outer, f[2].hoop90_outer, r);
  e.phi0 = phi.value;
  e.hoop90_outer = hoop.value;
  double d12 = 0, d23 = 0;
  for (std::size_t k = 0; k < e.w.size(); ++k) {
    d12 = std::max({d12, std::abs(f[0].w[k] - f[1].w[k]), std::abs(f[0].v[k] - f[1].v[k])});
    d23 = std::max({d23, std::abs(f[1].w[k] - f[2].w[k]), std::abs(f[1].v[k] - f[2].v[k])});
  }
  const double q = d23 > 0 ? d12 / d23 : 0;
  if (q > 1)
    for (std::size_t k = 0; k < e.w.size(); ++k) {
      e.w[k] += (f[2].w[k] - f[1].w[k]) / (q - 1);
      e.v[k] += (f[2].v[k] - f[1].v[k]) / (q - 1);
    }
  std::printf("  Richardson (ratio %.3g): phi0 order %.2f -> %.6e rad; hoop90 order %.2f -> %.2f MPa; neutral curve "
              "order %.2f (largest |dw|,|dv|: %.2e, %.2e of w0)\n",
              r, phi.order, phi.value, hoop.order, hoop.value / 1e6, q > 1 ? std::log(q) / std::log(r) : std::nan(""),
              d12 / e.w0, d23 / e.w0);
  return e;
}

struct Diff {
  double phi0 = 0, w = 0, v = 0, hoop = 0;
};
Diff diff(const Figures& a, const Figures& ref) {
  Diff d;
  d.phi0 = a.phi0 / ref.phi0 - 1;
  const double w0 = ref.w0 > 0 ? ref.w0 : 1;
  for (std::size_t k = 0; k < std::min(a.w.size(), ref.w.size()); ++k) {
    d.w = std::max(d.w, std::abs(a.w[k] - ref.w[k]) / w0);
    d.v = std::max(d.v, std::abs(a.v[k] - ref.v[k]) / w0);
  }
  d.hoop = ref.hoop90_outer != 0 ? a.hoop90_outer / ref.hoop90_outer - 1 : 0;
  return d;
}

void print_row(const Figures& f, const Figures& ref) {
  const Diff d = diff(f, ref);
  std::printf("| %-22s | %9lld | %9lld | %8.3f | %.6e | %+9.2e | %8.2e | %8.2e | %8.1f | %+9.2e | %8.1f |\n",
              f.label.c_str(), f.size, f.equations, f.seconds, f.phi0, d.phi0, d.w, d.v, f.hoop90_outer / 1e6, d.hoop,
              f.hoop_max / 1e6);
}

void print_header(const char* title, const char* size_name) {
  std::printf("\n%s\n", title);
  std::printf("| %-22s | %9s | %9s | %8s | %-12s | %9s | %8s | %8s | %8s | %9s | %8s |\n", "run", size_name, "equations",
              "time s", "phi0 rad", "dphi0 rel", "|dw|/w0", "|dv|/w0", "hoop90 MPa", "dhoop rel", "hoop max");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|\n");
}

int run(int argc, char** argv) {
  CLI::App app{"bench_fourier_vs_tet10: the harmonic solver against tet10 and CalculiX on one case, each converged on "
               "its own"};
  std::string case_path = "cases/seed_190_192.toml", tet10_meshes, harmonics_list = "16,32,64,96,128";
  int dgemm_n = 2000, ccx_threads = 2;
  bool skip_tet10 = false, with_ccx = false;
  app.add_option("case", case_path, "case file (teeth ring or none)")->capture_default_str();
  app.add_option("--harmonics", harmonics_list, "harmonic orders N to run (comma-separated); the last is the reference")
      ->capture_default_str();
  app.add_option("--tet10-meshes", tet10_meshes,
                 "tet10 meshes SIZE_MM/LAYERS[/CORNER_LEVELS],... coarsest first (default: the case's mesh; three: "
                 "extrapolated, by the ratio of their corner sizes)");
  app.add_flag("--skip-tet10", skip_tet10, "fourier tables only");
  app.add_flag("--ccx", with_ccx, "also CalculiX on the finest tet10 mesh (torque alone)");
  app.add_option("--ccx-threads", ccx_threads, "OMP_NUM_THREADS for ccx")->capture_default_str();
  app.add_option("--dgemm-n", dgemm_n, "order of the DGEMM reference matrices")->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  std::vector<Tet10Mesh> requested_meshes;
  for (const MeshSpec& m : parse_mesh_specs(tet10_meshes, "--tet10-meshes", true))
    requested_meshes.push_back({m.size_mm * 1e-3, m.layers, m.corner_levels});
  const Case c = load_case(case_path);
  std::vector<int> orders;
  {
    std::stringstream ss(harmonics_list);
    std::string item;
    while (std::getline(ss, item, ',')) orders.push_back(std::stoi(item));
  }
  const int n_ref = orders.back();
  std::printf("bench_fourier_vs_tet10 %s (BLAS: %s)\n", case_path.c_str(), detect_blas().description.c_str());
  const double dgemm = dgemm_gflops(dgemm_n, 3);
  std::printf("DGEMM %dx%d: %.1f GF/s (best of 3, same BLAS and threads, measured in this run)\n", dgemm_n, dgemm_n, dgemm);

  // Section convergence at the reference N, extrapolated: the reference of every table.
  std::vector<Figures> sections;
  for (const int k : {1, 2, 4})
    sections.push_back(run_fourier(c, n_ref, c.mesh.size_m / k, c.mesh.wall_layers * k));
  std::vector<Figures> harmonics;
  for (const int n : orders) harmonics.push_back(run_fourier(c, n, c.mesh.size_m, c.mesh.wall_layers));

  print_header("fourier: harmonic convergence on the case's section (differences against the largest N)", "sec nodes");
  for (const auto& f : harmonics) print_row(f, harmonics.back());
  print_header("fourier: section convergence at the largest N (size / k, layers x k), against the extrapolation",
               "sec nodes");
  const Figures ref = extrapolate(sections, 2.0, "fourier extrapolated");
  for (const auto& f : sections) print_row(f, ref);
  std::printf("| %-22s |           |           |          | %.6e |           |          |          | %8.1f |           |"
              "          |\n",
              ref.label.c_str(), ref.phi0, ref.hoop90_outer / 1e6);

  if (!skip_tet10) {
    std::vector<Tet10Mesh> meshes = requested_meshes;
    if (meshes.empty()) meshes.push_back({c.mesh.size_m, c.mesh.wall_layers, c.mesh.corner_levels});
    // The fourier run the speed is quoted for: N = 64 on the case's section when it was run, else the largest N.
    const auto it64 = std::find(orders.begin(), orders.end(), 64);
    const Figures& fast = harmonics[it64 != orders.end() ? it64 - orders.begin() : harmonics.size() - 1];
    std::vector<Figures> tet10;
    TorqueAlone alone;
    for (std::size_t i = 0; i < meshes.size(); ++i) {
      const bool last = i + 1 == meshes.size();
      tet10.push_back(run_tet10(c, meshes[i], with_ccx && last ? &alone : nullptr, ccx_threads));
    }
    print_header("tet10 against the extrapolated fourier values", "nodes");
    for (const auto& t : tet10) {
      print_row(t, ref);
      std::printf("  tet10 factor %.1f GF in %.2f s = %.1f GF/s = %.0f %% of DGEMM; end to end %.2f s vs fourier (%s) "
                  "%.3f s: %.0fx\n",
                  t.gflop, t.factor_s, t.gflop / t.factor_s, 100 * t.gflop / t.factor_s / dgemm, t.seconds,
                  fast.label.c_str(), fast.seconds, t.seconds / fast.seconds);
    }
    if (tet10.size() == 3) {
      // The refinement ratio: of the sizes, or of the corner sizes when only the corner levels change (the
      // singular corners then dominate the error).
      auto levels = [&](const Tet10Mesh& m) { return corner_levels(c.flexspline, mesh_params(c.mesh, m)); };
      const double r = meshes[1].size_m != meshes[2].size_m ? meshes[1].size_m / meshes[2].size_m
                                                          : std::ldexp(1.0, levels(meshes[2]) - levels(meshes[1]));
      const Figures t = extrapolate(tet10, r, "tet10 extrapolated");
      if (std::isnan(richardson(tet10[0].phi0, tet10[1].phi0, tet10[2].phi0, r).order))
        std::printf("  tet10 phi0 not monotone over these meshes: no extrapolation\n");
      else
        print_row(t, ref);
    }
    if (with_ccx) {
      Case ct = c;
      ct.wave_generator.reset();
      const Figures fa = run_fourier(ct, n_ref, c.mesh.size_m / 4, c.mesh.wall_layers * 4);
      std::printf("\nTorque alone (no generator; the CalculiX deck holds the clamp and the torque) on tet10 %s:\n",
                  tet10.back().label.c_str());
      std::printf("| solver | time s | phi0 rad | vs fourier |\n|---|---|---|---|\n");
      std::printf("| CalculiX (%lld equations) | %.2f | %.6e | %+.2e |\n", alone.ccx_equations, alone.ccx_s,
                  alone.ccx_phi0, alone.ccx_phi0 / fa.phi0 - 1);
      std::printf("| tet10, same mesh | (above) | %.6e | %+.2e |\n", alone.tet10_phi0, alone.tet10_phi0 / fa.phi0 - 1);
      std::printf("| fourier %s | %.2f | %.6e | 0 |\n", fa.label.c_str(), fa.seconds, fa.phi0);
      std::printf("ccx vs tet10 on the same mesh: %+.2e (the .frd holds 6 digits)\n%s", alone.ccx_phi0 / alone.tet10_phi0 - 1,
                  alone.ccx_summary.c_str());
    }
  }
  return 0;
}

}  // namespace
}  // namespace sw::bench

int main(int argc, char** argv) {
  try {
    return sw::bench::run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_fourier_vs_tet10: %s\n", e.what());
    return 2;
  }
}
