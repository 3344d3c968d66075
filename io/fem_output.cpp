#include "io/fem_output.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <sstream>

#include <nlohmann/json.hpp>

#include "common/error.hpp"
#include "fem/post.hpp"
#include "io/json_file.hpp"
#include "io/vtu.hpp"

namespace sw {

namespace {

/// How result.json's readers name it in their messages.
constexpr const char* kResultExpected = "the result.json of `strainwave fem`";
constexpr const char* kResultCannotOpen = "cannot open; give the result.json written by `strainwave fem CASE.toml`";

// ---- from the solution to the file's figures

FemResult::CupTheoryTerms cup_theory_terms(const CupTorsionTheory& th) {
  FemResult::CupTheoryTerms t;
  t.diaphragm_rad = th.diaphragm_rad;
  t.body_wall_rad = th.body_rad;
  t.rim_rad = th.rim_rad;
  t.diaphragm_radii_mm = {th.diaphragm_inner_radius_m * 1e3, th.diaphragm_outer_radius_m * 1e3};
  t.body_length_mm = th.body_length_m * 1e3;
  t.rim_length_mm = th.rim_length_m * 1e3;
  t.rim_outer_radius_mm = th.rim_outer_radius_m * 1e3;
  return t;
}

FemResult::HoopStressMPa hoop_stress_MPa(const HoopStressExtreme& h) {
  FemResult::HoopStressMPa m;
  m.nominal_bending = h.nominal_bending_Pa / 1e6;
  m.nominal_membrane = h.nominal_membrane_Pa / 1e6;
  m.nominal_angle_deg = h.nominal_angle_deg;
  m.nominal_z_mm = h.profile_z_m * 1e3;
  m.ring_theory_bending = h.ring_theory_bending_Pa / 1e6;
  m.local_peak_tensile = h.max_tensile_Pa / 1e6;
  m.local_peak_tensile_at = {h.max_tensile_angle_deg, h.max_tensile_z_m * 1e3};
  m.local_peak_compressive = h.max_compressive_Pa / 1e6;
  m.local_peak_compressive_at = {h.max_compressive_angle_deg, h.max_compressive_z_m * 1e3};
  return m;
}

/// Every degree over a half turn from the major axis (the generator's deformation repeats every half turn): enough
/// to draw the local peaks where the generator touches, which are a few degrees wide.
FemResult::HoopStressProfile hoop_stress_profile(const HoopStressExtreme& h) {
  FemResult::HoopStressProfile p;
  p.z_mm = h.profile_z_m * 1e3;
  p.inner_radius_mm = h.inner_radius_m * 1e3;
  p.outer_radius_mm = h.outer_radius_m * 1e3;
  for (int deg = 0; deg <= 180; ++deg) {
    p.angle_deg.push_back(deg);
    p.inner_Pa.push_back(h.inner_Pa.at(deg));
    p.outer_Pa.push_back(h.outer_Pa.at(deg));
  }
  return p;
}

FemResult::WaveGenerator wave_generator_figures(const FlexsplineSolution& s) {
  const FemChecks& checks = s.checks;
  FemResult::WaveGenerator w;
  w.force_per_point_N = s.generator_force_N;
  w.w0_reached_mm = s.generator_w0_m * 1e3;
  w.net_force_N = {checks.generator_net_force[0], checks.generator_net_force[1], checks.generator_net_force[2]};
  w.net_moment_Nm = {checks.generator_net_moment[0], checks.generator_net_moment[1], checks.generator_net_moment[2]};
  w.rim_rotation_rad = checks.generator_rotation_rad;
  return w;
}

FemResult::Generator generator_figures(const GeneratorReadout& g) {
  FemResult::Generator r;
  r.model = g.model;
  r.idealisation = g.unilateral ? "unilateral frictionless contact on the generator band"
                                : "the paper's given forces; torque case with the band held radially";
  r.total_radial_force_N = g.total_radial_force_N;
  for (const auto& [from, to] : g.zones_wg_deg) r.contact_zones_deg.push_back({from, to});
  for (const auto& [from, to] : g.zones_comb_deg) r.contact_zones_with_torque_deg.push_back({from, to});
  r.min_contact_force_N = g.min_contact_force_N;
  r.reaction_torque_Nm = g.reaction_torque_Nm;
  r.w_major_axis_mm = g.w_major_m * 1e3;
  r.w_minor_axis_mm = g.w_minor_m * 1e3;
  if (g.bearing_max_ball_load_N > 0)
    r.bearing = FemResult::Bearing{g.bearing_max_ball_load_N, g.bearing_max_approach_m * 1e6};
  for (std::size_t k = 0; k < g.station_angle_rad.size(); ++k) {
    FemResult::Station st;
    st.angle_deg = g.station_angle_rad[k] * 180 / std::numbers::pi;
    if (!g.force_wg_N.empty()) st.force_N = g.force_wg_N[k];
    st.force_with_torque_N = g.force_comb_N[k];
    r.stations.push_back(st);
  }
  return r;
}

FemResult::FatiguePoint fatigue_point(const FatiguePoint& p) {
  FemResult::FatiguePoint o;
  o.place = p.place;
  o.r_mm = p.r_m * 1e3;
  o.z_mm = p.z_m * 1e3;
  o.hoop_alternating_MPa = p.hoop.alternating_Pa / 1e6;
  o.hoop_mean_MPa = p.hoop.mean_Pa / 1e6;
  o.meridional_alternating_MPa = p.meridional.alternating_Pa / 1e6;
  o.meridional_mean_MPa = p.meridional.mean_Pa / 1e6;
  if (p.safety_factor > 0) o.goodman_safety_factor = p.safety_factor;
  return o;
}

FemResult::Fatigue fatigue_figures(const FlexsplineSolution& s) {
  FemResult::Fatigue f;
  f.case_name = s.cases.back().name;
  f.criterion = "Goodman per component, no credit for compressive mean";
  f.rim = fatigue_point(s.fatigue->rim);
  if (s.fatigue->diaphragm) f.diaphragm = fatigue_point(*s.fatigue->diaphragm);
  return f;
}

FemResult::Solver solver_figures(const Case& c, const TetMesh& mesh, const FactorStats& factor, const RunInfo& run) {
  FemResult::Solver v;
  v.method = c.solver.method == SolverMethod::Fourier ? "fourier" : "tet10";
  v.dofs = 3 * mesh.n_nodes();
  v.equations = factor.equations;
  v.matrix_nnz = factor.matrix_nnz;
  v.factor_nnz = factor.factor_nnz;
  v.factor_gflop = factor.factor_gflop;
  v.factor_gflop_per_s = factor.factor_s > 0 ? factor.factor_gflop / factor.factor_s : 0.0;
  v.ordering = factor.ordering;
  v.supernodal = factor.supernodal;
  v.blas = run.blas.description;
  v.backend = factor.backend;
  v.algorithm = factor.algorithm;
  v.ranks = factor.ranks;
  if (factor.backend == "petsc")
    v.petsc = FemResult::PetscFigures{factor.peak_rss_bytes_per_rank, factor.iterations, factor.right_hand_sides};
  return v;
}

/// The torque case's balance and the hoop stress figures of the solution.
void set_checks_and_hoop(FemResult& r, const FlexsplineSolution& s) {
  const FemChecks& checks = s.checks;
  r.applied_torque_Nm = checks.applied_torque_Nm;
  r.reaction_torque_Nm = checks.reaction_torque_Nm;
  r.torque_balance_error_rel =
      s.torque_Nm != 0 ? std::abs(checks.reaction_torque_Nm + checks.applied_torque_Nm) / std::abs(s.torque_Nm) : 0.0;
  r.max_hoop_stress_Pa = s.hoop.max_tensile_Pa;
  r.max_hoop_stress_angle_deg = s.hoop.max_tensile_angle_deg;
  r.min_hoop_stress_Pa = s.hoop.max_compressive_Pa;
  r.min_hoop_stress_angle_deg = s.hoop.max_compressive_angle_deg;
  r.hoop_stress_case = s.cases.front().name;
  r.hoop_stress_MPa = hoop_stress_MPa(s.hoop);
  r.hoop_stress_profile = hoop_stress_profile(s.hoop);
}

}  // namespace

FemResult fem_result(const Case& c, const TetMesh& mesh, const FlexsplineSolution& s, const RunInfo& run) {
  const FemChecks& checks = s.checks;
  const FactorStats& factor = s.timings.factor;
  FemResult r;
  r.case_path = c.path;
  r.provenance = provenance_of(c);
  r.torque_Nm = s.torque_Nm;
  r.phi0_rad = s.phi0_rad;
  r.compliance_rad_per_Nm = s.compliance_rad_per_Nm;
  r.phi0_theory_rad = checks.phi0_theory_rad;
  r.phi0_theory_cup_rad = checks.phi0_theory_cup.total_rad();
  r.phi0_theory_cup_terms = cup_theory_terms(checks.phi0_theory_cup);
  r.phi0_engaged_rad = s.phi0_engaged_rad;
  r.phi0_reading = {s.reading_radius_m * 1e3, s.reading_z_m * 1e3};
  set_checks_and_hoop(r, s);
  if (c.wave_generator) {
    r.wave_generator = wave_generator_figures(s);
    r.torque_sweep.emplace();
    for (const auto& [T, c_tau] : s.torque_sweep) r.torque_sweep->push_back({T, c_tau});
  }
  if (s.generator) r.generator = generator_figures(*s.generator);
  if (s.fatigue) r.fatigue = fatigue_figures(s);
  for (const auto& lc : s.cases) r.load_cases.push_back({lc.name, lc.rim_rotation_rad});
  r.mesh = TetMeshFigures{mesh.n_nodes(), mesh.tets.size(), mesh.quality.min_dihedral_deg,
                                     mesh.quality.max_dihedral_deg, mesh.quality.max_radius_edge_ratio};
  r.solver = solver_figures(c, mesh, factor, run);
  r.timings_s = {run.mesh_s, s.timings.assemble_s, factor.analyse_s, factor.factor_s, s.timings.solve_s,
                 run.output_s, run.total_s};
  r.peak_rss_bytes = run.peak_rss_bytes;
  return r;
}

FemResult fem_result(const Case& c, const FourierSolution& f, const RunInfo& run) {
  FemResult r = fem_result(c, f.grid, f.figures, run);
  std::optional<double> shear_factor;
  if (f.section.tooth_layer) shear_factor = f.section.tooth_layer->shear_factor;
  r.mesh = SectionMeshFigures{"meridian section, 6-node triangles", f.section.n_nodes(), f.section.triangles.size(),
                              f.grid.n_nodes(), f.grid.tets.size(), shear_factor};
  FemResult::Harmonics h{f.harmonics_kept, {}};
  r.solver.equations = 0;
  for (const HarmonicStats& n : f.harmonics) {
    r.solver.equations += n.equations;
    h.harmonics_solved.push_back({n.n, n.equations, n.factor_nnz, n.factor_s});
  }
  r.solver.dofs = 3 * f.section.n_nodes() * static_cast<std::size_t>(f.harmonics_kept + 1);
  r.solver.harmonics = h;
  return r;
}

// ---- result.json's field tables: its keys, each with the member that holds it

static auto fields(std::type_identity<FemResult::CupTheoryTerms>) {
  using T = FemResult::CupTheoryTerms;
  return std::tuple{field("diaphragm_rad", &T::diaphragm_rad), field("body_wall_rad", &T::body_wall_rad),
                    field("rim_rad", &T::rim_rad), field("diaphragm_radii_mm", &T::diaphragm_radii_mm),
                    field("body_length_mm", &T::body_length_mm), field("rim_length_mm", &T::rim_length_mm),
                    field("rim_outer_radius_mm", &T::rim_outer_radius_mm)};
}

static auto fields(std::type_identity<FemResult::Reading>) {
  using T = FemResult::Reading;
  return std::tuple{field("radius_mm", &T::radius_mm), field("z_mm", &T::z_mm)};
}

static auto fields(std::type_identity<FemResult::Place>) {
  using T = FemResult::Place;
  return std::tuple{field("angle_deg", &T::angle_deg), field("z_mm", &T::z_mm)};
}

static auto fields(std::type_identity<FemResult::HoopStressMPa>) {
  using T = FemResult::HoopStressMPa;
  return std::tuple{field("nominal_bending", &T::nominal_bending), field("nominal_membrane", &T::nominal_membrane),
                    field("nominal_angle_deg", &T::nominal_angle_deg), field("nominal_z_mm", &T::nominal_z_mm),
                    field("ring_theory_bending", &T::ring_theory_bending),
                    field("local_peak_tensile", &T::local_peak_tensile),
                    field("local_peak_tensile_at", &T::local_peak_tensile_at),
                    field("local_peak_compressive", &T::local_peak_compressive),
                    field("local_peak_compressive_at", &T::local_peak_compressive_at)};
}

static auto fields(std::type_identity<FemResult::HoopStressProfile>) {
  using T = FemResult::HoopStressProfile;
  return std::tuple{field("z_mm", &T::z_mm), field("inner_radius_mm", &T::inner_radius_mm),
                    field("outer_radius_mm", &T::outer_radius_mm), field("angle_deg", &T::angle_deg),
                    field("inner_Pa", &T::inner_Pa), field("outer_Pa", &T::outer_Pa)};
}

static auto fields(std::type_identity<FemResult::WaveGenerator>) {
  using T = FemResult::WaveGenerator;
  return std::tuple{field("force_per_point_N", &T::force_per_point_N), field("w0_reached_mm", &T::w0_reached_mm),
                    field("net_force_N", &T::net_force_N), field("net_moment_Nm", &T::net_moment_Nm),
                    field("rim_rotation_rad", &T::rim_rotation_rad)};
}

static auto fields(std::type_identity<FemResult::SweepPoint>) {
  using T = FemResult::SweepPoint;
  return std::tuple{field("torque_Nm", &T::torque_Nm), field("compliance_rad_per_Nm", &T::compliance_rad_per_Nm)};
}

static auto fields(std::type_identity<FemResult::Bearing>) {
  using T = FemResult::Bearing;
  return std::tuple{field("bearing_max_ball_load_N", &T::bearing_max_ball_load_N),
                    field("bearing_max_approach_um", &T::bearing_max_approach_um)};
}

static auto fields(std::type_identity<FemResult::Station>) {
  using T = FemResult::Station;
  return std::tuple{field("angle_deg", &T::angle_deg), field("force_N", &T::force_N),
                    field("force_with_torque_N", &T::force_with_torque_N)};
}

static auto fields(std::type_identity<FemResult::Generator>) {
  using T = FemResult::Generator;
  return std::tuple{field("model", &T::model), field("idealisation", &T::idealisation),
                    field("total_radial_force_N", &T::total_radial_force_N),
                    field("contact_zones_deg", &T::contact_zones_deg),
                    field("contact_zones_with_torque_deg", &T::contact_zones_with_torque_deg),
                    field("min_contact_force_N", &T::min_contact_force_N),
                    field("reaction_torque_Nm", &T::reaction_torque_Nm), field("w_major_axis_mm", &T::w_major_axis_mm),
                    field("w_minor_axis_mm", &T::w_minor_axis_mm), flattened(&T::bearing),
                    omitted_when_empty("stations", &T::stations)};
}

static auto fields(std::type_identity<FemResult::FatiguePoint>) {
  using T = FemResult::FatiguePoint;
  return std::tuple{field("place", &T::place), field("r_mm", &T::r_mm), field("z_mm", &T::z_mm),
                    field("hoop_alternating_MPa", &T::hoop_alternating_MPa),
                    field("hoop_mean_MPa", &T::hoop_mean_MPa),
                    field("meridional_alternating_MPa", &T::meridional_alternating_MPa),
                    field("meridional_mean_MPa", &T::meridional_mean_MPa),
                    field("goodman_safety_factor", &T::goodman_safety_factor)};
}

static auto fields(std::type_identity<FemResult::Fatigue>) {
  using T = FemResult::Fatigue;
  return std::tuple{field("case", &T::case_name), field("criterion", &T::criterion), field("rim", &T::rim),
                    field("diaphragm", &T::diaphragm)};
}

static auto fields(std::type_identity<FemResult::LoadCase>) {
  using T = FemResult::LoadCase;
  return std::tuple{field("name", &T::name), field("rim_rotation_rad", &T::rim_rotation_rad)};
}

static auto fields(std::type_identity<TetMeshFigures>) {
  using T = TetMeshFigures;
  return std::tuple{field("nodes", &T::nodes), field("elements", &T::elements),
                    field("min_dihedral_deg", &T::min_dihedral_deg), field("max_dihedral_deg", &T::max_dihedral_deg),
                    field("max_radius_edge_ratio", &T::max_radius_edge_ratio)};
}

static auto fields(std::type_identity<SectionMeshFigures>) {
  using T = SectionMeshFigures;
  return std::tuple{field("kind", &T::kind), field("nodes", &T::nodes), field("elements", &T::elements),
                    field("grid_nodes", &T::grid_nodes), field("grid_elements", &T::grid_elements),
                    field("tooth_layer_shear_factor", &T::tooth_layer_shear_factor)};
}

static auto fields(std::type_identity<FemResult::PetscFigures>) {
  using T = FemResult::PetscFigures;
  return std::tuple{field("peak_rss_bytes_per_rank", &T::peak_rss_bytes_per_rank),
                    field("iterations", &T::iterations), field("right_hand_sides", &T::right_hand_sides)};
}

static auto fields(std::type_identity<FemResult::HarmonicSolved>) {
  using T = FemResult::HarmonicSolved;
  return std::tuple{field("n", &T::n), field("equations", &T::equations), field("factor_nnz", &T::factor_nnz),
                    field("factor_s", &T::factor_s)};
}

static auto fields(std::type_identity<FemResult::Harmonics>) {
  using T = FemResult::Harmonics;
  return std::tuple{field("harmonics", &T::harmonics), field("harmonics_solved", &T::harmonics_solved)};
}

static auto fields(std::type_identity<FemResult::Solver>) {
  using T = FemResult::Solver;
  return std::tuple{field("method", &T::method), field("dofs", &T::dofs), field("equations", &T::equations),
                    field("matrix_nnz", &T::matrix_nnz), field("factor_nnz", &T::factor_nnz),
                    field("factor_gflop", &T::factor_gflop), field("factor_gflop_per_s", &T::factor_gflop_per_s),
                    field("ordering", &T::ordering), field("supernodal", &T::supernodal), field("blas", &T::blas),
                    field("backend", &T::backend), field("algorithm", &T::algorithm), field("ranks", &T::ranks),
                    flattened(&T::petsc), flattened(&T::harmonics)};
}

static auto fields(std::type_identity<FemResult::Timings>) {
  using T = FemResult::Timings;
  return std::tuple{field("mesh", &T::mesh),   field("assemble", &T::assemble), field("analyse", &T::analyse),
                    field("factor", &T::factor), field("solve", &T::solve),     field("output", &T::output),
                    field("total", &T::total)};
}

/// Every key but `mesh`, whose kind the solver tells.
static auto fields(std::type_identity<FemResult>) {
  using T = FemResult;
  return std::tuple{field("torque_Nm", &T::torque_Nm), field("phi0_rad", &T::phi0_rad),
                    field("compliance_rad_per_Nm", &T::compliance_rad_per_Nm),
                    field("phi0_theory_rad", &T::phi0_theory_rad), field("phi0_theory_cup_rad", &T::phi0_theory_cup_rad),
                    field("phi0_theory_cup_terms", &T::phi0_theory_cup_terms),
                    field("phi0_engaged_rad", &T::phi0_engaged_rad), field("phi0_reading", &T::phi0_reading),
                    field("applied_torque_Nm", &T::applied_torque_Nm), field("reaction_torque_Nm", &T::reaction_torque_Nm),
                    field("torque_balance_error_rel", &T::torque_balance_error_rel),
                    field("max_hoop_stress_Pa", &T::max_hoop_stress_Pa),
                    field("max_hoop_stress_angle_deg", &T::max_hoop_stress_angle_deg),
                    field("min_hoop_stress_Pa", &T::min_hoop_stress_Pa),
                    field("min_hoop_stress_angle_deg", &T::min_hoop_stress_angle_deg),
                    field("hoop_stress_case", &T::hoop_stress_case), field("hoop_stress_MPa", &T::hoop_stress_MPa),
                    field("hoop_stress_profile", &T::hoop_stress_profile),
                    field("wave_generator", &T::wave_generator), field("torque_sweep", &T::torque_sweep),
                    field("generator", &T::generator), field("fatigue", &T::fatigue),
                    field("load_cases", &T::load_cases), field("solver", &T::solver),
                    field("timings_s", &T::timings_s), field("peak_rss_bytes", &T::peak_rss_bytes),
                    field("case_file", &T::case_path), flattened(&T::provenance)};
}

std::string fem_result_json(const FemResult& r) {
  nlohmann::json j = to_json_object(r);
  std::visit([&j](const auto& m) { j["mesh"] = to_json_object(m); }, r.mesh);
  return j.dump(2) + "\n";
}

namespace {
JsonIn open_result_json(const std::filesystem::path& path) { return JsonIn::open(path, kResultCannotOpen, kResultExpected); }
}  // namespace

FemResult read_fem_result(const std::filesystem::path& path) {
  const JsonIn j = open_result_json(path);
  FemResult r = read_object<FemResult>(j);
  if (r.solver.method == "fourier") r.mesh = read_object<SectionMeshFigures>(j["mesh"]);
  else r.mesh = read_object<TetMeshFigures>(j["mesh"]);
  return r;
}

std::string neutral_curve_csv(const NeutralCurveSamples& nc) {
  std::ostringstream s;
  s << "# neutral circle radius_mm " << nc.radius_m * 1e3 << ", z_mm " << nc.z_m * 1e3 << "\n";
  s << "phi_rad,w_wg_m,v_wg_m,mu_wg_rad,w_comb_m,v_comb_m,mu_comb_rad\n";
  char line[512];
  for (std::size_t k = 0; k < nc.phi_rad.size(); ++k) {
    std::snprintf(line, sizeof line, "%.9f,%.9e,%.9e,%.9e,%.9e,%.9e,%.9e\n", nc.phi_rad[k], nc.w_wg_m[k], nc.v_wg_m[k],
                  nc.mu_wg_rad[k], nc.w_comb_m[k], nc.v_comb_m[k], nc.mu_comb_rad[k]);
    s << line;
  }
  return s.str();
}

NeutralCurveSamples read_neutral_curve_csv(const std::filesystem::path& csv) {
  std::ifstream in(csv);
  const std::string file = csv.string();
  if (!in) throw InputError(file + ": cannot open (run `strainwave fem` first, or pass the FEM output folder)");
  const std::string expected = "phi_rad,w_wg_m,v_wg_m,mu_wg_rad,w_comb_m,v_comb_m,mu_comb_rad";
  NeutralCurveSamples nc;
  std::vector<double>* columns[] = {&nc.phi_rad, &nc.w_wg_m, &nc.v_wg_m, &nc.mu_wg_rad,
                                    &nc.w_comb_m, &nc.v_comb_m, &nc.mu_comb_rad};
  std::string line;
  int line_no = 0;
  bool header = false;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    if (line[0] == '#') {
      std::istringstream meta(line.substr(1));  // "# neutral circle radius_mm R, z_mm Z"
      std::string key, value;
      while (meta >> key) {
        if ((key == "radius_mm" || key == "z_mm") && meta >> value) {
          (key == "radius_mm" ? nc.radius_m : nc.z_m) = std::strtod(value.c_str(), nullptr) * 1e-3;
        }
      }
      continue;
    }
    if (!header) {
      std::string cols;
      for (char ch : line)
        if (ch != ' ' && ch != '\t') cols += ch;
      if (cols != expected) throw InputError(file + ":" + std::to_string(line_no) + ": header must be `" + expected + "`");
      header = true;
      continue;
    }
    std::stringstream ss(line);
    std::string cell;
    size_t col = 0;
    while (std::getline(ss, cell, ',')) {
      char* end = nullptr;
      const double x = std::strtod(cell.c_str(), &end);
      while (end && (*end == ' ' || *end == '\t')) ++end;
      if (cell.empty() || end == cell.c_str() || *end != '\0' || !std::isfinite(x))
        throw InputError(file + ":" + std::to_string(line_no) + ": column " + std::to_string(col + 1) + " = '" + cell +
                         "'; expected a finite number");
      if (col < 7) columns[col]->push_back(x);
      ++col;
    }
    if (col != 7)
      throw InputError(file + ":" + std::to_string(line_no) + ": " + std::to_string(col) + " values; expected 7");
  }
  if (!header) throw InputError(file + ": no header line; expected `" + expected + "`");
  return nc;
}

