// The fem job on the harmonic solver (solver.method = "fourier"): the flexspline's meridian section, harmonics
// 0..N, the same outputs as the tet10 path (result.json with the same figures, its mesh the section and its solver
// the harmonics; neutral_curve.csv; flexspline.pvd with one .vtu per load case on the section revolved into a TET10
// grid).
#include <cstdio>

#include "app/fem_job.hpp"
#include "common/progress.hpp"
#include "contact/harmonic_body.hpp"
#include "contact/loaded_contact.hpp"
#include "fem/fourier_analysis.hpp"
#include "fem/fourier_element.hpp"
#include "fem/fourier_solver.hpp"
#include "io/atomic_file.hpp"
#include "io/fem_output.hpp"

namespace sw::app {

namespace fs = std::filesystem;

namespace {
// Sectors of the VTU grid (5.6°; quadratic in θ, the series exact at its nodes): on the seed cup's generator case it
// draws stress_hoop and the displacement within 0.1 % of their range of the series and every field within 1.2 %, and
// the rim's outline as a smooth curve; 24 sectors show the facets in the view, 48 and 96 only soften their shading, at
// 1.5x and 3x the cost (bench/README.md). The grid is for viewing; every figure is read from the series.
constexpr int kGridSectors = 32;
}  // namespace

FourierSolution solve_fourier_model(const Case& c, double max_memory_gb, double& section_s) {
  Stopwatch clock;
  // A case the loaded contact can take has its bands solved in the same pass (a few more columns per harmonic).
  const FlexsplineModel model = flexspline_model(c);
  const BandRequest bands = contact_model_gap(model) ? BandRequest{} : contact_band_request(model, c.contact.face_slices);
  SectionMesh section = case_section(model);
  section_s = clock.lap();
  // Seconds, not minutes: refused from the section before anything is assembled.
  refuse_if_too_large(fourier_model_size(model, section), max_memory_gb * 1e9, c.path);
  return analyse_section_fourier(model, std::move(section), bands);
}

FemJobResult run_fourier_fem_job(const Case& c, OutputSet& out, bool write_vtk, double max_memory_gb) {
  const double t_start = elapsed_s();
  RunInfo run;
  run.blas = detect_blas();
  auto fourier = std::make_shared<FourierSolution>(solve_fourier_model(c, max_memory_gb, run.mesh_s));
  Stopwatch clock;
  const FlexsplineSolution& s = fourier->figures;
  progress("output: " + out.dir().string());
  if (write_vtk) {
    // The views are a reader's, not the stages': the load cases are evaluated on the grid and written on a thread of
    // their own while the command goes on (Eigen only, no BLAS: the figures are the same with or without it).
    fourier->grid = fourier::revolve_section(fourier->section, kGridSectors);
    out.write_beside([fourier = std::shared_ptr<const FourierSolution>(fourier), material = c.material,
                      staging = out.staging()] {
      write_fem_vtk(staging, fourier->grid, revolved_load_cases(*fourier, material, kGridSectors));
    });
  }
  if (s.neutral_curve) write_file_atomic(out.staging() / "neutral_curve.csv", neutral_curve_csv(*s.neutral_curve));
  run.output_s = clock.lap();
  run.total_s = elapsed_s() - t_start;
  run.peak_rss_bytes = peak_rss_bytes();

  FemJobResult job;
  const FemResult result = fem_result(c, *fourier, run);
  job.result_json_path = out.dir() / "result.json";
  write_file_atomic(out.staging() / "result.json", fem_result_json(result));

  std::printf("fem %s (fourier): section %zu nodes, harmonics 0..%d (%zu solved, %lld equations in all), factor "
              "%.3f GF, total %.2f s, peak %.0f MB\n",
              c.path.c_str(), fourier->section.n_nodes(), fourier->harmonics_kept, fourier->harmonics.size(),
              static_cast<long long>(result.solver.equations), s.timings.factor.factor_gflop, run.total_s, run.peak_rss_bytes / 1e6);
  std::printf("  phi0 = %.6e rad at T = %g N·m (C_tau = %.6e rad/N·m); theory T·L/(G·J) = %.6e rad (FEM/theory %.4f)\n",
              s.phi0_rad, s.torque_Nm, s.compliance_rad_per_Nm, s.checks.phi0_theory_rad,
              s.checks.phi0_theory_rad != 0 ? s.phi0_rad / s.checks.phi0_theory_rad : 0.0);
  std::printf("  reaction torque %.9g N·m vs applied %.9g N·m\n", s.checks.reaction_torque_Nm,
              s.checks.applied_torque_Nm);
  if (const auto& layer = fourier->section.tooth_layer)
    std::printf("  teeth as ribs along the face on the rim: stiff along it at their solidity, no hoop load; their shear "
                "along the face %.3f of the rule of mixtures (one pitch's cell)\n",
                layer->shear_factor);
  if (c.wave_generator)
    std::printf("  generator: %.4g N per force, w0 = %.4f mm, net rim rotation %.2e rad; hoop stress %+.1f MPa at "
                "%.1f deg, %+.1f MPa at %.1f deg\n",
                s.generator_force_N, s.generator_w0_m * 1e3, s.checks.generator_rotation_rad,
                s.hoop.max_tensile_Pa / 1e6, s.hoop.max_tensile_angle_deg, s.hoop.max_compressive_Pa / 1e6,
                s.hoop.max_compressive_angle_deg);
  job.solution = s;
  job.harmonic = std::move(fourier);
  return job;
}

}  // namespace sw::app
