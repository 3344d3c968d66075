#include "mesh/flexspline_sizes.hpp"

#include <algorithm>
#include <cmath>

#include "common/error.hpp"
#include "gear/tooth_profile.hpp"

namespace sw {
namespace {

// Axial over cross-section edge length on the tooth flanks. The teeth are prisms whose fields vary slowly along the
// axis, so their tets may be longer axially than the layered walls' (kMaxLayerAspect = 2); 2.5 brings the seed case
// from ~600k to ~440k nodes with the worst tet set by the shoulder, not by the teeth.
constexpr double kToothAxialAspect = 2.5;

}  // namespace

ToothMeshSize tooth_mesh_size(const GearParams& g, const MeshParams& mesh) {
  const GearRadii r = gear_radii(g);
  const double t_mid = flexspline_tooth_thickness(g, 0.5 * (r.form_f + r.tip_f));
  ToothMeshSize size;
  size.across_m = std::min(mesh.size_m, 0.5 * t_mid);
  size.axial_m = std::min(mesh.size_m, kToothAxialAspect * size.across_m);
  return size;
}

int corner_levels(const FlexsplineParams& f, const MeshParams& mesh) {
  validate_mesh(mesh);
  if (f.shape != FlexsplineShape::Cup) return 0;
  return mesh.corner_levels == -1 ? derived_corner_levels(f, mesh) : mesh.corner_levels;
}

ProfileSizeField corner_size_field(const FlexsplineParams& f, const MeshParams& mesh) {
  ProfileSizeField field;
  const int levels = corner_levels(f, mesh);
  if (levels == 0) return field;
  const double td = f.diaphragm_thickness_m, rb = f.boss_radius_m;
  field.points = {Eigen::Vector2d(rb, 0.0), Eigen::Vector2d(rb, td)};
  field.size_m = std::ldexp(wall_size(td, mesh).across_m, -levels);
  field.growth = kCornerGrowth;
  field.max_aspect = kCornerAspect;
  return field;
}

double rim_outer_radius(const FlexsplineParams& f, const std::optional<GearParams>& gear) {
  const double root = f.inner_radius_m + f.rim_thickness_m;
  if (f.teeth == TeethModel::None || f.teeth == TeethModel::Layer) return root;
  if (!gear) throw InputError("flexspline.teeth needs the [gear] table (module, teeth, profile shift) for the tooth height");
  const GearRadii r = gear_radii(*gear);
  if (f.teeth == TeethModel::Explicit) return r.tip_f;
  return root + 0.5 * (r.tip_f - r.root_f);
}

}  // namespace sw
