#pragma once
// The flexspline's teeth as ribs along the face, sheared across the face: one pitch of the toothed rim, the periodic
// cell of the tooth layer (fem/fourier_element.hpp tooth_layer_elasticity) under its out-of-plane shear γ_θz.
//
// A rib that tilts along the face (u_θ growing with z, the rim twisting or coning under it) is sheared in its
// cross-section's plane (r, s), s = r θ around the rim: u_z(r, s) = γ s + w(r, s) with w periodic in s. Away from its
// root the rib relaxes (w ≈ −γ s: a free slab tilts as a body, no stress); at its root it is held to the rim, which is
// continuous around the circle and carries γ whole. The added energy over the rim's own, against the rule of mixtures'
// (the rib's whole section at γ), is the layer's factor on its shear modulus G_θz = κ φ G. The cell is Laplace's
// equation, G ∇²w = 0, flanks, tip, spaces and bore traction-free (∂u_z/∂n = 0), solved on bilinear quadrilaterals.
// Plane in (r, s): the rim's curvature over one pitch (tooth height / radius, 2–4 % on the designed drives) is left out.
// Verified against the series solution of a rectangular rib on a held root (tests/fem/test_rib_cell.cpp).
#include <vector>

namespace sw {

/// One pitch of a toothed rim in its cross-section. Metres.
struct RibCell {
  std::vector<double> height_m;  ///< from the root (0) to the tip, increasing, ≥ 2 entries
  std::vector<double> width_m;   ///< the rib's width at each height (read linearly between), ≤ pitch_m
  double pitch_m = 0;            ///< the period around the rim, at the root
  double rim_thickness_m = 0;    ///< the rim under the ribs, root to bore; 0: the root held (a rim that does not warp)
  int cells_across = 16;         ///< cells across the rib's root; the rest of the mesh follows at the same size
};

/// The rib's anti-plane shear stiffness on its rim against the rule of mixtures: κ = (U_cell − U_rim) / U_rib, with
/// U_cell the cell's least energy at a unit mean shear, U_rim the bare rim's (its area at γ = 1) and U_rib the rib's
/// area at γ = 1. 1 for a rib as wide as the pitch; toward 7ζ(3)/π³ · b / h for a tall rectangular rib of width b and
/// height h on a held root. Throws std::invalid_argument on a malformed cell (a programming error: the cell is built
/// from a checked design).
double rib_shear_factor(const RibCell& cell);

}  // namespace sw
