// The loaded contact on the harmonic solver against the same contact on TET10, on the shipped seed cup and the
// designed size-17 cup at their default settings (the case's mesh; harmonics by default_harmonics): the drive's curve,
// its three segments, the flank forces and the generator's zones; one circulant block against TET10 half solves; the
// harmonic count the flank patterns need.
#include <cmath>
#include <algorithm>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <tuple>

#include <gtest/gtest.h>

#include "app/contact_job.hpp"
#include "contact/harmonic_body.hpp"
#include "contact/loaded_contact.hpp"
#include "contact/tet10_body.hpp"
#include "fem/flexspline_analysis.hpp"
#include "fem/fourier_analysis.hpp"
#include "fem/fourier_solver.hpp"
#include "io/case.hpp"
#include "mesh/flexspline.hpp"

namespace sw {
namespace {

constexpr double kArcmin = 10800.0 / M_PI;

/// A case solved both ways, with the contact on each.
struct BothWays {
  Case c;
  std::unique_ptr<TetMesh> mesh;
  std::unique_ptr<FlexsplineSystem> system;
  FlexsplineSolution tet10_fem;
  std::unique_ptr<FourierSolution> fourier;
  ContactAnalysis tet10, harmonic;
  ContactAnalysis harmonic_own;  ///< on the harmonic solver's own FEM readout (its rim as the generator leaves it)
};

/// The contact's options as `contact` takes them from the case (app::contact_options), searching for the ratcheting
/// torque twice as far as the datasheet looks: the designed size 17 ratchets at 113 x rated with each section of the
/// face letting go on its own (3500 N·m), so both bodies reach it and the comparison below is made.
ContactOptions options_of(const Case& c) {
  ContactOptions o = app::contact_options(c, app::series_parts(c));
  o.ratcheting_ceiling_Nm = 200 * o.rated_torque_Nm;
  return o;
}

const BothWays& both_ways(const std::string& path) {
  static std::map<std::string, std::unique_ptr<BothWays>> solved;
  auto& s = solved[path];
  if (s) return *s;
  s = std::make_unique<BothWays>();
  // The two bodies of one idealisation: the bare rim (TET10 meshes no tooth layer; the layer's own checks are
  // tests/fem/test_tooth_layer.cpp).
  s->c = load_case(path);
  if (s->c.flexspline.teeth == TeethModel::Layer) s->c.flexspline.teeth = TeethModel::None;
  const FlexsplineModel m = flexspline_model(s->c);
  const ContactOptions o = options_of(s->c);
  s->mesh = std::make_unique<TetMesh>(mesh_flexspline(s->c.flexspline, s->c.gear, s->c.mesh));
  s->system = std::make_unique<FlexsplineSystem>(assemble_and_factorise(m, *s->mesh));
  s->tet10_fem = analyse_flexspline(m, *s->mesh, *s->system);
  s->tet10 = analyse_contact(m, *s->mesh, *s->system, fem_readout(s->tet10_fem), o);
  s->fourier = std::make_unique<FourierSolution>(
      analyse_flexspline_fourier(m, contact_band_request(m, s->c.contact.face_slices)));
  // The contact on both bodies from the same rim at rest (TET10's readout: the generator-deformed neutral curve, C_τ,
  // the stations' standoff), so that only the body's influence coefficients differ; and on the harmonic solver's own.
  const HarmonicBody body(m, *s->fourier);
  s->harmonic = analyse_contact(m, body, fem_readout(s->tet10_fem), o);
  s->harmonic_own = analyse_contact(m, body, fem_readout(s->fourier->figures), o);
  return *s;
}

/// The generator's zone at +rated around the major axis's end at 0° (the other end is its half-turn image): the first
/// and the last station carrying more than 1 % of the largest station force, degrees in [−90°, 90°). Inside the zone, where the cam and the bore conform,
/// which stations carry the small pressure is set by sub-micrometre differences of the two discretisations (TET10's
/// zone is fragmented there), so the zones are compared by their extent.
std::pair<double, double> zone_at_rated(const ContactAnalysis& a, const std::vector<double>& angles) {
  const std::vector<double>& f = a.steps.back().station_force_N;
  const double largest = *std::max_element(f.begin(), f.end());
  double lo = 90, hi = -90;
  for (std::size_t j = 0; j < angles.size(); ++j) {
    if (!(f[j] > 1e-2 * largest)) continue;  // carrying force (at a zone's edge the last station's is a trace)
    double deg = angles[j] * 180 / M_PI;
    if (deg >= 90) deg -= 180;
    lo = std::min(lo, deg);
    hi = std::max(hi, deg);
  }
  return {lo, hi};
}

class BothSolvers : public ::testing::TestWithParam<const char*> {};

// The same contact on both bodies (from TET10's rim at rest): twist at T1, T2 and rated torque within 1 %, K1..K3 at the
// same breakpoints within 2 %, the flank forces at rated within 5 % of the largest, the same generator zone. Both at
// the case's own settings: the TET10 mesh is within 0.5 % of the converged φ₀ (tests/app/test_cases.cpp), the
// harmonic count converged (below). Each on its own FEM's rim at rest, the twist at T2 and rated torque within 1 %;
// at T1 (1 % of rated on the seed, 13 % on size 17) the twist is mostly half the play, which the two discretisations'
// generator-deformed rims set 0.02 arcmin apart on the seed (0.820 vs 0.801 arcmin: the rims differ by 1e-3 of w0),
// and the forces near the major axis follow their gaps there (printed, not asserted).
TEST_P(BothSolvers, HarmonicContactMatchesTet10Contact) {
  const BothWays& b = both_ways(GetParam());
  const ContactAnalysis &t = b.tet10, &h = b.harmonic;
  EXPECT_EQ(t.solver, "tet10");
  EXPECT_EQ(h.solver, "fourier");
  const double T1 = t.catalog.t1_Nm, T2 = t.catalog.t2_Nm, TR = t.rated_torque_Nm;
  for (const double T : {T1, T2, TR}) {
    const double rel = twist_at(h.curve, T) / twist_at(t.curve, T) - 1;
    std::printf("%s: twist at %.3g N·m %.4f arcmin harmonic, %.4f tet10 (%+.2f %%)\n", GetParam(), T,
                twist_at(h.curve, T) * kArcmin, twist_at(t.curve, T) * kArcmin, 100 * rel);
    EXPECT_NEAR(rel, 0.0, 0.01) << "T = " << T;
  }
  const SegmentLaw kt = segment_law(t.curve, T1, T2, TR), kh = segment_law(h.curve, T1, T2, TR);
  for (const auto& [name, a, c] : {std::tuple{"K1", kh.k1_Nm_per_rad, kt.k1_Nm_per_rad},
                                   std::tuple{"K2", kh.k2_Nm_per_rad, kt.k2_Nm_per_rad},
                                   std::tuple{"K3", kh.k3_Nm_per_rad, kt.k3_Nm_per_rad}}) {
    std::printf("%s: %s %.5g harmonic, %.5g tet10 (%+.2f %%)\n", GetParam(), name, a, c, 100 * (a / c - 1));
    EXPECT_NEAR(a / c, 1.0, 0.02) << name;
  }
  double largest = 0, diff = 0;
  std::size_t worst = 0;
  ASSERT_EQ(h.flanks.size(), t.flanks.size());
  for (std::size_t i = 0; i < t.flanks.size(); ++i) {
    ASSERT_EQ(h.flanks[i].tooth, t.flanks[i].tooth);
    ASSERT_EQ(h.flanks[i].flank, t.flanks[i].flank);
    largest = std::max(largest, t.steps.back().flank_force_N[i]);
    const double d = std::abs(h.steps.back().flank_force_N[i] - t.steps.back().flank_force_N[i]);
    if (d > diff) std::tie(diff, worst) = std::tuple{d, i};
  }
  const FlankContact& w = t.flanks[worst];
  std::printf("%s: flank forces at rated: largest %.1f N, largest difference %.2f N (tooth %d at %.1f deg, section %d, "
              "%s on %s; %.1f vs %.1f N)\n", GetParam(), largest, diff, w.tooth, w.phi_rad * 180 / M_PI, w.slice,
              part_name(w.part_f), part_name(w.part_c), h.steps.back().flank_force_N[worst],
              t.steps.back().flank_force_N[worst]);
  // 5 %; on the seed 10 %: its teeth at the major axis touch at the flexspline's sharp tip corners (4 of the 5 largest
  // forces), contacts so stiff that the two models' local compliance under the hats shares the torque among them
  // differently (measured 17.9 N of 189.7 N on tooth 1, while the curve agrees within 0.34 %). The designed size 17
  // (straight teeth in three sections) shows the same on a lighter contact: 5.96 N of 162.5 N (3.7 %), a tip corner on
  // a flank at 5.4° at mid-face (9.7 vs 3.7 N), while the curve agrees within 0.71 %.
  EXPECT_LT(diff, (std::string(GetParam()).find("seed") != std::string::npos ? 0.10 : 0.05) * largest);
  const auto& st = b.fourier->stations;
  ASSERT_TRUE(st.has_value());
  ASSERT_EQ(st->angle_rad.size(), b.tet10_fem.generator->station_angle_rad.size());
  const auto zh = zone_at_rated(h, st->angle_rad), zt = zone_at_rated(t, b.tet10_fem.generator->station_angle_rad);
  const double station_deg = st->half_width_rad * 180 / M_PI;
  std::printf("%s: generator zone at rated %.2f..%.2f deg harmonic, %.2f..%.2f tet10 (stations %.2f deg apart)\n",
              GetParam(), zh.first, zh.second, zt.first, zt.second, station_deg);
  EXPECT_LE(std::abs(zh.first - zt.first), station_deg + 1e-9);
  EXPECT_LE(std::abs(zh.second - zt.second), station_deg + 1e-9);
  // The ratcheting ramp on both bodies: the same teeth, each tooth's overlap under load read through each body's own
  // radial observers at the tips (and the same circular spline). The torque within 3 %.
  ASSERT_TRUE(h.ratcheting && t.ratcheting);
  std::printf("%s: ratcheting torque %.1f N·m harmonic, %.1f tet10 (searched to %.0f); first release %.1f vs %.1f; "
              "last tooth %d vs %d, parted %.1f + %.1f um vs %.1f + %.1f um by the rim and the ring\n", GetParam(),
              h.ratcheting->torque_Nm, t.ratcheting->torque_Nm, t.ratcheting->ceiling_Nm, h.ratcheting->first_release_Nm,
              t.ratcheting->first_release_Nm, h.ratcheting->last_tooth, t.ratcheting->last_tooth,
              h.ratcheting->last_rim_in_m * 1e6, h.ratcheting->last_ring_out_m * 1e6, t.ratcheting->last_rim_in_m * 1e6,
              t.ratcheting->last_ring_out_m * 1e6);
  ASSERT_EQ(std::isfinite(h.ratcheting->torque_Nm), std::isfinite(t.ratcheting->torque_Nm));
  // The seed's teeth do not let go below the ceiling (first releases 498 and 557 N·m); the cup's must, or nothing is
  // compared (measured 3499.5 against 3525.4 N·m, 0.7 %).
  if (std::string(GetParam()).find("cup") != std::string::npos) ASSERT_TRUE(std::isfinite(t.ratcheting->torque_Nm));
  if (std::isfinite(t.ratcheting->torque_Nm)) EXPECT_NEAR(h.ratcheting->torque_Nm / t.ratcheting->torque_Nm, 1.0, 0.03);
  // The body's part of the twist by its regions on either body: they add to the body's, and each region's share of
  // the body agrees within 2 points on size 17 (measured 0.3); on the seed within 4 (measured 3.3 on the rim): the
  // tangent's force increment dz follows the flank forces at rated, which differ by 10 % of the largest there (above),
  // and so do the bodies' own shares of the twist (75.7 against 85.4 %).
  const double tolerance = std::string(GetParam()).find("seed") != std::string::npos ? 0.04 : 0.02;
  for (const auto& [name, ph, pt] : {std::tuple{"wall", h.split.wall, t.split.wall},
                                     std::tuple{"rim", h.split.rim, t.split.rim},
                                     std::tuple{"diaphragm", h.split.diaphragm, t.split.diaphragm},
                                     std::tuple{"boss", h.split.boss, t.split.boss}}) {
    std::printf("%s: the twist at rated in the %s %.2f %% harmonic, %.2f %% tet10 (%.1f and %.1f %% of the body)\n",
                GetParam(), name, 100 * ph, 100 * pt, 100 * ph / h.split.body, 100 * pt / t.split.body);
    EXPECT_NEAR(ph / h.split.body, pt / t.split.body, tolerance) << name;
  }
  EXPECT_NEAR(h.split.wall + h.split.rim + h.split.diaphragm + h.split.boss, h.split.body, 1e-12);
  EXPECT_NEAR(t.split.wall + t.split.rim + t.split.diaphragm + t.split.boss, t.split.body, 1e-12);
  // The harmonic body's own checks: the quadrature of its hats against its closed-form moments, the balances.
  EXPECT_LT(h.superposition_error_rel, 1e-8);
  EXPECT_LT(h.torque_balance_error_rel, 1e-9);
  EXPECT_NEAR(h.fem_reaction_torque_Nm / TR, 1.0, 1e-6);
  const ContactAnalysis& own = b.harmonic_own;
  for (const double T : {T1, T2, TR}) {
    const double rel = twist_at(own.curve, T) / twist_at(t.curve, T) - 1;
    std::printf("%s, each on its own rim at rest: twist at %.3g N·m %+.2f %%; play %.4f vs %.4f arcmin\n", GetParam(),
                T, 100 * rel, own.play_rad * kArcmin, t.play_rad * kArcmin);
    if (T != T1) EXPECT_NEAR(rel, 0.0, 0.01) << "T = " << T;
  }
}

INSTANTIATE_TEST_SUITE_P(Cases, BothSolvers,
                         ::testing::Values("cases/seed_190_192.toml", "cases/cup_size17.toml"));

/// A few of size 17's flank patterns (near the major axis, in the zone, at its edge).
std::vector<FlankPattern> some_flanks(const ContactAnalysis& a) {
  std::vector<FlankPattern> p;
  for (std::size_t i = 0; i < a.flanks.size(); i += std::max<std::size_t>(1, a.flanks.size() / 6)) {
    const FlankContact& f = a.flanks[i];
    const Eigen::Vector2d dir(-std::sin(f.phi_rad), std::cos(f.phi_rad));  // tangential at the tooth
    p.push_back({{f.phi_rad, f.phi_rad + M_PI}, dir, f.contact_radius_m});
  }
  return p;
}

// A circulant block (flank patterns among themselves) from the harmonics against the same block by TET10 half solves:
// 1 % of its largest entry (the two models' discretisations of the rim under the teeth differ at that level). Then
// the body's strain energy by the regions of its mesh (wall, toothed rim, diaphragm, boss: what the split of the twist
// reads) under those patterns' forces: on each body the regions add to ½xᵀAx, the energy its influence coefficients
// give (a direct field against the coefficients: round-off, 1e-8 asserted); between the bodies each region's share
// within 2 % of the whole (measured within 1 %).
TEST(HarmonicContact, CirculantBlockAndEnergyByRegionMatchTet10) {
  const BothWays& b = both_ways("cases/cup_size17.toml");
  const FlexsplineModel m = flexspline_model(b.c);
  const std::vector<FlankPattern> p = some_flanks(b.tet10);
  const Eigen::Index n = static_cast<Eigen::Index>(p.size());
  const Tet10Body tet10(m, *b.mesh, *b.system, nullptr);  // the influences' readings refer to their bodies
  const HarmonicBody harmonic(m, *b.fourier);
  const BodyInfluence it = tet10.influence(p, 1), ih = harmonic.influence(p, 1);
  const Eigen::MatrixXd At = it.A.topLeftCorner(n, n), Ah = ih.A.topLeftCorner(n, n);
  const double err = (Ah - At).cwiseAbs().maxCoeff() / At.cwiseAbs().maxCoeff();
  std::printf("size 17: %lld flank patterns, block from harmonics vs TET10 half solves: %.2e of the largest entry\n",
              static_cast<long long>(n), err);
  EXPECT_LT(err, 0.01);
  const auto loads = [&](const BodyInfluence& i) {  // the patterns' forces; the generator's stations unloaded
    Eigen::VectorXd x = Eigen::VectorXd::Zero(i.A.cols());
    for (Eigen::Index k = 0; k < n; ++k) x[k] = 100.0 * (1 + k % 3);  // N
    return x;
  };
  const Eigen::VectorXd xt = loads(it), xh = loads(ih);
  const std::vector<double> Ut = it.energy_by_region_J(xt), Uh = ih.energy_by_region_J(xh);
  ASSERT_EQ(Ut.size(), 4u);
  ASSERT_EQ(Uh.size(), 4u);
  double st = 0, sh = 0;
  for (std::size_t r = 0; r < 4; ++r) {
    EXPECT_GE(Ut[r], 0.0);
    EXPECT_GE(Uh[r], 0.0);
    st += Ut[r], sh += Uh[r];
  }
  // The regions' sum against the coefficients' work: the direct field's quadrature against the hats' moments, which
  // agree to round-off on TET10 and to 1.4e-8 on the harmonic section for these patterns (5e-8 asserted: a share of
  // the body's energy is printed to 1e-4).
  EXPECT_NEAR(st / (0.5 * xt.dot(it.A * xt)), 1.0, 1e-8);
  EXPECT_NEAR(sh / (0.5 * xh.dot(ih.A * xh)), 1.0, 5e-8);
  const char* names[] = {"wall", "rim", "diaphragm", "boss"};
  for (std::size_t r = 0; r < 4; ++r) {
    std::printf("size 17, flank patterns' forces: %s %.2f %% harmonic, %.2f %% tet10 of the body's strain energy\n",
                names[r], 100 * Uh[r] / sh, 100 * Ut[r] / st);
    EXPECT_NEAR(Uh[r] / sh, Ut[r] / st, 0.02) << names[r];
  }
}

// The harmonic count the flank patterns need: doubling it from default_harmonics (z_f/2 = 100 on size 17) changes no
// entry of the contact's influence matrix by more than 1e-3 of the largest (a hat one pitch wide has its spectrum's
// main lobe up to z_f; the work-conjugate products fall as n⁻⁵ past z_f/(2π)).
TEST(HarmonicContact, HalfTheToothCountOfHarmonicsIsEnough) {
  const Case c = load_case("cases/cup_size17.toml");
  FlexsplineModel m = flexspline_model(c);
  const FourierSolution once = analyse_flexspline_fourier(m, contact_band_request(m, 1));
  ContactOptions o = options_of(c);
  o.contact.face_slices = 1;  // whole-face patterns on the solution's whole-face band
  const ContactAnalysis a = analyse_contact(m, HarmonicBody(m, once), fem_readout(once.figures), o);
  const std::vector<FlankPattern> p = some_flanks(a);
  const Eigen::MatrixXd A = HarmonicBody(m, once).influence(p, 1).A;
  m.solver.harmonics *= 2;
  const FourierSolution twice = analyse_flexspline_fourier(m, contact_band_request(m, 1));
  const Eigen::MatrixXd A2 = HarmonicBody(m, twice).influence(p, 1).A;
  ASSERT_EQ(A.rows(), A2.rows());
  const double change = (A2 - A).cwiseAbs().maxCoeff() / A2.cwiseAbs().maxCoeff();
  std::printf("size 17: harmonics %d -> %d change the influence matrix by %.2e of its largest entry\n",
              once.harmonics_kept, m.solver.harmonics, change);
  EXPECT_LT(change, 1e-3);
}

}  // namespace
}  // namespace sw
