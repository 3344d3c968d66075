// The harmonic solver's tooth layer (flexspline.teeth = "layer"): the teeth homogenised as ribs along the face. Its
// elasticity against the closed forms of three exact fields on an annulus whose outer half is the layer (each field
// at most quadratic, so the quadratic section holds it exactly): a uniaxial stretch along the face, which the ribs
// carry at their solidity (plane stress in a rib: the field with u_r = −ν·ε·r is the exact one in both parts), a
// twist and a shear across the rim, which they carry at their solidity times the cell's factor and at their solidity,
// and a uniform radial growth, which the layer does not carry (no stress crosses the spaces between teeth); and the
// designed section's layer holds the teeth's own area and its shear factor is the cell's.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "fem/fourier_element.hpp"
#include "fem/fourier_section.hpp"
#include "fem/fourier_solver.hpp"
#include "fem/rib_cell.hpp"
#include "gear/tooth_profile.hpp"
#include "mesh/tet_mesh.hpp"

namespace sw {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kR0 = 10e-3, kR1 = 11e-3, kR2 = 12e-3, kL = 8e-3;  // tube kR0..kR1, layer kR1..kR2, length
constexpr double kPhi1 = 0.8, kPhi2 = 0.2;  // the layer's solidity, linear from kR1 to kR2

/// The annulus kR0..kR2 × 0..kL whose triangles outside kR1 are the tooth layer, of solidity linear in r.
SectionMesh layered_annulus() {
  SectionMesh s = mesh_annulus_section({kR0, 10.5e-3, kR1, 11.4e-3, 11.7e-3, kR2}, {0, 2e-3, 5e-3, kL});
  for (std::size_t e = 0; e < s.triangles.size(); ++e) {
    double r = 0;
    for (int a = 0; a < 3; ++a) r += s.nodes(s.triangles[e][a], 0) / 3;
    if (r > kR1) s.region[e] = kToothLayerRegion;
  }
  s.tooth_layer = ToothLayer{{kR1, kR2}, {kPhi1, kPhi2}};
  return s;
}

/// The harmonic-0 field of u_r(r, z), u_θ(r, z), u_z(r, z) at every node.
template <class Ur, class Ut, class Uz>
HarmonicField axisymmetric_field(const SectionMesh& s, Ur ur, Ut ut, Uz uz) {
  HarmonicField f;
  f.sym = {Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(s.n_nodes()), 3)};
  f.anti = f.sym;
  for (Eigen::Index i = 0; i < static_cast<Eigen::Index>(s.n_nodes()); ++i) {
    const double r = s.nodes(i, 0), z = s.nodes(i, 1);
    f.sym[0](i, 0) = ur(r, z);
    f.sym[0](i, 2) = uz(r, z);
    f.anti[0](i, 1) = -ut(r, z);  // n = 0: u_θ = −b̃ of the antisymmetric family
  }
  return f;
}

/// 2π·kL·∫ g(r)·r dr over kR1..kR2 (Simpson on 2000 intervals: smooth integrands, 1e-13).
template <class G>
double layer_volume_integral(G g) {
  const int n = 2000;
  double sum = 0;
  for (int k = 0; k <= n; ++k) {
    const double r = kR1 + (kR2 - kR1) * k / n;
    sum += (k == 0 || k == n ? 1 : k % 2 ? 4 : 2) * g(r) * r;
  }
  return 2 * kPi * kL * sum * (kR2 - kR1) / (3 * n);
}

double solidity(double r) { return kPhi1 + (kPhi2 - kPhi1) * (r - kR1) / (kR2 - kR1); }

// Stretched along the face by ε (u_z = ε z, u_r = −ν ε r), every rib carries σ_z = E ε at its solidity: the layer's
// energy is ½ E ε² ∫ φ dV, the tube's ½ E ε² V. The field is exact in both parts and the integrands are polynomials
// the 7-point rule integrates exactly: 1e-10 for the tube, 1e-9 for the layer, whose closed form also holds its residual
// hoop modulus' energy through ε_θ = −ν ε, ½ kToothLayerResidual·E ν² ε² V (some 1e-5 of it).
TEST(FourierToothLayer, CarriesItsSolidityAlongTheFace) {
  const SectionMesh s = layered_annulus();
  const Material m;
  const double E = m.youngs_modulus_Pa, nu = m.poisson_ratio, eps = 1e-3;
  const auto U = strain_energy_by_region_J(
      s, m,
      axisymmetric_field(s, [&](double r, double) { return -nu * eps * r; }, [](double, double) { return 0.0; },
                         [&](double, double z) { return eps * z; }));
  ASSERT_EQ(U.size(), static_cast<std::size_t>(kToothLayerRegion + 1));
  const double tube = 0.5 * E * eps * eps * kPi * (kR1 * kR1 - kR0 * kR0) * kL;
  const double layer = 0.5 * E * eps * eps *
                       (layer_volume_integral(solidity) +
                        fourier::kToothLayerResidual * nu * nu * layer_volume_integral([](double) { return 1.0; }));
  std::printf("stretched along the face: tube %.3e, layer %.9f of its closed form\n", U[0] / tube - 1,
              U[kToothLayerRegion] / layer);
  EXPECT_NEAR(U[0] / tube, 1.0, 1e-10);
  EXPECT_NEAR(U[kToothLayerRegion] / layer, 1.0, 1e-9);
}

