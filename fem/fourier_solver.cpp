#include "fem/fourier_solver.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <numbers>
#include <string>

#include <Eigen/LU>
#include <Eigen/Geometry>
#include <Eigen/Sparse>

#include "common/constants.hpp"
#include "common/error.hpp"
#include "common/progress.hpp"
#include "generator/cam_profile.hpp"
#include "fem/flexspline_system.hpp"
#include "fem/fourier_loads.hpp"
#include "fem/post.hpp"
#include "mesh/flexspline.hpp"

namespace sw {

using namespace fourier;

Eigen::Matrix<double, 18, 18> harmonic_element_stiffness(const Eigen::Matrix<double, 6, 2>& X, const Material& m,
                                                         int n) {
  const auto D = elasticity(m);
  Mat18 K = Mat18::Zero();
  for (int k = 0; k < 7; ++k) {
    const StrainPoint p = strain_matrix(X, kRule.xi[k], kRule.eta[k], n);
    K.noalias() += (kRule.w[k] * std::abs(p.det) * p.r) * (p.B.transpose() * D * p.B);
  }
  return theta_weight(n) * K;
}

Eigen::MatrixXd solve_harmonic(const SectionMesh& s, const Material& m, int n, const std::vector<bool>& fixed,
                               const Eigen::MatrixXd& F) {
  const HarmonicDofs d = number_dofs(s.n_nodes(), n, fixed, axis_nodes(s));
  const CholmodFactor factor(assemble_polynomial(s, element_polynomials(s, m), d).at(n), d.node_of_eq);
  return to_nodes(d, factor.solve(to_equations(d, F)), Eigen::MatrixXd::Zero(F.rows(), 3));
}

std::vector<BandResponse> band_responses(const SectionMesh& s, const Material& m, const std::vector<bool>& fixed,
                                         const std::vector<SurfaceBand>& bands, int N, bool odd_harmonics) {
  std::vector<BandResponse> out;
  for (const SurfaceBand& b : bands) {
    const auto edges = band_edges(s, b);
    if (edges.empty())
      throw InputError("no boundary edge of the band's surface lies in z = " + std::to_string(b.z_lo_m * 1e3) +
                       " .. " + std::to_string(b.z_hi_m * 1e3) + " mm of the section");
    out.push_back({band_vector(s, edges), std::vector<Eigen::MatrixXd>(N + 1), std::vector<Eigen::MatrixXd>(N + 1)});
  }
  const std::vector<ElementPolynomial> poly = element_polynomials(s, m);
  const std::vector<bool> axis = axis_nodes(s);
  std::array<std::optional<GlobalPolynomial>, 3> numbering;  // n = 0, n = 1, n ≥ 2 (the axis conditions)
  std::array<std::unique_ptr<CholmodFactor>, 3> factors;      // one analysis each, refactorised per harmonic
  for (int n = 0; n <= N; ++n) {
    if (n % 2 != 0 && !odd_harmonics) continue;
    const int k = std::min(n, 2);
    if (!numbering[k]) numbering[k] = assemble_polynomial(s, poly, number_dofs(s.n_nodes(), n, fixed, axis));
    const HarmonicDofs& d = numbering[k]->dofs;
    const SymmetricCsc K = numbering[k]->at(n);
    if (factors[k]) factors[k]->refactorise(K);
    else factors[k] = std::make_unique<CholmodFactor>(K, d.node_of_eq);
    store_band_responses(out, n, d, factors[k]->solve(band_load_columns(d, out, s.nodes.rows())), 0);
  }
  return out;
}

Eigen::MatrixXd section_traction_load(const SectionMesh& s, int marker, const Eigen::Vector3d& traction) {
  return edge_integral(s, select_edges(s, marker), [&](const Eigen::Vector2d&) { return traction; });
}

SectionMesh case_section(const FlexsplineModel& c) {
  std::optional<std::pair<double, double>> band;
  if (c.wave_generator)
    band = std::pair{c.flexspline.length_m - c.wave_generator->axial_position_m, c.wave_generator->band_width_m};
  return mesh_flexspline_section(c.flexspline, c.gear, c.mesh, band);
}

ModelSizeEstimate fourier_model_size(const FlexsplineModel& c, const SectionMesh& section) {
  constexpr double kBaseBytes = 150e6, kBytesPerEquation = 150;
  ModelSizeEstimate e;
  e.model = "harmonic model (section nodes, harmonics 0.." + std::to_string(c.solver.harmonics) + ")";
  e.nodes = static_cast<double>(section.n_nodes());
  e.equations = 3.0 * e.nodes * (c.solver.harmonics + 1);
  e.peak_bytes = kBaseBytes + kBytesPerEquation * e.equations;
  e.mesh_text = mesh_size_text(c.mesh);
  e.remedy = "coarsen mesh.size_mm or mesh.wall_layers, lower solver.harmonics, or raise --max-memory";
  return e;
}

std::vector<NeutralCurveSamples> neutral_curves_at(const SectionMesh& s, const HarmonicField& u, double radius_m,
                                                   const std::vector<double>& z_m) {
  std::vector<NeutralCurveSamples> out;
  for (const double z : z_m) {
    NeutralCurveSamples nc;
    nc.radius_m = radius_m;
    nc.z_m = z;
    for (int k = 0; k < kRingSamples; ++k) nc.phi_rad.push_back(2 * kPi * k / kRingSamples);
    ring_curve(u, probe_at(s, {radius_m, z}), radius_m, nc.w_wg_m, nc.v_wg_m, nc.mu_wg_rad);
    out.push_back(std::move(nc));
  }
  return out;
}

namespace {

/// Calls add(n, e, U) with the strain energy U (J) of harmonic n of the field in triangle e, for every harmonic the
/// field has and every triangle: ½ uᵀK_n u of its two families (at n = 0 the one field: a and c of the symmetric
/// family, b of the antisymmetric one).
template <class Add>
void for_each_element_energy(const SectionMesh& s, const Material& m, const HarmonicField& u, const Add& add) {
  const std::vector<ElementPolynomial> poly = element_polynomials(s, m);
  for (int n = 0; n <= u.harmonics(); ++n) {
    const Eigen::MatrixXd &sym = u.sym[static_cast<std::size_t>(n)], &anti = u.anti[static_cast<std::size_t>(n)];
    if (sym.size() == 0 && anti.size() == 0) continue;  // a harmonic the loads did not reach
    for (std::size_t e = 0; e < s.triangles.size(); ++e) {
      const auto& t = s.triangles[e];
      const Mat18 K = poly[e].at(n);
      Eigen::Matrix<double, 18, 1> us = Eigen::Matrix<double, 18, 1>::Zero(), ua = us;
      for (int a = 0; a < 6; ++a) {
        if (sym.size()) us.segment<3>(3 * a) = sym.row(t[a]).transpose();
        if (anti.size()) ua.segment<3>(3 * a) = anti.row(t[a]).transpose();
      }
      if (n == 0) {
        for (int a = 0; a < 6; ++a) us[3 * a + 1] = ua[3 * a + 1];
        add(n, e, 0.5 * us.dot(K * us));
      } else {
        add(n, e, 0.5 * (us.dot(K * us) + ua.dot(K * ua)));
      }
    }
  }
}

}  // namespace

std::vector<double> harmonic_strain_energy_J(const SectionMesh& s, const Material& m, const HarmonicField& u) {
  std::vector<double> U(static_cast<std::size_t>(u.harmonics() + 1), 0.0);
  for_each_element_energy(s, m, u, [&](int n, std::size_t, double e) { U[static_cast<std::size_t>(n)] += e; });
  return U;
}

std::vector<double> strain_energy_by_region_J(const SectionMesh& s, const Material& m, const HarmonicField& u) {
  const int regions = s.region.empty() ? 1 : *std::max_element(s.region.begin(), s.region.end()) + 1;
  std::vector<double> U(static_cast<std::size_t>(regions), 0.0);
  for_each_element_energy(s, m, u, [&](int, std::size_t e, double energy) {
    U[s.region.empty() ? 0 : static_cast<std::size_t>(s.region[e])] += energy;
  });
  return U;
}

double clamp_reaction_moment(const SectionMesh& s, const Material& m, const std::vector<bool>& clamped,
                             const HarmonicField& u, const Eigen::MatrixXd& anti0) {
  Eigen::MatrixXd R = -anti0;
  const std::vector<ElementPolynomial> poly = element_polynomials(s, m);
  for (std::size_t e = 0; e < s.triangles.size(); ++e) {
    const auto& t = s.triangles[e];
    Eigen::Matrix<double, 18, 1> ue;
    for (int a = 0; a < 6; ++a) ue.segment<3>(3 * a) = u.anti[0].row(t[a]).transpose();
    const Eigen::Matrix<double, 18, 1> fe = poly[e].at(0) * ue;
    for (int a = 0; a < 6; ++a) R.row(t[a]) += fe.segment<3>(3 * a).transpose();
  }
  for (std::size_t i = 0; i < s.n_nodes(); ++i)
    if (!clamped[i]) R.row(static_cast<Eigen::Index>(i)).setZero();
  return moment_z(s, R);
}

}  // namespace sw
