// The harmonic (Fourier) solver against exact solutions: rigid modes of the harmonic element, tube torsion (harmonic
// 0) against T·L/(G·J), Lamé's thick cylinder, the regularity on the axis, the revolved grid, and the figures of a
// generator case (w0 reached, balanced loads, torque balance).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include <Eigen/Eigenvalues>

#include "fem/fourier_analysis.hpp"
#include "fem/fourier_element.hpp"
#include "fem/fourier_section.hpp"
#include "fem/fourier_solver.hpp"

namespace sw {
namespace {

constexpr double kPi = std::numbers::pi;

Eigen::Matrix<double, 6, 2> curved_triangle() {
  // A distorted, curved element away from the axis.
  Eigen::Matrix<double, 6, 2> X;
  X << 10e-3, 1e-3, 11.2e-3, 1.3e-3, 10.4e-3, 2.4e-3, 10.6e-3, 1.1e-3, 10.85e-3, 1.95e-3, 10.15e-3, 1.7e-3;
  return X;
}

// Rigid motions give no strain: n = 0 translation along z and rotation about z; n = 1 translation along x and
// rotation about y (u = z·e_x − x·e_z: a = z, b = −z, c = −r). Exactly 2 zero eigenvalues at n = 0 and n = 1, none at
// n = 2 (a body of revolution has 6 rigid modes: z-translation and z-rotation at n = 0, two each at n = 1 in the two
// families).
TEST(HarmonicElement, RigidModesAndRank) {
  const auto X = curved_triangle();
  Material m;
  const auto K0 = harmonic_element_stiffness(X, m, 0), K1 = harmonic_element_stiffness(X, m, 1),
             K2 = harmonic_element_stiffness(X, m, 2);
  Eigen::Matrix<double, 18, 1> tz = Eigen::Matrix<double, 18, 1>::Zero(), rz = tz, tx = tz, ry = tz;
  for (int i = 0; i < 6; ++i) {
    tz[3 * i + 2] = 1;
    rz[3 * i + 1] = X(i, 0);
    tx[3 * i] = 1;
    tx[3 * i + 1] = -1;
    ry[3 * i] = X(i, 1);
    ry[3 * i + 1] = -X(i, 1);
    ry[3 * i + 2] = -X(i, 0);
  }
  const double scale = K0.norm() * 1e-3;
  EXPECT_LT((K0 * tz).norm(), 1e-9 * scale);
  EXPECT_LT((K0 * rz).norm(), 1e-9 * scale);
  EXPECT_LT((K1 * tx).norm(), 1e-9 * scale);
  EXPECT_LT((K1 * ry).norm(), 1e-9 * scale);
  for (const auto& [K, zeros] : {std::pair{K0, 2}, std::pair{K1, 2}, std::pair{K2, 0}}) {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 18, 18>> eig(K);
    int count = 0;
    for (int k = 0; k < 18; ++k) count += std::abs(eig.eigenvalues()[k]) < 1e-10 * eig.eigenvalues().cwiseAbs().maxCoeff();
    EXPECT_EQ(count, zeros);
    EXPECT_GT(eig.eigenvalues().minCoeff(), -1e-10 * eig.eigenvalues().cwiseAbs().maxCoeff());
  }
}

FlexsplineModel plain_tube() {
  FlexsplineModel c;
  c.flexspline.shape = FlexsplineShape::Tube;
  c.flexspline.teeth = TeethModel::None;
  c.flexspline.inner_radius_m = 18.5e-3;
  c.flexspline.wall_thickness_m = 1.0e-3;
  c.flexspline.length_m = 30e-3;
  c.load.torque_Nm = 100.0;
  c.solver.method = SolverMethod::Fourier;
  c.solver.harmonics = 0;
  return c;
}

// The torsion field u_θ = T·z·r/(G·J) is quadratic: the quadratic section reproduces it exactly (up to round-off)
// under the exact end shear τ = T·r/J, on a coarse section. Tolerance 1e-8 (the issue's), and the reaction balances.
TEST(FourierTorsion, TubeExact) {
  const FlexsplineModel c = plain_tube();
  const FourierSolution s = analyse_flexspline_fourier(c);
  const auto& f = s.figures;
  std::printf("tube torsion: %zu section nodes, phi0 %.12e vs T·L/(G·J) %.12e (rel %.2e)\n", s.section.n_nodes(),
              f.phi0_rad, f.checks.phi0_theory_rad, f.phi0_rad / f.checks.phi0_theory_rad - 1);
  EXPECT_NEAR(f.phi0_rad / f.checks.phi0_theory_rad, 1.0, 1e-8);
  EXPECT_NEAR(f.checks.applied_torque_Nm, c.load.torque_Nm, 1e-9 * c.load.torque_Nm);
  EXPECT_NEAR(f.checks.reaction_torque_Nm, -c.load.torque_Nm, 1e-8 * c.load.torque_Nm);
  ASSERT_EQ(s.harmonics.size(), 1u);
  EXPECT_EQ(s.harmonics[0].n, 0);
}

// Lamé's thick cylinder under internal pressure p with free ends (σ_z = 0, the plane-stress field is the exact 3-D
// solution): u_r = [(1 − ν)·A·r + (1 + ν)·B/r]/E, A = p·r_i²/(r_o² − r_i²), B = A·r_o²; u_z = −2ν·A·z/E.
// Harmonic 0, symmetric family; supports: b everywhere (the torsion dof, unloaded) and c at one node on z = 0
// (rigid z). The 1/r part is approximated: a thick wall (r_o = 2 r_i) on 8 × 8 cells must be within 2e-3 at every
// node, u_r and u_z (the tet10 check: 0.5 % on u_r(r_i); measured 1.2e-3, 1.7e-4 on 16 × 16), and halving the cells
// must divide the error by at least 4 (second order or better; measured 6.8).
double lame_worst_error(int cells) {
  const double ri = 10e-3, ro = 20e-3, L = 10e-3, p = 100e6;
  Material m;
  const SectionMesh s = mesh_annulus_section(ri, ro, L, cells, cells);
  std::vector<bool> fixed(3 * s.n_nodes(), false);
  for (std::size_t i = 0; i < s.n_nodes(); ++i) fixed[3 * i + 1] = true;
  fixed[2] = true;  // node 0 is (r_i, 0)
  const Eigen::MatrixXd F = 2 * kPi * section_traction_load(s, kSurfaceInner, Eigen::Vector3d(p, 0, 0));
  const Eigen::MatrixXd U = solve_harmonic(s, m, 0, fixed, F);
  const double A = p * ri * ri / (ro * ro - ri * ri), B = A * ro * ro, E = m.youngs_modulus_Pa, nu = m.poisson_ratio;
  double worst = 0;
  for (Eigen::Index i = 0; i < static_cast<Eigen::Index>(s.n_nodes()); ++i) {
    const double r = s.nodes(i, 0), z = s.nodes(i, 1);
    worst = std::max(worst, std::abs(U(i, 0) / (((1 - nu) * A * r + (1 + nu) * B / r) / E) - 1));
    worst = std::max(worst, std::abs(U(i, 2) - (-2 * nu * A * z / E)) / (2 * nu * A * L / E));
  }
  std::printf("Lame (fourier, %d x %d cells): worst nodal error %.2e\n", cells, cells, worst);
  return worst;
}

TEST(FourierLame, ThickCylinder) {
  const double coarse = lame_worst_error(8), fine = lame_worst_error(16);
  EXPECT_LT(coarse, 2e-3);
  EXPECT_GT(coarse / fine, 4.0);
}

// The strain energy of one harmonic (harmonic_strain_energy_J, what the flexspline's material damping dissipates a
// part of per wave cycle) against the thin ring's closed form: a free ring of mean radius R, square section t × t,
// under a radial traction p·cos nθ on its outside (force per unit arc of the mean line q = p·t·r_o/R) deforms
// inextensibly, w_n = q·R⁴/(E·I·(n² − 1)²), I = t⁴/12, and stores U = π·R·q·w_n/2 (Clapeyron; the bending energy
// E·I·π·(n² − 1)²·w_n²/(2R³) is the same). t/R = 1/20: shear, stretching and the curved section's stress move it by
// O((t/R)²), so 1 %. The same U from the solver's loads, ½ Fᵀu, to 1e-8 (the solve's round-off on a ring whose
// bending is (t/R)² of its stretching: 1.1e-9 at n = 2): the energy's element stiffness is the solver's.
TEST(FourierStrainEnergy, ThinRingHarmonicAgainstClosedForm) {
  const double R = 20e-3, t = 1e-3, p = 1e6;
  Material m;
  const SectionMesh s = mesh_annulus_section(R - t / 2, R + t / 2, t, 4, 4);
  const std::vector<bool> fixed(3 * s.n_nodes(), false);  // n >= 2: no rigid mode
  for (const int n : {2, 4}) {
    const Eigen::MatrixXd F = kPi * section_traction_load(s, kSurfaceOuter, Eigen::Vector3d(p, 0, 0));
    HarmonicField u;
    u.sym.assign(static_cast<std::size_t>(n + 1), Eigen::MatrixXd());
    u.anti = u.sym;
    u.sym[static_cast<std::size_t>(n)] = solve_harmonic(s, m, n, fixed, F);
    const std::vector<double> U = harmonic_strain_energy_J(s, m, u);
    ASSERT_EQ(U.size(), static_cast<std::size_t>(n + 1));
    for (int k = 0; k < n; ++k) EXPECT_EQ(U[static_cast<std::size_t>(k)], 0.0);
    const double q = p * t * (R + t / 2) / R, I = t * t * t * t / 12;
    const double w = q * std::pow(R, 4) / (m.youngs_modulus_Pa * I * (n * n - 1.0) * (n * n - 1.0));
    const double closed = kPi * R * q * w / 2, energy = U[static_cast<std::size_t>(n)];
    const double work = 0.5 * (F.array() * u.sym[static_cast<std::size_t>(n)].array()).sum();
    std::printf("ring n = %d: U %.6e J, closed form %.6e (%+.3f %%), 1/2 F.u %.6e\n", n, energy, closed,
                100 * (energy / closed - 1), work);
    EXPECT_NEAR(energy / closed, 1.0, 1e-2) << "n = " << n;
    EXPECT_NEAR(energy / work, 1.0, 1e-8) << "n = " << n;
  }
}

// The cup's boss reaches the axis: the regularity conditions must keep every harmonic well posed (a singular or
// indefinite matrix throws) and the axis displacement single-valued: at n = 1, b = −a.
TEST(FourierAxis, CupBossWithEveryHarmonic) {
  FlexsplineModel c;
  c.flexspline.shape = FlexsplineShape::Cup;
  c.flexspline.teeth = TeethModel::None;
  c.flexspline.length_m = 14.7e-3;
  c.flexspline.diaphragm_thickness_m = 1.5e-3;
  c.flexspline.boss_radius_m = 10e-3;
  c.mesh.size_m = 1e-3;
  c.mesh.wall_layers = 1;
  c.load.torque_Nm = 10;
  WaveGeneratorParams w;
  const GivenForces given{{{0.3, 1.0}, {2.0, 0.5}, {4.0, 0.7}}};  // no symmetry: every harmonic and both families
  w.model = given;
  w.force_N = 100;
  c.wave_generator = w;
  c.solver.method = SolverMethod::Fourier;
  c.solver.harmonics = 6;
  const FourierSolution s = analyse_flexspline_fourier(c);
  EXPECT_EQ(s.harmonics.size(), 7u);
  for (std::size_t i = 0; i < s.section.n_nodes(); ++i) {
    if (s.section.nodes(static_cast<Eigen::Index>(i), 0) > 1e-12) continue;
    for (const auto* fam : {&s.generator.sym, &s.generator.anti}) {
      EXPECT_DOUBLE_EQ((*fam)[1](i, 1), -(*fam)[1](i, 0));
      EXPECT_EQ((*fam)[1](i, 2), 0.0);
      for (int n : {0, 2, 3}) EXPECT_EQ((*fam)[n](i, 0), 0.0);
    }
  }
  // The loads' resultant is what the forces add up to (weights × force scale along their directions).
  Eigen::Vector3d expect = Eigen::Vector3d::Zero();
  double at_end = 0;
  for (const auto& f : given.forces) if (std::abs(std::remainder(f.angle_rad, 2 * kPi)) < kPi / 2) at_end += f.weight;
  const double scale = w.force_N / at_end;
  for (const auto& f : given.forces) {
    // A patch ±3° wide: its resultant is the weight times sin(3°)/(3°) along the patch's centre direction.
    const double h = 3.0 * kPi / 180, k = std::sin(h) / h;
    expect += scale * f.weight * k * Eigen::Vector3d(std::cos(f.angle_rad), std::sin(f.angle_rad), 0);
  }
  EXPECT_LT((s.figures.checks.generator_net_force - expect).norm(), 1e-9 * expect.norm());
}

// The revolved grid: its straight-edged TET10 volume approaches 2π ∫ r dA from below by the chord error of the
// sectors, the grid's displacement at a node equals the series there, and the torque case's stress at a node is the
// exact torsion shear τ_θz = T·r/J turned to the node's angle (σ_xz = −τ·sin θ, σ_yz = τ·cos θ, the rest 0; the
// quadratic section reproduces torsion exactly, so to round-off: 1e-6 of τ).
TEST(FourierGrid, RevolvedVolumeAndValues) {
  FlexsplineModel c = plain_tube();
  c.solver.harmonics = 4;
  WaveGeneratorParams w;
  w.model = FourForce{};
  w.radial_deformation_m = 0.1e-3;
  c.wave_generator = w;
  const int sectors = 48;
  const FourierSolution s = analyse_flexspline_fourier(c);
  const TetMesh g = fourier::revolve_section(s.section, sectors);
  const std::vector<LoadCaseSolution> cases = revolved_load_cases(s, c.material, sectors);
  ASSERT_EQ(cases.size(), 3u);
  double vol = 0;
  for (const auto& t : g.tets) {
    const Eigen::Vector3d p0 = g.nodes.row(t[0]), p1 = g.nodes.row(t[1]), p2 = g.nodes.row(t[2]), p3 = g.nodes.row(t[3]);
    const double v = (p1 - p0).cross(p2 - p0).dot(p3 - p0) / 6;
    ASSERT_GT(v, 0);
    vol += v;
  }
  const auto& f = c.flexspline;
  const double ro = f.inner_radius_m + f.wall_thickness_m;
  const double exact = kPi * (ro * ro - f.inner_radius_m * f.inner_radius_m) * f.length_m;
  // Each sector is the section swept along chords: volume sin(Δθ)·∫ r dA, Δθ = 2π / sectors.
  const double chord = std::sin(2 * kPi / sectors) / (2 * kPi / sectors);
  EXPECT_NEAR(vol / exact, chord, 1e-9);
  // Node 7 of the section at station 5.
  const int node = 7, station = 5;
  const double t = kPi * station / sectors;
  const long id = static_cast<long>(station) * static_cast<long>(s.section.n_nodes()) + node;
  const auto [e, q] = locate_in_section(s.section, s.section.nodes.row(node).transpose());
  ASSERT_GE(e, 0);
  const Eigen::Vector3d cyl = s.generator.displacement(s.section, e, q, t);
  const Eigen::Vector3d cart(cyl[0] * std::cos(t) - cyl[1] * std::sin(t), cyl[0] * std::sin(t) + cyl[1] * std::cos(t),
                             cyl[2]);
  ASSERT_EQ(cases.front().name, "generator");
  EXPECT_LT((cases.front().u.segment<3>(3 * id) - cart).norm(), 1e-12 * cart.norm() + 1e-18);

  const LoadCaseSolution& torque = cases[1];
  ASSERT_EQ(torque.name, "torque");
  const double r = s.section.nodes(node, 0);
  const double tau = c.load.torque_Nm * r / (kPi / 2 * (std::pow(ro, 4) - std::pow(f.inner_radius_m, 4)));
  Eigen::Matrix<double, 1, 6> exact_stress;  // xx yy zz yz xz xy
  exact_stress << 0, 0, 0, tau * std::cos(t), -tau * std::sin(t), 0;
  EXPECT_LT((torque.stress.row(id) - exact_stress).norm(), 1e-6 * tau);
  // The combined case is the two added (linear: to round-off).
  ASSERT_EQ(cases[2].name, "generator_torque");
  EXPECT_LE((cases[2].u - cases[0].u - cases[1].u).lpNorm<Eigen::Infinity>(), 1e-12 * cases[0].u.lpNorm<Eigen::Infinity>());
  EXPECT_LE((cases[2].stress - cases[0].stress - cases[1].stress).lpNorm<Eigen::Infinity>(),
            1e-12 * cases[0].stress.lpNorm<Eigen::Infinity>());
}

// The cam in unilateral contact on the harmonic basis: the generator pushes only (every station force ≥ 0), touches
// where the cam stands out to the bore (w at the major axis = w0 within the contact stations' hat averaging), lifts off
// at the minor axis; the torque case balances (clamp + generator reaction = −applied, 1e-9), and the station forces sum
// to the total radial force (each pair's unit load is 1 N of normal force at each of its two stations).
TEST(FourierCam, UnilateralContactBalances) {
  FlexsplineModel c = plain_tube();
  c.solver.harmonics = 48;
  c.load.torque_Nm = 20;
  WaveGeneratorParams w;
  w.model = Cam{};
  w.radial_deformation_m = 0.1e-3;
  c.wave_generator = w;
  const FourierSolution s = analyse_flexspline_fourier(c);
  ASSERT_TRUE(s.figures.generator.has_value());
  const auto& g = *s.figures.generator;
  EXPECT_TRUE(g.unilateral);
  EXPECT_EQ(g.model, "cam");
  double sum = 0;
  for (double p : g.force_wg_N) {
    EXPECT_GE(p, 0.0);
    sum += 2 * p;
  }
  // The normal is tilted by the cam's slope (≤ 2·w0/r = 0.01): its radial part is ≥ 0.99995 of the force.
  EXPECT_NEAR(g.total_radial_force_N / sum, 1.0, 1e-4);
  EXPECT_GT(g.w_major_m, 0.9 * *w.radial_deformation_m);
  EXPECT_LT(g.w_major_m, 1.02 * *w.radial_deformation_m);  // measured 1.0105·w0: the gap is held hat-averaged
  EXPECT_LT(g.w_minor_m, -0.5 * *w.radial_deformation_m);
  ASSERT_EQ(g.zones_wg_deg.size(), 2u);
  EXPECT_LT(g.zones_wg_deg[0].first, -10.0);
  EXPECT_GT(g.zones_wg_deg[0].second, 10.0);
  EXPECT_NEAR(s.figures.checks.reaction_torque_Nm, -s.figures.checks.applied_torque_Nm,
              1e-9 * std::abs(c.load.torque_Nm));
}

}  // namespace
}  // namespace sw
