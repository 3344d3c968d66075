#include "mesh/flexspline_params.hpp"

#include <cmath>
#include <cstdio>
#include <string>

#include "common/error.hpp"
#include "gear/tooth_profile.hpp"

namespace sw {
namespace {


[[noreturn]] void reject(const std::string& key, double value_m, const std::string& expectation) {
  throw InputError("flexspline." + key + " = " + mm_text(value_m) + "; " + expectation);
}

}  // namespace

std::string mm_text(double length_m) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", length_m * 1e3);
  return buf;
}

void validate_mesh(const MeshParams& mesh) {
  if (!(mesh.size_m > 0.0)) throw InputError("mesh.size_mm = " + mm_text(mesh.size_m) + "; must be > 0");
  if (mesh.wall_layers < 1)
    throw InputError("mesh.wall_layers = " + std::to_string(mesh.wall_layers) + "; must be >= 1");
  if (mesh.corner_levels < -1 || mesh.corner_levels > kMaxCornerLevels)
    throw InputError("mesh.corner_levels = " + std::to_string(mesh.corner_levels) + "; must be in [-1, " +
                     std::to_string(kMaxCornerLevels) + "] (-1: the default grading, 0: none)");
}

void validate_flexspline(const FlexsplineParams& f, const MeshParams& mesh) {
  validate_mesh(mesh);
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

}  // namespace sw
