#pragma once
// The flexspline's geometry and its mesh (the case file's [flexspline] and [mesh] tables), SI units, and their
// validation: the mesh stage owns them.
#include <optional>
#include <string>
#include <vector>

#include "common/case_keys.hpp"
#include "gear/gear.hpp"

namespace sw {

enum class FlexsplineShape { Cup, Tube };
enum class TeethModel { None, Ring, Explicit, Layer };

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

/// The case key's spelling of a teeth model ("none", "ring", "explicit", "layer").
inline const char* teeth_name(TeethModel t) {
  return t == TeethModel::None ? "none" : t == TeethModel::Ring ? "ring" : t == TeethModel::Layer ? "layer" : "explicit";
}

/// The mesh: the case file's [mesh] table, resolved. A case may give size_mm, wall_layers and corner_levels, some of
/// them or none; each key it leaves out is derived from the part by one rule (derive_mesh). The rule is scale-free
/// (a part and its copy at another size get the same mesh up to scale):
/// - wall_layers = 1: one quadratic tet through a wall holds its torsion (shear constant through it) and the
///   generator's bending (strain linear through it); a wall thicker than size_mm gets more (wall_size).
/// - size_mm: as fine as kDerivedEdgesAround edges around the bore (the generator's two-lobe wave, its contact
///   stations two edges apart and the torque's engagement zones) and kDerivedEdgesOverRim across a rim's width (the
///   loads' axial spread) need, but within [t, kMaxLayerAspect·t] for the body wall's thickness t: one layer through
///   it, and no longer along it than that layer allows. The teeth follow: a ring is the rim's outer layer, meshed with
///   the rim (as the harmonic section's tooth layer is); explicit teeth take their edges from their own thickness,
///   axially no longer than size_mm (tooth_mesh_size in mesh/flexspline_sizes.hpp).
/// - corner_levels = kDerivedCornerLevels + floor(log2(layers through the diaphragm)) for a cup, 0 for a tube (the
///   corner edge is the diaphragm's layer halved that many times: it shrinks about as size² when a mesh is refined,
///   as the singular corners want). The same value grades the TET10 mesh and the harmonic section.
/// Measured, φ₀ (cam in place) against the converged value extrapolated from graded harmonic sections: the designed
/// cups of sizes 14 / 17 / 20 at their derived mesh (0.83 mm at size 17, 1 layer, 4 levels: 170k nodes) −0.41 %
/// (the d/54 mesh `design` wrote before, 181k nodes, the same); the seed cup at its own 0.6 mm / 2 layers with the
/// derived 4 levels (298k nodes) −0.45 %, uniform −2.1 %. One level less: −0.56 % (size 17 at d/54) and −0.60 %; one
/// more: −0.29 % and −0.34 % for 1.6x the nodes.
/// A message about a derived value says what it was derived from and which key to write (the *_from members). The
/// members' initial values are for code that builds a MeshParams itself (tests, benches); corner_levels = -1 there
/// asks for the rule's value (corner_levels() in mesh/flexspline_sizes.hpp resolves it for both solvers).
struct MeshParams {
  double size_m = 0.6e-3;    ///< target edge length away from thin walls
  int wall_layers = 2;       ///< minimum TET10 layers through any wall
  /// Refinement toward a cup's clamp corners (the boss meets the free diaphragm faces; the field is singular there):
  /// the edge length at the corners is the diaphragm's layer thickness halved this many times, growing away from
  /// them. 0: none; -1: the rule's value. Both solvers (the TET10 size field, the graded harmonic section).
  int corner_levels = -1;
  double min_dihedral_deg = 0.0;      ///< TetGen quality switch (0 = TetGen default)
  double max_radius_edge_ratio = 2.0; ///< TetGen -q bound
  /// What a key the case file left out was derived from, e.g. "2 x flexspline.wall_thickness_mm = 0.3"; empty for a
  /// key the case file gave (or the caller set).
  std::string size_from, wall_layers_from, corner_levels_from;
};

/// The rule's constants (see MeshParams).
inline constexpr int kDerivedWallLayers = 1;
inline constexpr double kDerivedEdgesAround = 160.0;
inline constexpr double kDerivedEdgesOverRim = 4.0;
inline constexpr int kDerivedCornerLevels = 3;

/// The [mesh] keys a case file gave (std::nullopt: left out, derived).
struct MeshKeysGiven {
  std::optional<double> size_m;
  std::optional<int> wall_layers;
  std::optional<int> corner_levels;
};

/// The mesh of the part: the keys `given`, each other one derived by the rule of MeshParams, with what it was derived
/// from. Never throws; a flexspline whose own keys are out of range gives a derived value out of range too, so check
/// the flexspline first (validate_flexspline does).
MeshParams derive_mesh(const FlexsplineParams& f, const MeshKeysGiven& given);

/// Largest ratio of along-wall to through-wall edge length in a layered wall. TetGen does not insert layers by
/// itself (a wall meshed at edge t / layers everywhere came out one tet thick), so walls are split into layers by
/// internal surfaces and the along-wall edge may be longer; 2:1 keeps the quadratic tets well shaped.
inline constexpr double kMaxLayerAspect = 2.0;

/// Edge lengths for a wall of thickness t (m): `layers` = max(wall_layers, ceil(t / size)) layers each one tet
/// thick, `across` = t / layers, `along` = min(size, kMaxLayerAspect * across). Throws InputError for mesh.size_mm <= 0 or
/// mesh.wall_layers < 1.
struct WallSize {
  double across_m = 0.0;
  double along_m = 0.0;
  int layers = 1;
};
WallSize wall_size(double thickness_m, const MeshParams& mesh);

/// The rule's corner_levels for the mesh's size and layers: kDerivedCornerLevels + floor(log2(layers through the
/// diaphragm)) for a cup, 0 for a tube.
int derived_corner_levels(const FlexsplineParams& f, const MeshParams& mesh);

/// Largest mesh.corner_levels: 2^-8 of a layer is already far below any tooth or fillet a case resolves.
inline constexpr int kMaxCornerLevels = 8;

/// A length in millimetres for a message (6 significant digits).
std::string mm_text(double length_m);

/// The mesh's size_mm and wall_layers for a message: "mesh.size_mm = 1.2, mesh.wall_layers = 1", each derived value
/// followed by what it was derived from.
std::string mesh_size_text(const MeshParams& mesh);

/// The [flexspline] table's schema (common/case_keys.hpp). Its ranges depend on each other: validate_flexspline's.
const std::vector<CaseKey<FlexsplineParams>>& flexspline_keys();
/// The [mesh] table's schema; size_mm, wall_layers and corner_levels derived by derive_mesh where left out.
const std::vector<CaseKey<MeshParams>>& mesh_keys();

/// Checks the mesh keys: size_mm > 0, wall_layers >= 1, corner_levels in [-1, kMaxCornerLevels]. Throws InputError
/// "mesh.<key> = value; expectation", for a derived value with what it was derived from and the key that sets it.
void validate_mesh(const MeshParams& mesh);

/// Checks every dimension and combination of the flexspline keys, then the mesh keys (so a mesh value derived from a
/// bad flexspline key is reported as that key). Throws InputError naming the keys in mm, e.g.
/// "flexspline.fillet_radius_mm = 3; must be < inner_radius_mm - boss_radius_mm = 2.4".
void validate_flexspline(const FlexsplineParams& f, const MeshParams& mesh);

/// Checks that the teeth sit on the rim to be meshed: their root circle within 0.25 module of inner_radius +
/// rim_thickness (and, for "explicit", outside inner_radius + wall_thickness). Needed to mesh the teeth (ring or
/// explicit), not by the stages that take the teeth on a neutral curve alone. Throws InputError naming the key.
void check_teeth_on_rim(const FlexsplineParams& f, const std::optional<GearParams>& gear);

}  // namespace sw