void write_fem_vtk(const std::filesystem::path& dir, const TetMesh& mesh, const std::vector<LoadCaseSolution>& cases) {
  std::vector<std::pair<std::string, std::string>> datasets;
  const Eigen::Index n = static_cast<Eigen::Index>(mesh.n_nodes());
  for (const auto& lc : cases) {
    const CylindricalFields cyl = cylindrical_components(mesh, lc.u, lc.stress);
    std::vector<NodalField> fields;
    fields.push_back({"displacement", Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(
                                          lc.u.data(), n, 3)});
    fields.push_back({"stress", lc.stress});
    fields.push_back({"von_mises", von_mises(lc.stress)});
    fields.push_back({"u_r", cyl.u_r});
    fields.push_back({"u_theta", cyl.u_theta});
    fields.push_back({"stress_rr", cyl.s_rr});
    fields.push_back({"stress_hoop", cyl.s_thetatheta});
    fields.push_back({"stress_zz", cyl.s_zz});
    fields.push_back({"stress_ztheta", cyl.s_ztheta});
    const std::string file = "flexspline_" + lc.name + ".vtu";
    write_vtu(dir / file, mesh, fields);
    datasets.emplace_back(lc.name, file);
  }
  write_pvd(dir / "flexspline.pvd", datasets);
}

