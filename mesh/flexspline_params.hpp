#pragma once
// The flexspline's geometry and its mesh (the case file's [flexspline] and [mesh] tables), SI units, and their
// validation: the mesh stage owns them.
#include <optional>
#include <string>

#include "gear/gear.hpp"

namespace sw {

enum class FlexsplineShape { Cup, Tube };
enum class TeethModel { None, Ring, Explicit };

struct FlexsplineParams {
  FlexsplineShape shape = FlexsplineShape::Cup;
  double inner_radius_m = 18.4e-3;
  double wall_thickness_m = 0.6e-3;     ///< body wall
  double length_m = 20.0e-3;            ///< clamped end (or diaphragm) to the open end
  double rim_width_m = 6.0e-3;          ///< axial width of the toothed rim at the open end
  double rim_thickness_m = 0.7e-3;      ///< radial thickness under the teeth
  TeethModel teeth = TeethModel::Ring;
  double diaphragm_thickness_m = 1.0e-3;  ///< cup only
  double boss_radius_m = 8.0e-3;          ///< cup only: clamped hub
  double fillet_radius_m = 1.0e-3;        ///< cup only
};

/// The case key's spelling of a teeth model ("none", "ring", "explicit").
inline const char* teeth_name(TeethModel t) {
  return t == TeethModel::None ? "none" : t == TeethModel::Ring ? "ring" : "explicit";
}

struct MeshParams {
  double size_m = 0.6e-3;    ///< target edge length away from thin walls
  int wall_layers = 2;       ///< minimum TET10 layers through any wall
  /// Refinement toward a cup's clamp corners (the boss meets the free diaphragm faces; the field is singular there):
  /// the edge length at the corners is the diaphragm's layer thickness halved this many times, growing away from
  /// them. -1: each solver's default (TET10: none, mesh/flexspline.hpp; harmonic section: 2 + ceil(log2 layers),
  /// fem/fourier_section.cpp); 0: none. Both solvers (the TET10 size field, the graded harmonic section).
  int corner_levels = -1;
  double min_dihedral_deg = 0.0;      ///< TetGen quality switch (0 = TetGen default)
  double max_radius_edge_ratio = 2.0; ///< TetGen -q bound
};

/// Largest mesh.corner_levels: 2^-8 of a layer is already far below any tooth or fillet a case resolves.
inline constexpr int kMaxCornerLevels = 8;

/// A length in millimetres for a message (6 significant digits).
std::string mm_text(double length_m);

/// Checks the mesh keys: size_mm > 0, wall_layers >= 1, corner_levels in [-1, kMaxCornerLevels]. Throws InputError
/// "mesh.<key> = value; expectation".
void validate_mesh(const MeshParams& mesh);

/// Checks every dimension and combination of the flexspline keys and the mesh keys. Throws InputError naming the keys
/// in mm, e.g. "flexspline.fillet_radius_mm = 3; must be < inner_radius_mm - boss_radius_mm = 2.4".
void validate_flexspline(const FlexsplineParams& f, const MeshParams& mesh);

/// Checks that the teeth sit on the rim to be meshed: their root circle within 0.25 module of inner_radius +
/// rim_thickness (and, for "explicit", outside inner_radius + wall_thickness). Needed to mesh the teeth (ring or
/// explicit), not by the stages that take the teeth on a neutral curve alone. Throws InputError naming the key.
void check_teeth_on_rim(const FlexsplineParams& f, const std::optional<GearParams>& gear);

}  // namespace sw