// Twisted (u_θ = κ r z: the one shear γ_θz = κ r), sheared across the rim (u_θ = c r²: the one shear γ_rθ = c r) or
// grown (u_r = c: the one hoop term ε_θ = c/r), the tube carries its closed-form energy and the layer its solidity
// times the shear factor in twist, its solidity in γ_rθ and only the residual hoop modulus in growth. The first two
// fields are polynomials the section and the 7-point rule hold exactly (1e-10); 1/r is not: the rule's error on these
// cells is below 1e-6.
TEST(FourierToothLayer, ShearsAtItsSolidityAndCarriesNoHoop) {
  SectionMesh s = layered_annulus();
  s.tooth_layer->shear_factor = 0.4;
  const Material m;
  const double E = m.youngs_modulus_Pa, nu = m.poisson_ratio, G = E / (2 * (1 + nu)), kappa = 1e-2, c = 1e-6;
  const auto zero = [](double, double) { return 0.0; };
  const auto Ut = strain_energy_by_region_J(
      s, m, axisymmetric_field(s, zero, [&](double r, double z) { return kappa * r * z; }, zero));
  const auto phi_r2 = [](double r) { return solidity(r) * r * r; };
  EXPECT_NEAR(Ut[0] / (0.5 * G * kappa * kappa * kPi * (std::pow(kR1, 4) - std::pow(kR0, 4)) / 2 * kL), 1.0, 1e-10);
  EXPECT_NEAR(Ut[kToothLayerRegion] / (0.4 * 0.5 * G * kappa * kappa * layer_volume_integral(phi_r2)), 1.0, 1e-10);

  const auto Us = strain_energy_by_region_J(s, m, axisymmetric_field(s, zero, [&](double r, double) { return c * r * r; }, zero));
  EXPECT_NEAR(Us[kToothLayerRegion] / (0.5 * G * c * c * layer_volume_integral(phi_r2)), 1.0, 1e-10);

  const auto Ug = strain_energy_by_region_J(s, m, axisymmetric_field(s, [&](double, double) { return c; }, zero, zero));
  const double lambda = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = G;
  const auto hoop = [&](double r) { return c * c / (r * r); };
  EXPECT_NEAR(Ug[kToothLayerRegion] / (0.5 * E * layer_volume_integral(hoop)), fourier::kToothLayerResidual,
              1e-6 * fourier::kToothLayerResidual);
  const double tube = 0.5 * (lambda + 2 * mu) * c * c * 2 * kPi * kL * std::log(kR1 / kR0);
  EXPECT_NEAR(Ug[0] / tube, 1.0, 1e-6);
}

/// The default gear and flexspline with the rim's outside on the root circle, everything scaled by k (the drive
/// geometrically similar), meshed for the harmonic solver.
SectionMesh designed_section(double k = 1.0, double rim_offset_m = 0) {
  GearParams g;
  g.module_m *= k;
  FlexsplineParams f;
  f.teeth = TeethModel::Layer;
  f.inner_radius_m *= k;
  f.wall_thickness_m *= k;
  f.length_m *= k;
  f.rim_width_m *= k;
  f.diaphragm_thickness_m *= k;
  f.fillet_radius_m *= k;
  f.boss_radius_m *= k;
  f.rim_thickness_m = gear_radii(g).root_f - f.inner_radius_m + rim_offset_m;
  MeshParams mesh;
  mesh.size_m *= k;
  return mesh_flexspline_section(f, g, mesh);
}

ToothLayer designed_layer(double k, double rim_offset_m = 0) { return *designed_section(k, rim_offset_m).tooth_layer; }