FemCompensation read_fem_compensation(const std::filesystem::path& path) {
  const JsonIn j = open_result_json(path);
  FemCompensation c;
  c.phi0_rad = j["phi0_rad"].finite();
  // C_τ is taken when it is a number: a run at zero torque writes none (null).
  if (const auto compliance = j.optional_number("compliance_rad_per_Nm"); compliance && std::isfinite(*compliance))
    c.compliance_rad_per_Nm = *compliance;
  return c;
}

FemRunForContact read_fem_run_for_contact(const std::filesystem::path& path) {
  const JsonIn j = open_result_json(path);
  FemRunForContact r;
  r.compliance_rad_per_Nm = read_fem_compliance(path);
  r.method = j["solver"]["method"].text();
  if (r.method != "tet10" && r.method != "fourier") j["solver"]["method"].fail("\"tet10\" or \"fourier\"");
  r.equations = j["solver"]["equations"].integer();
  r.generator_model = j["generator"]["model"].text();
  r.neutral_curve = read_neutral_curve_csv(path.parent_path() / "neutral_curve.csv");
  return r;
}

double read_fem_compliance(const std::filesystem::path& path) {
  const JsonIn compliance = open_result_json(path)["compliance_rad_per_Nm"];
  if (!(compliance.finite() > 0)) compliance.fail("the FEM's C_tau > 0 in rad/(N m)");
  return compliance.finite();
}

}  // namespace sw
