#include "io/fem_output.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <sstream>

#include <nlohmann/json.hpp>

#include "common/error.hpp"
#include "fem/post.hpp"
#include "io/vtu.hpp"

namespace sw {

std::string fem_result_json(const Case& c, const TetMesh& mesh, const FlexsplineSolution& s, const RunInfo& run) {
  using nlohmann::json;
  const FemChecks& checks = s.checks;
  const FactorStats& factor = s.timings.factor;
  json j;
  j["case"] = c.path;
  j["torque_Nm"] = s.torque_Nm;
  j["phi0_rad"] = s.phi0_rad;
  j["compliance_rad_per_Nm"] = s.compliance_rad_per_Nm;
  j["phi0_theory_rad"] = checks.phi0_theory_rad;
  j["phi0_theory_cup_rad"] = checks.phi0_theory_cup.total_rad();
  j["phi0_theory_cup_terms"] = {{"diaphragm_rad", checks.phi0_theory_cup.diaphragm_rad},
                                {"body_wall_rad", checks.phi0_theory_cup.body_rad},
                                {"rim_rad", checks.phi0_theory_cup.rim_rad},
                                {"diaphragm_radii_mm",
                                 {checks.phi0_theory_cup.diaphragm_inner_radius_m * 1e3,
                                  checks.phi0_theory_cup.diaphragm_outer_radius_m * 1e3}},
                                {"body_length_mm", checks.phi0_theory_cup.body_length_m * 1e3},
                                {"rim_length_mm", checks.phi0_theory_cup.rim_length_m * 1e3},
                                {"rim_outer_radius_mm", checks.phi0_theory_cup.rim_outer_radius_m * 1e3}};
  j["phi0_engaged_rad"] = s.phi0_engaged_rad;
  j["phi0_reading"] = {{"radius_mm", s.reading_radius_m * 1e3}, {"z_mm", s.reading_z_m * 1e3}};
  j["applied_torque_Nm"] = checks.applied_torque_Nm;
  j["reaction_torque_Nm"] = checks.reaction_torque_Nm;
  j["torque_balance_error_rel"] =
      s.torque_Nm != 0 ? std::abs(checks.reaction_torque_Nm + checks.applied_torque_Nm) / std::abs(s.torque_Nm)
                       : 0.0;
  j["max_hoop_stress_Pa"] = s.hoop.max_tensile_Pa;
  j["max_hoop_stress_angle_deg"] = s.hoop.max_tensile_angle_deg;
  j["min_hoop_stress_Pa"] = s.hoop.max_compressive_Pa;
  j["min_hoop_stress_angle_deg"] = s.hoop.max_compressive_angle_deg;
  j["hoop_stress_case"] = s.cases.front().name;
  j["hoop_stress_MPa"] = {
      {"nominal_bending", s.hoop.nominal_bending_Pa / 1e6},
      {"nominal_membrane", s.hoop.nominal_membrane_Pa / 1e6},
      {"nominal_angle_deg", s.hoop.nominal_angle_deg},
      {"nominal_z_mm", s.hoop.profile_z_m * 1e3},
      {"ring_theory_bending", s.hoop.ring_theory_bending_Pa / 1e6},
      {"local_peak_tensile", s.hoop.max_tensile_Pa / 1e6},
      {"local_peak_tensile_at", {{"angle_deg", s.hoop.max_tensile_angle_deg}, {"z_mm", s.hoop.max_tensile_z_m * 1e3}}},
      {"local_peak_compressive", s.hoop.max_compressive_Pa / 1e6},
      {"local_peak_compressive_at",
       {{"angle_deg", s.hoop.max_compressive_angle_deg}, {"z_mm", s.hoop.max_compressive_z_m * 1e3}}}};
  {
    nlohmann::json profile = {{"z_mm", s.hoop.profile_z_m * 1e3},
                              {"inner_radius_mm", s.hoop.inner_radius_m * 1e3},
                              {"outer_radius_mm", s.hoop.outer_radius_m * 1e3},
                              {"angle_deg", json::array()}, {"inner_Pa", json::array()}, {"outer_Pa", json::array()}};
    for (int deg : {0, 15, 30, 45, 60, 75, 90}) {
      profile["angle_deg"].push_back(deg);
      profile["inner_Pa"].push_back(s.hoop.inner_Pa.at(deg));
      profile["outer_Pa"].push_back(s.hoop.outer_Pa.at(deg));
    }
    j["hoop_stress_profile"] = profile;
  }
  if (c.wave_generator) {
    j["wave_generator"] = {{"force_per_point_N", s.generator_force_N},
                           {"w0_reached_mm", s.generator_w0_m * 1e3},
                           {"net_force_N",
                            {checks.generator_net_force[0], checks.generator_net_force[1],
                             checks.generator_net_force[2]}},
                           {"net_moment_Nm",
                            {checks.generator_net_moment[0], checks.generator_net_moment[1],
                             checks.generator_net_moment[2]}},
                           {"rim_rotation_rad", checks.generator_rotation_rad}};
    json sweep = json::array();
    for (const auto& [T, c_tau] : s.torque_sweep) sweep.push_back({{"torque_Nm", T}, {"compliance_rad_per_Nm", c_tau}});
    j["torque_sweep"] = sweep;
  }
  if (s.generator) {
    const GeneratorReadout& g = *s.generator;
    auto zones = [](const std::vector<std::pair<double, double>>& z) {
      json a = json::array();
      for (const auto& [from, to] : z) a.push_back({from, to});
      return a;
    };
    j["generator"] = {
        {"model", g.model},
        {"idealisation", g.unilateral ? "unilateral frictionless contact on the generator band"
                                      : "the paper's given forces; torque case with the band held radially"},
        {"total_radial_force_N", g.total_radial_force_N},
        {"contact_zones_deg", zones(g.zones_wg_deg)},
        {"contact_zones_with_torque_deg", zones(g.zones_comb_deg)},
        {"min_contact_force_N", g.min_contact_force_N},
        {"reaction_torque_Nm", g.reaction_torque_Nm},
        {"w_major_axis_mm", g.w_major_m * 1e3},
        {"w_minor_axis_mm", g.w_minor_m * 1e3}};
    if (g.bearing_max_ball_load_N > 0) {
      j["generator"]["bearing_max_ball_load_N"] = g.bearing_max_ball_load_N;
      j["generator"]["bearing_max_approach_um"] = g.bearing_max_approach_m * 1e6;
    }
    if (!g.station_angle_rad.empty()) {
      json st = json::array();
      for (std::size_t k = 0; k < g.station_angle_rad.size(); ++k) {
        json row = {{"angle_deg", g.station_angle_rad[k] * 180 / std::numbers::pi}};
        if (!g.force_wg_N.empty()) row["force_N"] = g.force_wg_N[k];
        row["force_with_torque_N"] = g.force_comb_N[k];
        st.push_back(row);
      }
      j["generator"]["stations"] = st;  // each force acts at angle and at angle + 180°
    }
  }
  if (s.fatigue) {
    auto point = [](const FatiguePoint& p) {
      json o = {{"place", p.place},
                {"r_mm", p.r_m * 1e3},
                {"z_mm", p.z_m * 1e3},
                {"hoop_alternating_MPa", p.hoop.alternating_Pa / 1e6},
                {"hoop_mean_MPa", p.hoop.mean_Pa / 1e6},
                {"meridional_alternating_MPa", p.meridional.alternating_Pa / 1e6},
                {"meridional_mean_MPa", p.meridional.mean_Pa / 1e6}};
      if (p.safety_factor > 0) o["goodman_safety_factor"] = p.safety_factor;
      return o;
    };
    j["fatigue"] = {{"case", s.cases.back().name}, {"criterion", "Goodman per component, no credit for compressive mean"},
                    {"rim", point(s.fatigue->rim)}};
    if (s.fatigue->diaphragm) j["fatigue"]["diaphragm"] = point(*s.fatigue->diaphragm);
  }
  json cases = json::array();
  for (const auto& lc : s.cases) cases.push_back({{"name", lc.name}, {"rim_rotation_rad", lc.rim_rotation_rad}});
  j["load_cases"] = cases;
  j["mesh"] = {{"nodes", mesh.n_nodes()},
               {"elements", mesh.tets.size()},
               {"min_dihedral_deg", mesh.quality.min_dihedral_deg},
               {"max_dihedral_deg", mesh.quality.max_dihedral_deg},
               {"max_radius_edge_ratio", mesh.quality.max_radius_edge_ratio}};
  j["solver"] = {{"method", c.solver.method == SolverMethod::Fourier ? "fourier" : "tet10"},
                 {"dofs", 3 * mesh.n_nodes()},
                 {"equations", factor.equations},
                 {"matrix_nnz", factor.matrix_nnz},
                 {"factor_nnz", factor.factor_nnz},
                 {"factor_gflop", factor.factor_gflop},
                 {"factor_gflop_per_s", factor.factor_s > 0 ? factor.factor_gflop / factor.factor_s : 0.0},
                 {"ordering", factor.ordering},
                 {"supernodal", factor.supernodal},
                 {"blas", run.blas.description},
                 {"backend", factor.backend},
                 {"algorithm", factor.algorithm},
                 {"ranks", factor.ranks}};
  if (factor.backend == "petsc")
    j["solver"].update({{"peak_rss_bytes_per_rank", factor.peak_rss_bytes_per_rank},
                        {"iterations", factor.iterations},
                        {"right_hand_sides", factor.right_hand_sides}});
  j["timings_s"] = {{"mesh", run.mesh_s},
                    {"assemble", s.timings.assemble_s},
                    {"analyse", factor.analyse_s},
                    {"factor", factor.factor_s},
                    {"solve", s.timings.solve_s},
                    {"output", run.output_s},
                    {"total", run.total_s}};
  j["peak_rss_bytes"] = run.peak_rss_bytes;
  return j.dump(2) + "\n";
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

void write_fem_vtk(const std::filesystem::path& dir, const Case& c, const TetMesh& mesh, const FlexsplineSolution& s) {
  std::vector<std::pair<std::string, std::string>> datasets;
  const Eigen::Index n = static_cast<Eigen::Index>(mesh.n_nodes());
  for (const auto& lc : s.cases) {
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
  (void)c;
  write_pvd(dir / "flexspline.pvd", datasets);
}

namespace {
/// result.json as a JSON object, or one InputError line naming the file.
nlohmann::json read_fem_result_json(const std::filesystem::path& path) {
  std::ifstream in(path);
  const std::string file = path.string();
  if (!in) throw InputError(file + ": cannot open; give the result.json written by `strainwave fem CASE.toml`");
  nlohmann::json j;
  try {
    in >> j;
  } catch (const std::exception& e) {
    throw InputError(file + ": not valid JSON (" + std::string(e.what()) + ")");
  }
  if (!j.is_object()) throw InputError(file + ": not a JSON object; expected the result.json of `strainwave fem`");
  return j;
}
}  // namespace

FemCompensation read_fem_compensation(const std::filesystem::path& path) {
  const nlohmann::json j = read_fem_result_json(path);
  const std::string file = path.string();
  if (!j.contains("phi0_rad") || !j["phi0_rad"].is_number())
    throw InputError(file + ": phi0_rad is missing or not a number; expected the result.json of `strainwave fem`");
  FemCompensation c;
  c.phi0_rad = j["phi0_rad"].get<double>();
  if (j.contains("compliance_rad_per_Nm") && j["compliance_rad_per_Nm"].is_number())
    c.compliance_rad_per_Nm = j["compliance_rad_per_Nm"].get<double>();
  return c;
}

FemRunForContact read_fem_run_for_contact(const std::filesystem::path& path) {
  const nlohmann::json j = read_fem_result_json(path);
  const std::string file = path.string();
  FemRunForContact r;
  r.compliance_rad_per_Nm = read_fem_compliance(path);
  const auto& solver = j.contains("solver") ? j["solver"] : nlohmann::json();
  if (!solver.is_object() || solver.value("method", "") != "tet10" || !solver.contains("equations") ||
      !solver["equations"].is_number_integer())
    throw InputError(file + ": solver.equations is missing or solver.method is not \"tet10\"; the tooth contact "
                            "needs the result of a TET10 run");
  r.equations = solver["equations"].get<std::int64_t>();
  const auto& gen = j.contains("generator") ? j["generator"] : nlohmann::json();
  if (!gen.is_object() || !gen.contains("model") || !gen["model"].is_string())
    throw InputError(file + ": generator.model is missing; the tooth contact needs a run with a [wave_generator]");
  r.generator_model = gen["model"].get<std::string>();
  r.neutral_curve = read_neutral_curve_csv(path.parent_path() / "neutral_curve.csv");
  return r;
}

double read_fem_compliance(const std::filesystem::path& path) {
  const nlohmann::json j = read_fem_result_json(path);
  if (!j.contains("compliance_rad_per_Nm") || !j["compliance_rad_per_Nm"].is_number() ||
      !(j["compliance_rad_per_Nm"].get<double>() > 0))
    throw InputError(path.string() + ": compliance_rad_per_Nm is missing or not > 0; expected the FEM's C_tau in "
                                     "rad/(N m)");
  return j["compliance_rad_per_Nm"].get<double>();
}

}  // namespace sw