// The designed section's layer: its triangles fill the rim's width from the root circle to the tip, the rim's outer
// surface (where the contact loads and reads) stays at the root circle, and ∫ φ dV over the layer is the teeth's
// volume, z_f times the tooth's area above the root circle (the outline polygon's shoelace area less the root disc)
// times the width: within 0.1 % (φ tabulated at 64 radii; measured 1.5e-4, the fillet's steep φ near the root).
TEST(FourierToothLayer, TheDesignedLayerHoldsTheTeethsArea) {
  const GearParams g;
  const GearRadii radii = gear_radii(g);
  const SectionMesh s = designed_section();
  ASSERT_TRUE(s.tooth_layer.has_value());
  double steel = 0, r_lo = 1, r_hi = 0;
  for (std::size_t e = 0; e < s.triangles.size(); ++e) {
    if (s.region[e] != kToothLayerRegion) continue;
    const fourier::Mat6x2 X = fourier::coords(s, e);
    for (int k = 0; k < 7; ++k) {
      const fourier::ShapePoint p = fourier::shape_point(X, fourier::kRule.xi[k], fourier::kRule.eta[k]);
      steel += 2 * kPi * fourier::kRule.w[k] * std::abs(p.det) * p.r * s.tooth_layer->at(p.r);
    }
    for (int a = 0; a < 6; ++a) r_lo = std::min(r_lo, X(a, 0)), r_hi = std::max(r_hi, X(a, 0));
  }
  EXPECT_NEAR(r_lo, radii.root_f, 1e-9);
  EXPECT_NEAR(r_hi, radii.tip_f, 1e-9);
  int rim_edges = 0;
  for (const SectionEdge& edge : s.edges) {
    if (edge.marker != kSurfaceRimOuter) continue;
    ++rim_edges;
    for (const int i : edge.nodes) EXPECT_NEAR(s.nodes(i, 0), radii.root_f, 1e-9);
  }
  EXPECT_GT(rim_edges, 0);
  const auto pts = flexspline_outline(g, 400);
  double polygon = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const auto& a = pts[i];
    const auto& b = pts[(i + 1) % pts.size()];
    polygon += 0.5 * (a.x() * b.y() - a.y() * b.x());
  }
  const double teeth = (polygon - kPi * radii.root_f * radii.root_f) * FlexsplineParams{}.rim_width_m;
  std::printf("the layer's steel over the teeth's volume: %.6f\n", steel / teeth);
  EXPECT_NEAR(steel / teeth, 1.0, 1e-3);
}

// The layer's shear factor is the rib cell's of the designed tooth: against the cell built here from the solidity at
// 512 rows and 64 cells across (the layer's 128 × 32 within 0.5 % of it: 1 %), the
// tooth read from just above the root circle, where the spaces' floor begins. A drive scaled as a whole keeps it (to
// 1e-9), and so does a rim whose outer radius misses the root circle by a rounding (1e-10 m, where the solidity
// jumps from 1 to the teeth's share; to 1e-3, the fillet's width growing as the square root of the height there).
TEST(FourierToothLayer, ItsShearIsTheRibCellsOfTheDesignedTooth) {
  const GearParams g;
  const FlexsplineParams f0;
  const GearRadii radii = gear_radii(g);
  const ToothLayer layer = designed_layer(1.0);
  RibCell cell;
  cell.pitch_m = 2 * kPi * radii.root_f / g.teeth_flexspline;
  cell.rim_thickness_m = radii.root_f - f0.inner_radius_m;
  cell.cells_across = 64;
  const double h = radii.tip_f - radii.root_f;
  for (int k = 0; k <= 512; ++k) {
    const double r = radii.root_f + h * std::max(k / 512.0, 1e-6);
    cell.height_m.push_back(h * k / 512.0);
    cell.width_m.push_back(std::min(cell.pitch_m, flexspline_solidity(g, r) * 2 * kPi * r / g.teeth_flexspline));
  }
  const double converged = rib_shear_factor(cell);
  std::printf("the designed layer's shear factor %.6f, the converged cell's %.6f\n", layer.shear_factor, converged);
  EXPECT_NEAR(layer.shear_factor / converged, 1.0, 1e-2);
  EXPECT_NEAR(designed_layer(1.3).shear_factor / layer.shear_factor, 1.0, 1e-9);
  EXPECT_NEAR(designed_layer(1.0, 1e-10).shear_factor / layer.shear_factor, 1.0, 1e-3);
  EXPECT_NEAR(designed_layer(1.0, -1e-10).shear_factor / layer.shear_factor, 1.0, 1e-3);
}

}  // namespace
}  // namespace sw
