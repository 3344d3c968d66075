#include "mesh/flexspline_params.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <tuple>
#include <utility>

#include "common/constants.hpp"
#include "common/error.hpp"
#include "gear/tooth_profile.hpp"

namespace sw {
namespace {

[[noreturn]] void reject(const std::string& key, double value_m, const std::string& expectation) {
  throw InputError("flexspline." + key + " = " + mm_text(value_m) + "; " + expectation);
}

/// A number for a derivation's text (6 significant digits).
std::string number_text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

/// The rule's size_mm and what it came from (MeshParams): as fine as kDerivedEdgesAround edges around the bore and
/// kDerivedEdgesOverRim over a rim need, within [wall thickness, kMaxLayerAspect × wall thickness].
std::pair<double, std::string> derived_size(const FlexsplineParams& f) {
  const double t = f.wall_thickness_m;
  const double around = 2.0 * kPi * f.inner_radius_m / kDerivedEdgesAround;
  const bool rim = f.shape == FlexsplineShape::Cup || f.teeth != TeethModel::None;
  const double over_rim = rim ? f.rim_width_m / kDerivedEdgesOverRim : around;
  const double wanted = std::min(around, over_rim);
  if (wanted >= kMaxLayerAspect * t)
    return {kMaxLayerAspect * t, number_text(kMaxLayerAspect) + " x flexspline.wall_thickness_mm = " + mm_text(t)};
  if (wanted <= t) return {t, "flexspline.wall_thickness_mm = " + mm_text(t) + " (one layer through the body wall)"};
  if (around <= over_rim)
    return {around, "2 pi x flexspline.inner_radius_mm = " + mm_text(f.inner_radius_m) + " over " +
                        number_text(kDerivedEdgesAround) + " edges around"};
  return {over_rim, "flexspline.rim_width_mm = " + mm_text(f.rim_width_m) + " over " +
                        number_text(kDerivedEdgesOverRim) + " edges"};
}

/// "mesh.<key> = <value>; <expectation>", for a derived value with what it was derived from and the key that sets it
/// (the case reader's form for derived keys).
std::string mesh_key_message(const std::string& key, const std::string& value, const std::string& from,
                             const std::string& expectation) {
  if (from.empty()) return "mesh." + key + " = " + value + "; " + expectation;
  return "mesh." + key + " = " + value + " (not in the file: derived from " + from + "); " + expectation +
         "; write mesh." + key + " to set it";
}

/// Layers through the cup's diaphragm at the mesh's sizes (wall_size); 1 when the sizes are out of range
/// (validate_mesh reports them).
int diaphragm_layers(const FlexsplineParams& f, const MeshParams& mesh) {
  if (!(mesh.size_m > 0) || mesh.wall_layers < 1) return 1;
  return wall_size(f.diaphragm_thickness_m, mesh).layers;
}

}  // namespace

int derived_corner_levels(const FlexsplineParams& f, const MeshParams& mesh) {
  if (f.shape != FlexsplineShape::Cup) return 0;
  const double layers = diaphragm_layers(f, mesh);
  return kDerivedCornerLevels + static_cast<int>(std::floor(std::log2(layers)));
}

MeshParams derive_mesh(const FlexsplineParams& f, const MeshKeysGiven& given) {
  MeshParams m;
  if (given.size_m) {
    m.size_m = *given.size_m;
  } else {
    std::tie(m.size_m, m.size_from) = derived_size(f);
  }
  m.wall_layers = given.wall_layers.value_or(kDerivedWallLayers);
  if (!given.wall_layers) m.wall_layers_from = "the rule of one quadratic tet through each wall";
  if (given.corner_levels && *given.corner_levels != -1) {
    m.corner_levels = *given.corner_levels;
  } else {
    m.corner_levels = derived_corner_levels(f, m);
    m.corner_levels_from = f.shape != FlexsplineShape::Cup
                               ? "the shape: a tube has no clamp corner"
                               : number_text(kDerivedCornerLevels) + " + log2 of the diaphragm's " +
                                     std::to_string(diaphragm_layers(f, m)) + " layers, rounded down";
  }
  return m;
}

std::string mm_text(double length_m) { return number_text(length_m * 1e3); }

std::string mesh_size_text(const MeshParams& mesh) {
  auto key = [](const std::string& name, const std::string& value, const std::string& from) {
    return "mesh." + name + " = " + value + (from.empty() ? "" : " (derived from " + from + ")");
  };
  return key("size_mm", mm_text(mesh.size_m), mesh.size_from) + ", " +
         key("wall_layers", std::to_string(mesh.wall_layers), mesh.wall_layers_from);
}

const std::vector<CaseKey<FlexsplineParams>>& flexspline_keys() {
  using F = FlexsplineParams;
  const auto cup = [](const F& f) { return f.shape == FlexsplineShape::Cup; };
  static const std::vector<CaseKey<F>> keys = {
      choice_key<F>("shape", &F::shape, {{"cup", FlexsplineShape::Cup}, {"tube", FlexsplineShape::Tube}},
                    "a cup (diaphragm and boss at the closed end) or a tube clamped at one end"),
      number_key<F>("inner_radius_mm", &F::inner_radius_m, 1e-3, "mm", any_value(), "the bore's radius, > 0"),
      number_key<F>("wall_thickness_mm", &F::wall_thickness_m, 1e-3, "mm", any_value(), "the body wall's, > 0"),
      number_key<F>("length_mm", &F::length_m, 1e-3, "mm", any_value(),
                    "the clamped end (or the diaphragm's outer face) to the open end, > 0"),
      choice_key<F>("teeth", &F::teeth,
                    {{teeth_name(TeethModel::None), TeethModel::None},
                     {teeth_name(TeethModel::Ring), TeethModel::Ring},
                     {teeth_name(TeethModel::Explicit), TeethModel::Explicit},
                     {teeth_name(TeethModel::Layer), TeethModel::Layer}},
                    "no teeth, the teeth as a ring on the rim, as solids on the cup (the 3-D reference, TET10), or as a "
                    "layer of ribs along the face on the bare rim (stiff along the face, free around it; harmonic solver)")
          .with_default("\"ring\" for a cup, \"none\" for a tube"),
      number_key<F>("rim_width_mm", &F::rim_width_m, 1e-3, "mm", any_value(),
                    "the toothed rim's axial width at the open end, > 0 and short of the diaphragm's fillet"),
      number_key<F>("rim_thickness_mm", &F::rim_thickness_m, 1e-3, "mm", any_value(),
                    "radial thickness under the teeth, >= wall_thickness_mm; bore + it = the teeth's root circle")
          .with_default("0.7 (a tube without teeth: wall_thickness_mm)"),
      number_key<F>("diaphragm_thickness_mm", &F::diaphragm_thickness_m, 1e-3, "mm", any_value(),
                    "the cup's bottom, > 0 and < length_mm")
          .only_when(cup, "shape = \"cup\""),
      number_key<F>("boss_radius_mm", &F::boss_radius_m, 1e-3, "mm", any_value(),
                    "the clamped hub's radius, in (0, inner_radius_mm)")
          .only_when(cup, "shape = \"cup\""),
      number_key<F>("fillet_radius_mm", &F::fillet_radius_m, 1e-3, "mm", any_value(),
                    "where the diaphragm meets the wall, >= 0 and < inner_radius_mm - boss_radius_mm")
          .only_when(cup, "shape = \"cup\""),
  };
  return keys;
}

const std::vector<CaseKey<MeshParams>>& mesh_keys() {
  using M = MeshParams;
  static const std::vector<CaseKey<M>> keys = {
      number_key<M>("size_mm", &M::size_m, 1e-3, "mm", above(0), "target edge length away from thin walls")
          .with_default("160 edges around the bore, 4 across the rim, within [t, 4 t] of the wall t (derive_mesh)"),
      integer_key<M>("wall_layers", &M::wall_layers, at_least(1), "least TET10 layers through any wall")
          .with_default("1, more for a wall thicker than size_mm (derive_mesh)"),
      integer_key<M>("corner_levels", &M::corner_levels,
                     within(-1, kMaxCornerLevels, false, false, "-1: the rule's value, 0: none"),
                     "halvings of the diaphragm's layer toward a cup's clamp corners (both solvers)")
          .with_default("3 + floor(log2(layers through the diaphragm)) for a cup, 0 for a tube"),
      number_key<M>("max_radius_edge_ratio", &M::max_radius_edge_ratio, 1, "", at_least(1.1), "TetGen's -q bound"),
      number_key<M>("min_dihedral_deg", &M::min_dihedral_deg, 1, "deg",
                    within(0, 20, false, true, "TetGen cannot guarantee more"),
                    "TetGen's least dihedral angle (0: TetGen's default)"),
  };
  return keys;
}

void validate_mesh(const MeshParams& mesh) {
  // The schema's ranges; a value the file left out says what it was derived from and which key sets it.
  const std::pair<const char*, const std::string*> derived[] = {
      {"size_mm", &mesh.size_from}, {"wall_layers", &mesh.wall_layers_from}, {"corner_levels", &mesh.corner_levels_from}};
  for (const CaseKey<MeshParams>& k : mesh_keys()) {
    const KeyValue v = *k.get(mesh);
    const double x = k.kind == KeyKind::Integer ? static_cast<double>(std::get<long long>(v)) : std::get<double>(v);
    if (k.range.contains(x)) continue;
    std::string from;
    for (const auto& [key, origin] : derived)
      if (k.name == key) from = *origin;
    throw InputError(mesh_key_message(k.name, key_value_text(v), from, k.range.expectation()));
  }
}

void validate_flexspline(const FlexsplineParams& f, const MeshParams& mesh) {
  if (!(f.inner_radius_m > 0)) reject("inner_radius_mm", f.inner_radius_m, "must be > 0");
  if (!(f.wall_thickness_m > 0)) reject("wall_thickness_mm", f.wall_thickness_m, "must be > 0");
  if (!(f.length_m > 0)) reject("length_mm", f.length_m, "must be > 0");
  const bool cup = f.shape == FlexsplineShape::Cup;
  const bool rim = cup || f.teeth != TeethModel::None;
  const double below_rim = cup ? f.length_m - f.diaphragm_thickness_m - f.fillet_radius_m : f.length_m;
  if (cup) {
    if (!(f.diaphragm_thickness_m > 0)) reject("diaphragm_thickness_mm", f.diaphragm_thickness_m, "must be > 0");
    if (!(f.boss_radius_m > 0)) reject("boss_radius_mm", f.boss_radius_m, "must be > 0");
    if (!(f.boss_radius_m < f.inner_radius_m))
      reject("boss_radius_mm", f.boss_radius_m, "must be < inner_radius_mm = " + mm_text(f.inner_radius_m));
    if (!(f.fillet_radius_m >= 0)) reject("fillet_radius_mm", f.fillet_radius_m, "must be >= 0");
    if (!(f.fillet_radius_m < f.inner_radius_m - f.boss_radius_m))
      reject("fillet_radius_mm", f.fillet_radius_m,
             "must be < inner_radius_mm - boss_radius_mm = " + mm_text(f.inner_radius_m - f.boss_radius_m));
    if (!(f.diaphragm_thickness_m < f.length_m))
      reject("diaphragm_thickness_mm", f.diaphragm_thickness_m, "must be < length_mm = " + mm_text(f.length_m));
  }
  if (rim) {
    if (!(f.rim_thickness_m > 0)) reject("rim_thickness_mm", f.rim_thickness_m, "must be > 0");
    if (!(f.rim_thickness_m >= f.wall_thickness_m))
      reject("rim_thickness_mm", f.rim_thickness_m,
             "must be >= wall_thickness_mm = " + mm_text(f.wall_thickness_m) + " (the rim is the thick end of the wall)");
    if (!(f.rim_width_m > 0)) reject("rim_width_mm", f.rim_width_m, "must be > 0");
    if (!(f.rim_width_m < below_rim))
      reject("rim_width_mm", f.rim_width_m,
             cup ? "must be < length_mm - diaphragm_thickness_mm - fillet_radius_mm = " + mm_text(below_rim)
                 : "must be < length_mm = " + mm_text(below_rim));
  }
  validate_mesh(mesh);
}

void check_teeth_on_rim(const FlexsplineParams& f, const std::optional<GearParams>& gear) {
  if (f.teeth == TeethModel::None) return;
  if (!gear) throw InputError("flexspline.teeth needs the [gear] table (module, teeth, profile shift)");
  const double root = gear_radii(*gear).root_f;
  const double want = f.inner_radius_m + f.rim_thickness_m;
  if (std::abs(root - want) > 0.25 * gear->module_m)
    throw InputError("flexspline.rim_thickness_mm = " + mm_text(f.rim_thickness_m) + "; inner_radius_mm + rim_thickness_mm = " +
                     mm_text(want) + " must match the teeth's root circle " + mm_text(root) +
                     " mm (from [gear]) within 0.25 module = " + mm_text(0.25 * gear->module_m) + " mm");
  const double ro = f.inner_radius_m + f.wall_thickness_m;
  if (f.teeth == TeethModel::Explicit && !(root > ro))
    throw InputError("flexspline.teeth = \"explicit\": the teeth's root circle " + mm_text(root) +
                     " mm (from [gear]) must lie outside the body wall, inner_radius_mm + wall_thickness_mm = " +
                     mm_text(ro) + " mm; reduce wall_thickness_mm or inner_radius_mm");
}

WallSize wall_size(double thickness_m, const MeshParams& mesh) {
  validate_mesh(mesh);
  WallSize w;
  // Thick walls get more layers, so no layer is thicker than the target size.
  w.layers = std::max(mesh.wall_layers, static_cast<int>(std::ceil(thickness_m / mesh.size_m - 1e-9)));
  w.across_m = thickness_m / w.layers;
  w.along_m = std::min(mesh.size_m, kMaxLayerAspect * w.across_m);
  return w;
}

}  // namespace sw
