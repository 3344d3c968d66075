#pragma once
// The flexspline body of the loaded contact on the harmonic solver (fem/fourier_solver.hpp): no mesh, no TET10.
//
// For a body of revolution (teeth "ring", "layer" or "none") the response at θ_i to a load pattern at θ_j depends on θ_i − θ_j
// only: every block of the contact's influence matrix is circulant. A flank's pattern is the TET10 path's
// (contact/tet10_body.hpp FlankLoads): a radial and a tangential linear hat one tooth pitch wide and a radial couple
// (two hats half as wide, outward and inward) on the rim's outer surface, uniform across the face (or its slice), the
// three amplitudes set so the pattern has exactly the contact force's resultant and its moment about the axis. Their θ
// moments are closed forms: a linear hat of half-width h at c has ∫ hat·cos nθ dθ = H_n(h)·cos nc and ∫ hat·sin nθ dθ =
// H_n(h)·sin nc with H_0 = h, H_n = 2(1 − cos nh)/(n²h). So each pattern's load of harmonic n lies in the span of its
// band's two spatial vectors E_r, E_θ (fem/fourier_solver.hpp SurfaceBand), whose responses the harmonic pass solved:
//     A = Σ_n Φs_n·G_n·Φs_nᵀ + Φa_n·G_n·Φa_nᵀ,   G_n(a, b) = E_aᵀ·K_n⁻¹·E_b,
// Φ the patterns' moments per band and component (the generator's stations are one more band), exact up to the
// series' truncation at N. The hats' spectra fall as 1/n² past n ≈ π/h = z_f/2; contact/README.md states the harmonic
// count the patterns need and what it was measured from.
#include <vector>

#include "contact/contact_body.hpp"
#include "fem/flexspline_model.hpp"
#include "fem/fourier_solver.hpp"

namespace sw {

/// The bands the harmonic pass must solve for the loaded contact: the rim's outer surface over the whole face, then
/// each of `face_slices` axial slices when more than one; every harmonic when the flexspline has an odd tooth count
/// (no half-turn pairs).
BandRequest contact_band_request(const FlexsplineModel& c, int face_slices);

/// The body on a harmonic solution that was solved with contact_band_request(c, slices) (slices: those the influence
/// will ask for). `s` must outlive the body.
class HarmonicBody final : public ContactBody {
public:
  HarmonicBody(const FlexsplineModel& c, const FourierSolution& s);
  std::string solver() const override { return "fourier"; }
  const BodyStations& stations() const override { return stations_; }
  BodyInfluence influence(const std::vector<FlankPattern>& patterns, int slices) const override;
  std::vector<NeutralCurveSamples> generator_curves_at(const std::vector<double>& z_m) const override;

private:
  const FlexsplineModel c_;  ///< a copy: the caller's may be a temporary
  const FourierSolution& s_;
  BodyStations stations_;
};

}  // namespace sw
