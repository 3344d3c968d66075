#pragma once
// The flexspline's geometry and its mesh (the case file's [flexspline] and [mesh] tables), SI units. The mesh stage
// owns them and checks them (mesh/flexspline.hpp validate_flexspline, corner_levels).
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

}  // namespace sw
