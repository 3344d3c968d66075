// `strainwave run CASE.toml [--curve fem|generator]`: the main job. fem (φ₀, C_τ, neutral curve) then backlash fed
// with that φ₀ and, by default, the FEM's own generator-deformed neutral curve; both sets of files under one folder.
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <optional>

#include <CLI/CLI.hpp>

#include "app/backlash_job.hpp"
#include "app/commands.hpp"
#include "app/contact_job.hpp"
#include "app/fem_job.hpp"
#include "common/constants.hpp"
#include "common/progress.hpp"
#include "io/atomic_file.hpp"
#include "io/case.hpp"
#include "io/run_report.hpp"
#include "kinematics/neutral_curve.hpp"

namespace sw::app {

namespace {

RunReportInputs report_inputs(const Case& c, const OutputSet& out) {
  RunReportInputs in;
  in.out_dir = out.staging();
  in.shown_dir = out.dir();
  in.case_path = c.path;
  in.case_text = describe_case(c);
  if (c.wave_generator && c.wave_generator->radial_deformation_m) {
    const NeutralCurve theory =
        generator_neutral_curve(rim_mean_radius(c.flexspline), *c.wave_generator->radial_deformation_m, *c.wave_generator);
    in.theory_label = "generator model: " + theory.source;
    for (int i = -180; i <= 180; ++i) {
      in.theory_phi_rad.push_back(i * std::numbers::pi / 180.0);
      in.theory_w_m.push_back(theory.w.value(in.theory_phi_rad.back()));
    }
  }
  return in;
}

/// The designer's summary: every figure with what it is, and what is not computed.
void print_summary(const Case& c, const FemJobResult& fem, const std::optional<BacklashReport>& b,
                   const std::optional<ContactAnalysis>& contact, const std::filesystem::path& dir) {
  const FlexsplineSolution& s = fem.solution;
  std::printf("\nsummary of %s\n", c.path.c_str());
  std::printf("  flexspline body: wind-up phi0 %.4e rad (%.3f arcmin) at %.4g N·m; torsional stiffness of the body "
              "alone %.4g N·m/rad\n", s.phi0_rad, s.phi0_rad * kArcmin, s.torque_Nm,
              s.compliance_rad_per_Nm > 0 ? 1.0 / s.compliance_rad_per_Nm : 0.0);
  if (contact) {
    const ContactAnalysis& a = *contact;
    std::printf("  whole drive (generator locked): twist %.3f arcmin at rated torque %.4g N·m, K1 %.4g and K3 %.4g "
                "N·m/rad, lost motion %.3f arcmin (±4 %% of rated, elastic twist included)%s\n",
                a.curve.twist_rad.back() * kArcmin, a.rated_torque_Nm, a.catalog.k1_Nm_per_rad,
                a.catalog.k3_Nm_per_rad, a.lost_motion_rad * kArcmin,
                a.overlap_at_rest_m > 0 ? "; the teeth overlap at rest: part of it is a preload from interference" : "");
  } else {
    const std::optional<std::string> gap = contact_model_gap(flexspline_model(c));
    std::printf("  whole drive's twist: not computed (%s)\n",
                gap ? gap->c_str() : "the loaded tooth contact needs the factor in this process: backend = \"cholmod\"");
  }
  if (b) {
    const auto& rb = b->revolution_basic;
    std::printf("  geometric angular play of the output%s: %.3f .. %.3f arcmin over a revolution (rigid teeth; not the "
                "catalog's lost motion); interference at rest: %s\n", at_face_centre(c).c_str(),
                rb.angular_play_min_rad * kArcmin, rb.angular_play_max_rad * kArcmin,
                b->geometry.interference ? "YES" : "none");
    const bool point_loads = !cam_of(*c.wave_generator);
    if (b->geometry.interference && point_loads && b->curve_source.find("FEM") != std::string::npos)
      std::printf("  note: the neutral curve is the FEM's under a generator that loads the rim at points (forces or "
                  "rollers); on a short cup they dent it locally and the rim is far from elliptic. `--curve generator` "
                  "gives the thin-ring curve; model = \"cam\" a generator in contact over a zone\n");
  }
  if (s.generator)
    std::printf("  nominal hoop bending stress %+.0f MPa (thin-ring theory %+.0f MPa); local peaks where the generator "
                "touches %+.0f / %+.0f MPa\n", s.hoop.nominal_bending_Pa / 1e6, s.hoop.ring_theory_bending_Pa / 1e6,
                s.hoop.max_tensile_Pa / 1e6, s.hoop.max_compressive_Pa / 1e6);
  std::printf("  not computed here: the limits (buckling, ratcheting, strength) and the generator bearing's life, which "
              "`strainwave datasheet` computes\n");
  std::printf("  report: %s\n", (dir / "report.html").string().c_str());
}

}  // namespace

void add_run_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("run", "fem, backlash fed with its phi0, then the loaded tooth contact: the main job");
  static std::string case_path, out, solver, backend, curve = "fem";
  static FemJobOptions fem_options;
  cmd->add_option("case", case_path, "case file (TOML)")->required();
  add_fem_job_options(cmd, fem_options);
  cmd->add_option("--curve", curve,
                  "neutral curve for the backlash: fem (the FEM's generator-deformed rim, default) or generator "
                  "(the generator model's thin-ring/cam curve)")
      ->check(CLI::IsMember({"generator", "fem"}));
  cmd->add_option("--out", out, "output directory (default out/<case stem>/)");
  add_solver_options(cmd, solver, backend);
  cmd->callback([] {
    const Case c = load_case_with_solver(case_path, solver, backend);
    OutputSet outputs(out.empty() ? default_out_dir(c) : std::filesystem::path(out), {"report.html"});
    write_resolved_case(c, outputs);
    outputs.own(kBacklashJobFiles);  // also when this case has no backlash or contact stage: none stays from before
    outputs.own(kContactJobFiles);
    const bool contact_stage = !contact_model_gap(flexspline_model(c));
    // The series parts (tooth slabs, the circular spline's ring) are built after the FEM, not beside it: BLAS called
    // from two threads at once gave figures that differ from run to run at 1e-8.
    const FemJobResult fem = run_fem_job(c, outputs, fem_options);
    std::optional<BacklashReport> backlash;
    if (c.gear && c.wave_generator && c.wave_generator->radial_deformation_m) {
      BacklashJobOptions options;
      options.fem_result = fem.result_json_path;
      options.fem_curve = curve == "fem";
      backlash = run_backlash_job(c, options, outputs);
    } else {
      std::printf("run: no backlash for this case (it needs [gear] and [wave_generator] with radial_deformation_mm)\n");
    }
    std::optional<ContactAnalysis> contact;
    if (contact_stage) {
      const FemReadout readout = fem_readout(fem.solution);
      contact = run_contact_job(c, *contact_body(c, fem, readout.generator_u), readout, outputs);
    }
    write_file_atomic(outputs.staging() / "report.html", run_report_html(report_inputs(c, outputs)));
    outputs.commit();
    std::printf("  wrote %s\n", outputs.dir().string().c_str());
    print_summary(c, fem, backlash, contact, outputs.dir());
  });
}

}  // namespace sw::app
