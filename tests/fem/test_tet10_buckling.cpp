// Torsion buckling on the TET10 model (fem/tet10_buckling.hpp): a thin tube clamped at z = 0 under the torque case's
// end shear, against CalculiX *BUCKLE on the identical mesh, clamp and nodal loads (the deck of io/inp.hpp), and
// against the harmonic solver (fem/fourier_buckling.hpp) on its own section; the geometric stiffness's symmetry and
// its null space; the error paths.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "fem/elasticity.hpp"
#include "fem/flexspline_analysis.hpp"
#include "fem/flexspline_system.hpp"
#include "fem/fourier_analysis.hpp"
#include "fem/fourier_buckling.hpp"
#include "fem/fourier_section.hpp"
#include "fem/fourier_solver.hpp"
#include "fem/tet10_buckling.hpp"
#include "io/case.hpp"
#include "io/inp.hpp"
#include "mesh/flexspline.hpp"

namespace sw {
namespace {

namespace fs = std::filesystem;

/// A plain tube (no teeth, no generator) of inner radius ri, wall t, length L; the torque case's 1 N·m on its open
/// end (the exact torsion shear), the clamp at z = 0. TET10 edges `size_m` along the wall, `layers` through it.
FlexsplineModel tube_model(double ri, double t, double L, double size_m, int layers) {
  FlexsplineModel c;
  c.flexspline.shape = FlexsplineShape::Tube;
  c.flexspline.teeth = TeethModel::None;
  c.flexspline.inner_radius_m = ri;
  c.flexspline.wall_thickness_m = t;
  c.flexspline.length_m = L;
  c.flexspline.rim_width_m = 0.0;
  c.load.torque_Nm = 1.0;
  c.mesh.size_m = size_m;
  c.mesh.wall_layers = layers;
  return c;
}

// The tube of tests (1) and (2): R/t = 15 (ri = 14.5 mm, t = 1 mm), L = 2R = 30 mm, steel (E = 210 GPa, ν = 0.3):
// thin enough to buckle as a shell (a few circumferential waves), thick enough that a 1-layer TET10 mesh at 2 mm
// stays small (the ccx run takes seconds).
constexpr double kInner = 14.5e-3, kWall = 1e-3, kLength = 30e-3;

struct TubeRun {
  FlexsplineModel c;
  TetMesh mesh;
  FlexsplineSystem system;
  BucklingResultTet10 buckling;
};

/// The tube meshed and factorised; its `modes` smallest |λ| under the torque case when `modes` > 0.
TubeRun run_tube(double size_m, int layers, int modes = 2) {
  TubeRun r;
  r.c = tube_model(kInner, kWall, kLength, size_m, layers);
  r.mesh = mesh_flexspline(r.c.flexspline, r.c.gear, r.c.mesh);
  r.system = assemble_and_factorise(r.c, r.mesh);
  if (modes == 0) return r;
  Tet10BucklingOptions o;
  o.modes = modes;
  r.buckling = torsion_buckling_tet10(r.c, r.mesh, r.system, false, o);
  return r;
}

// An eigenpair converged to Spectra's 1e-9 on μ leaves an energy residual of the same order; 1e-6 is far from both
// round-off and an unconverged pair (measured 5e-13).
constexpr double kConvergedResidual = 1e-6;

/// The 2 mm / 1 layer tube of tests (1) and (2), solved once for its four smallest |λ| (the pair of each sign).
const TubeRun& coarse_tube() {
  static const TubeRun r = run_tube(2e-3, 1, 4);
  return r;
}

/// The smallest |λ| of a result.
double lowest(const BucklingResultTet10& b) { return std::abs(b.load_factors.front()); }

/// Path of `name` on PATH, empty if absent.
std::string on_path(const std::string& name) {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "/usr/bin:/bin");
  for (std::string dir; std::getline(dirs, dir, ':');)
    if (!dir.empty() && access((fs::path(dir) / name).c_str(), X_OK) == 0) return (fs::path(dir) / name).string();
  return {};
}

/// The buckling factors ccx writes to its .dat ("B U C K L I N G   F A C T O R   O U T P U T", then "mode factor"
/// lines).
std::vector<double> read_buckling_factors(const fs::path& dat) {
  std::ifstream in(dat);
  std::vector<double> factors;
  bool in_block = false;
  for (std::string line; std::getline(in, line);) {
    if (line.find("B U C K L I N G") != std::string::npos) {
      in_block = true;
      continue;
    }
    if (!in_block) continue;
    std::istringstream ls(line);
    int mode = 0;
    double factor = 0;
    if (ls >> mode >> factor) factors.push_back(factor);
  }
  return factors;
}

/// The case's deck (io/inp.hpp: nodes, C3D10, clamp, material, the torque's nodal loads) with its *STATIC step turned
/// into *BUCKLE for four factors at ARPACK accuracy 1e-7, run by ccx in a fresh directory; the factors it reports
/// (ccx lists the positive ones). Four, not two: the lowest factor is a pair (the mode turned by a quarter wave), and
/// asked for two ccx returned one of the pair and the next factor (3142.02, 3606.66); at its default accuracy 0.01
/// its first factor was 4.8e-4 high.
std::vector<double> ccx_buckling(const std::string& ccx, const TubeRun& r) {
  const fs::path dir = fs::temp_directory_path() / ("sw_tet10_buckling_" + std::to_string(getpid()));
  fs::create_directories(dir);
  Case deck_case;
  deck_case.path = "test_tet10_buckling";
  deck_case.stem = "tube";
  deck_case.material = r.c.material;
  write_inp_deck(dir / "static.inp", deck_case, r.mesh, r.system.clamped,
                 torque_load_vector(r.c, r.mesh, r.c.load.torque_Nm), "test_tet10_buckling");
  std::ifstream in(dir / "static.inp");
  std::stringstream text;
  text << in.rdbuf();
  std::string deck = text.str();
  const std::size_t at = deck.find("*STATIC\n");
  EXPECT_NE(at, std::string::npos);
  deck.replace(at, 8, "*BUCKLE\n4,1e-7\n");
  std::ofstream(dir / "job.inp") << deck;
  const std::string cmd = "cd '" + dir.string() + "' && OMP_NUM_THREADS=1 '" + ccx + "' -i job > ccx.log 2>&1";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << "see " << (dir / "ccx.log");
  const std::vector<double> factors = read_buckling_factors(dir / "job.dat");
  if (!factors.empty()) fs::remove_all(dir);
  return factors;
}

// (1) The same element (C3D10: VTK's and CalculiX's node orders agree), the same mesh, clamp and nodal loads, the same
// 4-point rule for K and for the Gauss-point stresses of K_σ: the two codes solve the same discrete eigenproblem, so
// only the eigen solvers' tolerances (Spectra 1e-9 here, ARPACK 1e-7 in the deck) and ccx's printed digits (6
// significant: 1.6e-6 relative at 3142) differ. 1e-5 holds that with a margin of 6; the 1 % target is the
// bound for a comparison that differs in stress recovery, which this one does not. Measured: 7e-8 on both factors
// (the pair of modes a quarter wave apart, 3141.99 and 3142.02 N·m per N·m).
constexpr double kSameDiscreteProblem = 1e-5;

TEST(Tet10Buckling, ThinTubeInTorsionMatchesCalculixBuckleOnTheSameMesh) {
  const std::string ccx = on_path("ccx");
  if (ccx.empty()) GTEST_SKIP() << "ccx (CalculiX, Debian calculix-ccx) is not on PATH: no reference to compare with";
  const TubeRun& r = coarse_tube();
  const std::vector<double> factors = ccx_buckling(ccx, r);
  ASSERT_FALSE(factors.empty()) << "ccx wrote no buckling factor";
  ASSERT_GE(factors.size(), 2u);
  std::vector<double> positive;
  for (const double l : r.buckling.load_factors)
    if (l > 0) positive.push_back(l);
  std::sort(positive.begin(), positive.end());
  ASSERT_GE(positive.size(), 2u) << "torsion buckles both ways: two of the four smallest |λ| are positive";
  std::printf("tube %zu nodes: tet10 lambda %.8g, %.8g, %.8g, %.8g; ccx %.8g, %.8g (%+.1e, %+.1e)\n", r.mesh.n_nodes(),
              r.buckling.load_factors[0], r.buckling.load_factors[1], r.buckling.load_factors[2],
              r.buckling.load_factors[3], factors[0], factors[1], factors[0] / positive[0] - 1,
              factors[1] / positive[1] - 1);
  for (int k = 0; k < 2; ++k) EXPECT_NEAR(factors[k] / positive[k], 1.0, kSameDiscreteProblem) << "factor " << k + 1;
  for (const double res : r.buckling.residuals) EXPECT_LT(res, kConvergedResidual);
}

// (2) The harmonic solver on its own section of the same tube (6-node triangles, exact in θ per harmonic; 4 layers
// × 120 cells, converged far below the TET10 meshes' error) with the same clamp and the torque case's harmonic 0 as
// prestress (a plain tube's end shear is axisymmetric, so that is all of it): the same continuum, and the TET10 load
// factor converges to it from above as the mesh is refined (stiffer coarse quadratic tets in the wall's bending).
// Measured: 2 mm / 1 layer (18.6k nodes) +1.03 %, 1 mm / 1 layer (36.6k) +0.51 %, 1 mm / 2 layers (117k) +0.16 %,
// all at n = 3. The issue asks 2 % on a comparable mesh: held on the 2 mm mesh of test (1); the 1 mm mesh must halve
// the error (1 %, measured 0.51 %), which a K_σ with a wrong term would not do.
constexpr double kHarmonicAgreement = 0.02;
constexpr double kHarmonicAgreementRefined = 0.01;

TEST(Tet10Buckling, ThinTubeInTorsionAgreesWithTheHarmonicSolver) {
  FlexsplineModel cf = tube_model(kInner, kWall, kLength, 0.5e-3, 2);
  cf.solver.method = SolverMethod::Fourier;
  cf.solver.harmonics = 0;
  const FourierSolution s = analyse_section_fourier(cf, mesh_annulus_section(kInner, kInner + kWall, kLength, 4, 120));
  const BucklingResult f = torsion_buckling_fourier(cf, s);
  const TubeRun& coarse = coarse_tube();
  const TubeRun fine = run_tube(1e-3, 1);
  const double e_coarse = lowest(coarse.buckling) / f.load_factor - 1, e_fine = lowest(fine.buckling) / f.load_factor - 1;
  std::printf("fourier %.6g (n = %d); tet10 2 mm / 1 layer %.6g (%+.2e), 1 mm / 1 layer %.6g (%+.2e)\n",
              f.load_factor, f.n, lowest(coarse.buckling), e_coarse, lowest(fine.buckling), e_fine);
  EXPECT_LT(std::abs(e_coarse), kHarmonicAgreement);
  EXPECT_LT(std::abs(e_fine), kHarmonicAgreementRefined);
  EXPECT_LT(std::abs(e_fine), std::abs(e_coarse));
}

// The generator as a support: its stations all round held radially (fem/tet10_buckling.hpp's constrained inverse).
// The modes must meet the constraints (Lᵀ·x = 0 to the solves' round-off; 1e-9 of the patterns' size is far above
// round-off and far below a violated hold, whose Lᵀ·x is of order ‖L‖·‖x‖/√m) and the load factor must rise, the held
// band taking away the open end's ovalisation. Measured on the 2 mm tube with a four-force generator's band (60
// stations, 3 mm from the open end): λ 3142 free, 6474 held; Lᵀ·x at 6e-17 of ‖L‖·‖x‖.
constexpr double kHeldToRoundOff = 1e-9;

TEST(Tet10Buckling, GeneratorStationsHeldRadiallyAreMetByTheModesAndRaiseTheLoadFactor) {
  TubeRun r = run_tube(2e-3, 1, 0);
  r.c.wave_generator = WaveGeneratorParams{};
  r.c.wave_generator->radial_deformation_m = 0.2e-3;
  Tet10BucklingOptions o;
  o.modes = 2;
  const BucklingResultTet10 held = torsion_buckling_tet10(r.c, r.mesh, r.system, true, o);
  const Eigen::SparseMatrix<double> L = generator_radial_holds(r.c, r.mesh);
  ASSERT_GT(L.cols(), 0);
  std::printf("held: %zu stations, lambda %.6g, %.6g (residuals %.1e, %.1e, |L^T x| / |L| |x| %.1e); free %.6g\n",
              static_cast<std::size_t>(L.cols()), held.load_factors[0], held.load_factors[1], held.residuals[0],
              held.residuals[1],
              Eigen::VectorXd(L.transpose() * held.modes[0]).norm() / (L.norm() * held.modes[0].norm()),
              lowest(coarse_tube().buckling));
  for (std::size_t k = 0; k < held.modes.size(); ++k) {
    EXPECT_LT(Eigen::VectorXd(L.transpose() * held.modes[k]).norm(), kHeldToRoundOff * L.norm() * held.modes[k].norm())
        << "mode " << k + 1;
    EXPECT_LT(held.residuals[k], kConvergedResidual);
  }
  EXPECT_GT(std::abs(held.load_factors[0]), lowest(coarse_tube().buckling));
}

// A base state (the generator's deformation in the drive) enters as its stress's geometric stiffness added to K. A base
// that is a times the torque case itself turns the pencil into (K + (a + λ)·K_σ)·x = 0, so each load factor drops by
// a exactly: through the sum of the two matrices, its new factorisation and the pencil on it. Held to the Lanczos
// tolerance (1e-9 on μ; 1e-7 of λ leaves a margin of 100).
constexpr double kShiftedExactly = 1e-7;

TEST(Tet10Buckling, ABaseStateOfTheTorqueItselfShiftsEveryFactorByItsMultiple) {
  const TubeRun& r = coarse_tube();
  const Eigen::VectorXd u = r.system.solve(torque_load_vector(r.c, r.mesh, r.c.load.torque_Nm)).col(0);
  const double a = 0.4 * lowest(r.buckling);
  Tet10BucklingOptions o;
  o.modes = 4;
  const BucklingResultTet10 shifted = torsion_buckling_tet10(r.c, r.mesh, r.system, false, o, a * u);
  // The positive pair (the mode and its quarter-wave turn) moves down by a; the negative one moves away, so other
  // modes take its place among the smallest |λ|: compare the two smallest positive factors.
  const auto positive = [](const std::vector<double>& l) {
    std::vector<double> p;
    for (const double x : l)
      if (x > 0) p.push_back(x);
    std::sort(p.begin(), p.end());
    return p;
  };
  const std::vector<double> before = positive(r.buckling.load_factors), after = positive(shifted.load_factors);
  ASSERT_GE(before.size(), 2u);
  ASSERT_GE(after.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    std::printf("lambda %.8g with no base, %.8g on a base of %.6g x the torque (%+.1e)\n", before[k], after[k], a,
                (after[k] - (before[k] - a)) / std::abs(before[k]));
    EXPECT_NEAR(after[k], before[k] - a, kShiftedExactly * std::abs(before[k])) << k;
  }
}

/// A dof map with no dof fixed.
DofMap all_free(const TetMesh& mesh) { return make_dof_map(std::vector<bool>(3 * mesh.n_nodes(), false)); }

/// The volume of a mesh by the elements' 4-point rule (tet10_volume), the rule K_σ is integrated with: on curved
/// elements it differs from the exact volume (mesh/tetgen_mesh.hpp mesh_volume) by the rule's error in det J.
double rule_volume(const TetMesh& mesh) {
  double v = 0;
  for (std::size_t e = 0; e < mesh.tets.size(); ++e) v += tet10_volume(element_coordinates(mesh, e));
  return v;
}

// (3) K_σ is symmetric (its blocks are ∇N_aᵀ·σ⁰·∇N_b with σ⁰ symmetric), and a rigid translation has no
// displacement gradient, so K_σ·t = 0 for every prestress (row sums Σ_b ∇N_b = ∇1 = 0). Round-off only: 1e-12 of the
// matrix's size. The prestress is the tube's torque case.
constexpr double kRoundOff = 1e-12;

TEST(GeometricStiffness, IsSymmetricAndLeavesARigidTranslationWithoutForce) {
  const TubeRun r = run_tube(2e-3, 1, 0);
  const Eigen::VectorXd u = r.system.solve(torque_load_vector(r.c, r.mesh, 1.0)).col(0);
  const DofMap dofs = all_free(r.mesh);
  const Eigen::SparseMatrix<double> Ks = geometric_stiffness(r.mesh, r.c.material, dofs, u);
  const double size = Ks.norm();
  ASSERT_GT(size, 0.0);
  EXPECT_LT((Ks - Eigen::SparseMatrix<double>(Ks.transpose())).norm(), kRoundOff * size);
  for (int k = 0; k < 3; ++k) {
    Eigen::VectorXd t = Eigen::VectorXd::Zero(dofs.n_equations);
    for (std::size_t i = 0; i < r.mesh.n_nodes(); ++i) t[static_cast<Eigen::Index>(3 * i) + k] = 1.0;
    EXPECT_LT((Ks * t).norm(), kRoundOff * size * t.norm()) << "translation along axis " << k;
  }
}

// xᵀ·K_σ·x by hand: a uniaxial prestress σ_xx = E·ε (u⁰ = ε·(x, −ν·y, −ν·z), every other stress 0) and the field
// x_y = a·X (a uniform shear of the y component along x) give ∫ σ_ij x_k,i x_k,j dV = σ_xx·a²·V. Both fields are
// linear, which the quadratic element reproduces exactly and the Gauss rule integrates exactly (the integrand is
// constant): the two agree to round-off, on the curved tube mesh as on any.
TEST(GeometricStiffness, GivesTheWorkOfAUniaxialPrestressOnAShearField) {
  const FlexsplineModel c = tube_model(kInner, kWall, 10e-3, 2e-3, 1);
  const TetMesh mesh = mesh_flexspline(c.flexspline, c.gear, c.mesh);
  const double eps = 1e-4, a = 1e-3, nu = c.material.poisson_ratio;
  Eigen::VectorXd u0(3 * mesh.n_nodes()), x = Eigen::VectorXd::Zero(3 * mesh.n_nodes());
  for (std::size_t i = 0; i < mesh.n_nodes(); ++i) {
    const auto p = mesh.nodes.row(static_cast<Eigen::Index>(i));
    u0.segment<3>(static_cast<Eigen::Index>(3 * i)) << eps * p[0], -nu * eps * p[1], -nu * eps * p[2];
    x[static_cast<Eigen::Index>(3 * i) + 1] = a * p[0];
  }
  const Eigen::SparseMatrix<double> Ks = geometric_stiffness(mesh, c.material, all_free(mesh), u0);
  const double by_hand = c.material.youngs_modulus_Pa * eps * a * a * rule_volume(mesh);
  EXPECT_NEAR(x.dot(Ks * x) / by_hand, 1.0, 1e-10);
}

TEST(Tet10Buckling, RejectsMismatchedSizesAndOptionsAndAMissingGenerator) {
  const TubeRun r = run_tube(2e-3, 1, 0);
  const SymmetricCsc K = assemble_stiffness(r.mesh, r.c.material, r.system.dofs);
  const Eigen::VectorXd u = r.system.solve(torque_load_vector(r.c, r.mesh, 1.0)).col(0);
  auto message = [](const std::function<void()>& f) {
    try {
      f();
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no InputError");
  };
  EXPECT_NE(message([&] { geometric_stiffness(r.mesh, r.c.material, r.system.dofs, u.head(10)); })
                .find("prestress displacement has 10 entries"),
            std::string::npos);
  Tet10BucklingOptions o;
  o.modes = 0;
  EXPECT_NE(message([&] { buckling_tet10(r.mesh, r.c.material, r.system.dofs, K, *r.system.factor, u, o); })
                .find("buckling.modes = 0"),
            std::string::npos);
  EXPECT_NE(message([&] {
              buckling_tet10(r.mesh, r.c.material, r.system.dofs, K, *r.system.factor,
                             Eigen::VectorXd::Zero(u.size()));
            }).find("geometric stiffness is zero"),
            std::string::npos);
  EXPECT_NE(message([&] { torsion_buckling_tet10(r.c, r.mesh, r.system, true); }).find("no [wave_generator]"),
            std::string::npos);
}

}  // namespace
}  // namespace sw
