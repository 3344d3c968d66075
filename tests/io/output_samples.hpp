#pragma once
// Typed values of result.json, backlash.json and contact.json with every optional part present and every figure
// distinct (a figure read into the wrong member, or dropped, changes what is written back).
#include <filesystem>
#include <string>
#include <unistd.h>

#include "io/backlash_output.hpp"
#include "io/contact_output.hpp"
#include "io/fem_output.hpp"

namespace sw::testing {

/// Distinct figures, none a round binary number: 0.1 + k·√½.
struct Figures {
  int k = 0;
  double operator()() { return 0.1 + ++k * 0.7071067811865476; }
  int whole() { return ++k; }
};

/// An output's stored case (as the reader takes it back: a JSON object's text, keys sorted) and the tool's version.
inline Provenance sample_provenance() {
  return {R"({"flexspline":{"shape":"tube","teeth":"none"},"load":{"torque_Nm":10.5}})", "v1.2-3-gabcdef0"};
}

/// A fresh folder under the temporary directory.
inline std::filesystem::path scratch_dir(const std::string& name) {
  const auto d = std::filesystem::temp_directory_path() / ("sw_io_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

inline FemResult::FatiguePoint sample_fatigue_point(Figures& f, const std::string& place, bool safety_factor) {
  FemResult::FatiguePoint p{place, f(), f(), f(), f(), f(), f(), std::nullopt};
  if (safety_factor) p.goodman_safety_factor = f();
  return p;
}

/// A TET10 result on the petsc backend, with a cam generator, its bearing and stations, and fatigue at both places.
inline FemResult sample_fem_result() {
  Figures f;
  FemResult r;
  r.case_path = "cases/sample.toml";
  r.provenance = sample_provenance();
  r.torque_Nm = f(), r.phi0_rad = f(), r.compliance_rad_per_Nm = f(), r.phi0_theory_rad = f();
  r.phi0_theory_cup_rad = f();
  r.phi0_theory_cup_terms = {f(), f(), f(), {f(), f()}, f(), f(), f()};
  r.phi0_engaged_rad = f();
  r.phi0_reading = {f(), f()};
  r.applied_torque_Nm = f(), r.reaction_torque_Nm = -f(), r.torque_balance_error_rel = f();
  r.max_hoop_stress_Pa = f(), r.max_hoop_stress_angle_deg = f(), r.min_hoop_stress_Pa = -f();
  r.min_hoop_stress_angle_deg = f();
  r.hoop_stress_case = "generator";
  r.hoop_stress_MPa = {f(), f(), f(), f(), f(), f(), {f(), f()}, -f(), {f(), f()}};
  r.hoop_stress_profile = {f(), f(), f(), {0, 15, 30}, {f(), f(), f()}, {f(), f(), f()}};
  r.wave_generator = FemResult::WaveGenerator{f(), f(), {f(), f(), f()}, {f(), f(), f()}, f()};
  r.torque_sweep = std::vector<FemResult::SweepPoint>{{f(), f()}, {f(), f()}};
  r.generator = FemResult::Generator{"cam", "unilateral frictionless contact on the generator band", f(),
                                     {{-f(), f()}, {f(), f()}}, {{-f(), f()}}, f(), f(), f(), -f(),
                                     FemResult::Bearing{f(), f()}, {{f(), f(), f()}, {f(), std::nullopt, f()}}};
  r.fatigue = FemResult::Fatigue{"generator_torque", "Goodman per component, no credit for compressive mean",
                                 sample_fatigue_point(f, "rim outer surface", true),
                                 sample_fatigue_point(f, "diaphragm fillet", false)};
  r.load_cases = {{"generator", f()}, {"torque", f()}, {"generator_torque", f()}};
  r.mesh = TetMeshFigures{static_cast<std::size_t>(f.whole()), static_cast<std::size_t>(f.whole()), f(), f(), f()};
  r.solver = {"tet10", static_cast<std::size_t>(f.whole()), f.whole(), f.whole(), f(), f(), f(), "PORD", false,
              "OpenBLAS", "petsc", "preonly + cholesky (mumps)", 2,
              FemResult::PetscFigures{{f.whole(), f.whole()}, f.whole(), f.whole()}, std::nullopt};
  r.timings_s = {f(), f(), f(), f(), f(), f(), f()};
  r.peak_rss_bytes = f.whole();
  return r;
}

/// The same on the harmonic solver: the section as the mesh, the harmonics solved; no generator.
inline FemResult sample_fourier_result() {
  Figures f;
  f.k = 1000;
  FemResult r = sample_fem_result();
  r.wave_generator.reset();
  r.torque_sweep.reset();
  r.generator.reset();
  r.fatigue.reset();
  r.mesh = SectionMeshFigures{"meridian section, 6-node triangles", 947, 418, 181824, 118368, 0.304};
  r.solver.method = "fourier";
  r.solver.backend = "cholmod";
  r.solver.petsc.reset();
  r.solver.harmonics = FemResult::Harmonics{64, {{0, f.whole(), f(), f()}, {2, f.whole(), f(), f()}}};
  return r;
}

inline BacklashResult::Pair sample_pair(Figures& f, bool in_mesh) {
  return {f(), in_mesh, f(), f(), f(), f(), {f(), f(), "flank / flank"}, {f(), -f(), "tip corner / tip land"}};
}

/// Backlash with an interference at rest (its remedy), a row out of the mesh and one in it, two mesh states.
inline BacklashResult sample_backlash_result() {
  Figures f;
  BacklashResult r;
  r.case_path = "cases/sample.toml";
  r.provenance = sample_provenance();
  r.neutral_curve = "FEM neutral curve out/sample/neutral_curve.csv (generator alone)";
  r.module_mm = f(), r.phi0_rad = f();
  r.phi0_source = "C_tau x torque from out/sample/result.json";
  r.torque_Nm = f();
  r.compliance_rad_per_Nm = f();
  r.geometry_check = {{f(), f(), f()}, {f(), f(), f()}, f(), -f(), f(), f(), f(), f(), -f(), sample_pair(f, true),
                      f(), true, -f(), sample_pair(f, true),
                      BacklashResult::Remedy{f(), f(), f(), {f(), f()}, "largest common factor"}};
  r.table_model = "the backlash paper's model";
  r.table.push_back({0.0, false, std::nullopt, std::nullopt, std::nullopt, "not in mesh", sample_pair(f, false),
                     sample_pair(f, false)});
  r.table.push_back({90.0, true, f(), -f(), f(), "loaded flank in contact", sample_pair(f, true), sample_pair(f, true)});
  r.min_backlash_basic_mm = f(), r.min_backlash_compensated_mm = -f(), r.max_backlash_basic_mm = f();
  r.max_backlash_compensated_mm = f();
  r.angular_play_arcmin = {f(), f(), {f(), f()}, "geometric play"};
  r.revolution = {static_cast<std::size_t>(f.whole()), f.whole(), f(), f(), {f.whole(), f.whole()}, "min over pairs",
                  {{f(), f.whole(), f(), f(), f(), f(), {f.whole(), f.whole(), f.whole()}, {f.whole(), f.whole(), 0}},
                   {f(), f.whole(), f(), f(), -f(), f(), {0, 0, 0}, {f.whole(), 0, 0}}}};
  r.interference = true;
  r.interference_locations = {{f(), f(), "cw side: flexspline tip corner into circular-spline flank", f(), -f(), f()}};
  return r;
}

/// Contact with the catalog's reference law, three face sections, an edge tooth whose removal leaves nothing to carry
/// the torque (null) and one flank each way.
inline ContactResult sample_contact_result() {
  Figures f;
  ContactResult r;
  r.case_path = "cases/sample.toml";
  r.provenance = sample_provenance();
  r.rated_torque_Nm = 31.0;
  r.torque_twist = {{-31.0, -f(), f.whole(), f()}, {0.0, -f(), 0, 0.0}, {0.0, f(), 0, 0.0}, {31.0, f(), f.whole(), f()}};
  r.catalog = {f(), f(), f(), f(), f(), "fitted to the curve"};
  r.catalog_reference = ContactResult::CatalogReference{17, f.whole(), f(), f(), f(), f(), f(), f(), f()};
  r.lost_motion_arcmin = f(), r.play_arcmin = f(), r.overlap_at_rest_um = f(), r.min_closing_angle_arcmin = -f();
  r.face_slices = 3;
  r.face_sections = {{f(), f(), f(), f(), f()}, {f(), f(), f(), 0.0, 0.0}, {f(), f(), -f(), f(), f()}};
  r.twist_at_rated_arcmin = f(), r.torque_balance_error_rel = f(), r.fem_reaction_torque_Nm = f();
  r.compliance_split = {-f(), f(), f(), f(), f(), ContactResult::BodyParts{f(), f(), f(), f()}};
  r.zone_edges = {false, {{f.whole(), f(), true, true, f(), -f(), f(), true, false}}, f(), std::nullopt};
  r.generator_support = "cam in unilateral contact";
  r.half_turn_pairs = true;
  r.flanks = {{f.whole(), 0, f(), "ccw", "flank on flank", false, f(), f(), f(), f(), f(), 0.0},
              {f.whole(), 2, -f(), "cw", "tip corner on flank", true, f(), -f(), f(), f(), 0.0, f()}};
  r.timings_s = {f(), f(), f(), f()};
  r.unknowns = f.whole();
  r.friction = ContactResult::Friction{f(), f.whole(), f.whole()};
  r.hysteresis_loss_arcmin = f(), r.rig_hysteresis_loss_arcmin = f();
  r.widest_loop_width_arcmin = f(), r.widest_loop_width_at_Nm = f();
  r.dissipated_energy_J = f(), r.friction_work_J = f();
  return r;
}

}  // namespace sw::testing
