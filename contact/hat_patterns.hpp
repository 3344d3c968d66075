#pragma once
// A contact force carried down a rigid tooth onto a body of revolution, as load patterns on a band of its surface whose
// circumferential harmonics are closed forms (contact/harmonic_body.hpp: the flexspline's rim under its teeth;
// contact/circular_spline.hpp: the circular spline's ring under its teeth).
//
// A flank's pattern is a radial and a tangential linear hat one tooth pitch wide (half-width h) and a radial couple
// (two hats half as wide, outward and inward) on the band, uniform across it, the three amplitudes set so the pattern
// has exactly the contact force's resultant and its moment about the axis. Their θ moments are closed forms: a linear
// hat of half-width h at c has ∫ hat·cos nθ dθ = H_n(h)·cos nc and ∫ hat·sin nθ dθ = H_n(h)·sin nc with H_0 = h,
// H_n = 2(1 − cos nh)/(n²h). So each pattern's load of harmonic n lies in the span of its band's two spatial vectors
// E_r, E_θ (fem/fourier_solver.hpp SurfaceBand), whose responses K_n⁻¹E_r, K_n⁻¹E_θ a harmonic pass solves:
//     A = Σ_n Φs_n·G_n·Φs_nᵀ + Φa_n·G_n·Φa_nᵀ,   G_n(a, b) = E_aᵀ·K_n⁻¹·E_b,
// Φ the patterns' moments per band and component, exact up to the series' truncation at N.
#include <vector>

#include <Eigen/Core>

#include "contact/contact_body.hpp"
#include "fem/fourier_solver.hpp"

namespace sw {

/// ∫ hat(θ − c)·cos nθ dθ / cos nc for a linear hat of height 1 and half-width h (the same for sin).
double hat_moment(int n, double h);

/// A flank pattern's three amplitudes (tractions at the hats' peaks, Pa) on a band with spatial vector S: radial and
/// tangential hats of half-width h at the station, a radial couple of hats h/2 wide either side. In the station's own
/// frame (e_r, e_θ) the pattern's resultant is (H_1(h)·a_r, H_1(h)·a_t + 2·H_1(h/2)·sin(h/2)·a_m)·ΣS and its moment
/// about the axis h·a_t·Σ r_i S_i (the couple's is zero), which the contact force F at radius ρ sets to (F_r, F_θ)
/// and ρ·F_θ.
struct HatAmplitudes {
  double radial = 0, tangential = 0, couple = 0;
};
HatAmplitudes amplitudes(const FlankPattern& p, double h, double sum_S, double sum_rS);

/// The θ moments of every load per harmonic: row j's load of harmonic n is Σ_b Φs(j, 2b)·E_r,b + Φs(j, 2b+1)·E_θ,b
/// in the symmetric family, the same with Φa in the antisymmetric one (fem/fourier_solver.hpp HarmonicStations).
struct Moments {
  std::vector<Eigen::MatrixXd> sym, anti;
};

/// Adds a flank pattern (row `row`, band columns `col`, `col` + 1) with its amplitudes at each of its stations (the
/// half-turn partner's local frame is turned with it, so its amplitudes are the same).
void add_flank(Moments& m, Eigen::Index row, Eigen::Index col, const FlankPattern& p, const HatAmplitudes& a,
               double h);

/// Each pattern's band (0: the whole face; 1 + its slice when `slices` > 1) and its amplitudes.
struct FlankHats {
  std::vector<HatAmplitudes> amplitude;
  std::vector<Eigen::Index> band;
};

/// Adds `patterns` as rows 0.. of `m` (each on its band: `r[0]` the whole face, `r[1 + slice]` its slice when
/// `slices` > 1), hats of half-width h on a section whose node radii are `radius`.
FlankHats add_flanks(Moments& m, const std::vector<FlankPattern>& patterns, int slices,
                     const std::vector<const BandResponse*>& r, const Eigen::VectorXd& radius, double h);

/// G_n(2a + k, 2b + l) = E_{a,k}ᵀ·K_n⁻¹·E_{b,l} (k, l: 0 radial, 1 tangential); empty when n was not solved.
Eigen::MatrixXd gram(const std::vector<const BandResponse*>& r, std::size_t n);

/// A = Σ_n Φs_n·G_n·Φs_nᵀ + Φa_n·G_n·Φa_nᵀ over the harmonics solved, made exactly symmetric (rows × rows, m/N).
Eigen::MatrixXd influence_of(const Moments& m, const std::vector<const BandResponse*>& r);

/// The field of loads x (per row of the moments): Σ_b the band's responses weighted by the loads' moments.
HarmonicField field_of(const Moments& m, const std::vector<const BandResponse*>& r, const Eigen::VectorXd& x);

/// The harmonic-0 antisymmetric generalised forces (n_nodes × 3) of loads x: what carries their moment about the axis
/// (fem/fourier_solver.hpp clamp_reaction_moment).
Eigen::MatrixXd anti0_loads(const Moments& m, const std::vector<const BandResponse*>& r, const Eigen::VectorXd& x);

}  // namespace sw
