#include "io/case.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <set>
#include <sstream>

#include <toml++/toml.h>

#include "common/error.hpp"
#include "common/overloaded.hpp"
#include "design/catalog.hpp"
#include "dynamics/model.hpp"
#include "generator/cam_profile.hpp"
#include "gear/tooth_profile.hpp"
#include "mesh/flexspline.hpp"

namespace sw {
namespace {

constexpr double kMm = 1e-3;
constexpr double kDeg = std::numbers::pi / 180.0;

std::string format_number(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

/// Reads one table strictly: every key must be known, every value of the right type and range.
class TableReader {
public:
  TableReader(const toml::table& table, std::string name, std::string file)
      : table_(table), name_(std::move(name)), file_(std::move(file)) {}

  /// Throws for every key that was never asked for (typos, keys of another shape).
  void reject_unknown() const {
    for (const auto& [key, node] : table_) {
      if (!used_.count(std::string(key.str())))
        fail(std::string(key.str()), node, "unknown key (allowed: " + allowed() + ")");
    }
  }

  std::optional<double> number(const std::string& key) {
    used_.insert(key);
    const toml::node* node = table_.get(key);
    if (!node) return std::nullopt;
    if (auto v = node->value<double>()) {
      if (!std::isfinite(*v)) fail(key, *node, "must be a finite number");
      return *v;
    }
    fail(key, *node, "expected a number");
  }

  double number(const std::string& key, double fallback) { return number(key).value_or(fallback); }

  double positive(const std::string& key, double fallback) {
    const double v = number(key, fallback);
    if (!(v > 0)) fail_value(key, v, "must be > 0");
    return v;
  }

  double non_negative(const std::string& key, double fallback) {
    const double v = number(key, fallback);
    if (!(v >= 0)) fail_value(key, v, "must be >= 0");
    return v;
  }

  int integer(const std::string& key, int fallback, int at_least) {
    used_.insert(key);
    const toml::node* node = table_.get(key);
    if (!node) return fallback;
    const auto v = node->value_exact<int64_t>();
    if (!v) fail(key, *node, "expected an integer");
    if (*v < at_least) fail(key, *node, "must be >= " + std::to_string(at_least));
    if (*v > std::numeric_limits<int>::max()) fail(key, *node, "must be <= " + std::to_string(std::numeric_limits<int>::max()));
    return static_cast<int>(*v);
  }

  std::string choice(const std::string& key, const std::string& fallback, const std::vector<std::string>& allowed) {
    used_.insert(key);
    const toml::node* node = table_.get(key);
    if (!node) return fallback;
    const auto v = node->value_exact<std::string>();
    std::string list;
    for (const auto& a : allowed) list += (list.empty() ? "\"" : ", \"") + a + "\"";
    if (!v) fail(key, *node, "expected one of " + list);
    for (const auto& a : allowed)
      if (*v == a) return *v;
    fail(key, *node, "expected one of " + list);
  }

  const toml::array* array(const std::string& key) {
    used_.insert(key);
    const toml::node* node = table_.get(key);
    if (!node) return nullptr;
    if (!node->is_array()) fail(key, *node, "expected an array of tables");
    return node->as_array();
  }

  /// An inline table {key = value, ...} (nullptr when absent).
  const toml::table* table(const std::string& key) {
    used_.insert(key);
    const toml::node* node = table_.get(key);
    if (!node) return nullptr;
    if (!node->is_table()) fail(key, *node, "expected a table {key = value, ...}");
    return node->as_table();
  }

  [[noreturn]] void fail_value(const std::string& key, double value, const std::string& expectation) const {
    throw InputError(file_ + where(table_.get(key)) + ": " + name_ + "." + key + " = " + format_number(value) + "; " +
                     expectation);
  }

  [[noreturn]] void fail(const std::string& key, const toml::node& node, const std::string& expectation) const {
    std::ostringstream value;
    if (node.is_table()) value << "{...}";
    else if (node.is_array()) value << "[...]";
    else node.visit([&](const auto& v) { value << v; });
    throw InputError(file_ + where(&node) + ": " + name_ + "." + key + " = " + value.str() + "; " + expectation);
  }

  const std::string& name() const { return name_; }
  const std::string& file() const { return file_; }

private:
  static std::string where(const toml::node* node) {
    if (!node || !node->source().begin) return "";
    return ":" + std::to_string(node->source().begin.line);
  }
  std::string allowed() const {
    std::string s;
    for (const auto& k : used_) s += (s.empty() ? "" : ", ") + k;
    return s;
  }

  const toml::table& table_;
  std::string name_;
  std::string file_;
  std::set<std::string> used_;
};

const toml::table* sub_table(const toml::table& root, const std::string& name, const std::string& file) {
  const toml::node* node = root.get(name);
  if (!node) return nullptr;
  if (!node->is_table())
    throw InputError(file + ":" + std::to_string(node->source().begin.line) + ": " + name + " must be a table ([" +
                     name + "])");
  return node->as_table();
}

GearParams read_gear(TableReader r) {
  GearParams g;
  g.module_m = r.number("module_mm", g.module_m / kMm) * kMm;
  g.teeth_flexspline = r.integer("teeth_flexspline", g.teeth_flexspline, 4);
  g.teeth_circular = r.integer("teeth_circular", g.teeth_circular, 5);
  g.pressure_angle_rad = r.number("pressure_angle_deg", g.pressure_angle_rad / kDeg) * kDeg;
  g.profile_shift_flexspline = r.number("profile_shift_flexspline", g.profile_shift_flexspline);
  g.profile_shift_circular = r.number("profile_shift_circular", g.profile_shift_circular);
  g.cutter_teeth = r.integer("cutter_teeth", g.cutter_teeth, 8);
  g.addendum_coefficient_flexspline = r.number("addendum_coefficient_flexspline", g.addendum_coefficient_flexspline);
  g.addendum_coefficient_circular = r.number("addendum_coefficient_circular", g.addendum_coefficient_circular);
  g.dedendum_coefficient_flexspline = r.number("dedendum_coefficient_flexspline", g.dedendum_coefficient_flexspline);
  g.dedendum_coefficient_circular = r.number("dedendum_coefficient_circular", g.dedendum_coefficient_circular);
  g.tip_rounding_flexspline_m = r.number("tip_rounding_flexspline_mm", g.tip_rounding_flexspline_m / kMm) * kMm;
  g.tip_rounding_circular_m = r.number("tip_rounding_circular_mm", g.tip_rounding_circular_m / kMm) * kMm;
  r.reject_unknown();
  validate_gear(g, r.file());  // gear/ owns the ranges and the consistency of a set that can be made
  return g;
}

FlexsplineParams read_flexspline(TableReader r) {
  FlexsplineParams f;
  const std::string shape = r.choice("shape", "cup", {"cup", "tube"});
  f.shape = shape == "cup" ? FlexsplineShape::Cup : FlexsplineShape::Tube;
  // Ranges and consistency: mesh/flexspline.hpp validate_flexspline, once the mesh table is read (parse_case).
  f.inner_radius_m = r.number("inner_radius_mm", f.inner_radius_m / kMm) * kMm;
  f.wall_thickness_m = r.number("wall_thickness_mm", f.wall_thickness_m / kMm) * kMm;
  f.length_m = r.number("length_mm", f.length_m / kMm) * kMm;
  const std::string teeth = r.choice("teeth", shape == "cup" ? "ring" : "none", {"none", "ring", "explicit"});
  f.teeth = teeth == "none" ? TeethModel::None : teeth == "ring" ? TeethModel::Ring : TeethModel::Explicit;
  const bool has_rim = f.teeth != TeethModel::None;
  // Without teeth a tube has no rim: its rim keys are accepted when >= 0 and not used.
  f.rim_width_m = (has_rim ? r.number("rim_width_mm", f.rim_width_m / kMm) : r.non_negative("rim_width_mm", 0.0)) * kMm;
  if (has_rim) f.rim_thickness_m = r.number("rim_thickness_mm", f.rim_thickness_m / kMm) * kMm;
  else if (const auto t = r.number("rim_thickness_mm"); t && !(*t >= 0)) r.fail_value("rim_thickness_mm", *t, "must be >= 0");
  else f.rim_thickness_m = t ? *t * kMm : f.wall_thickness_m;  // derived, not checked: a tube without teeth has no rim
  if (f.shape == FlexsplineShape::Cup) {
    f.diaphragm_thickness_m = r.number("diaphragm_thickness_mm", f.diaphragm_thickness_m / kMm) * kMm;
    f.boss_radius_m = r.number("boss_radius_mm", f.boss_radius_m / kMm) * kMm;
    f.fillet_radius_m = r.number("fillet_radius_mm", f.fillet_radius_m / kMm) * kMm;
  }
  // A tube has no diaphragm, boss or fillet: those keys stay unknown for it and are rejected as such.
  r.reject_unknown();
  return f;
}

Material read_material(TableReader r) {
  Material m;
  m.youngs_modulus_Pa = r.positive("youngs_modulus_Pa", m.youngs_modulus_Pa);
  m.poisson_ratio = r.number("poisson_ratio", m.poisson_ratio);
  if (!(m.poisson_ratio > -1.0 && m.poisson_ratio < 0.5))
    r.fail_value("poisson_ratio", m.poisson_ratio, "must be in (-1, 0.5)");
  m.density_kg_m3 = r.positive("density_kg_m3", m.density_kg_m3);
  if (auto se = r.number("fatigue_limit_MPa")) {
    if (!(*se > 0)) r.fail_value("fatigue_limit_MPa", *se, "must be > 0");
    m.fatigue_limit_Pa = *se * 1e6;
  }
  if (auto su = r.number("ultimate_strength_MPa")) {
    if (!(*su > 0)) r.fail_value("ultimate_strength_MPa", *su, "must be > 0");
    m.ultimate_strength_Pa = *su * 1e6;
  }
  if (m.fatigue_limit_Pa.has_value() != m.ultimate_strength_Pa.has_value())
    throw InputError(r.file() + ": material.fatigue_limit_MPa and material.ultimate_strength_MPa go together (the "
                                "Goodman line needs both)");
  if (m.fatigue_limit_Pa && !(*m.fatigue_limit_Pa < *m.ultimate_strength_Pa))
    r.fail_value("fatigue_limit_MPa", *m.fatigue_limit_Pa / 1e6,
                 "must be < material.ultimate_strength_MPa = " + format_number(*m.ultimate_strength_Pa / 1e6));
  r.reject_unknown();
  return m;
}

/// wave_generator.bearing = {balls, ball_diameter_mm, inner_groove_conformity, outer_groove_conformity}; the pitch
/// radius follows from the flexspline's bore (generator/generator_bearing.hpp), and the bearing checks itself.
GeneratorBearing read_bearing(TableReader r, double bore_radius_m) {
  GeneratorBearing b;
  b.balls = r.integer("balls", 0, 3);
  const std::optional<double> ball = r.number("ball_diameter_mm");
  if (b.balls == 0 || !ball)
    throw InputError(r.file() + ": " + r.name() + "." + (b.balls == 0 ? "balls" : "ball_diameter_mm") +
                     " is missing; a bearing needs balls and ball_diameter_mm");
  if (!(*ball > 0)) r.fail_value("ball_diameter_mm", *ball, "must be > 0");
  b.ball_diameter_m = *ball * kMm;
  b.inner_groove_conformity = r.number("inner_groove_conformity", b.inner_groove_conformity);
  b.outer_groove_conformity = r.number("outer_groove_conformity", b.outer_groove_conformity);
  r.reject_unknown();
  b.pitch_radius_m = bearing_pitch_radius_m(bore_radius_m, b.ball_diameter_m);
  validate_generator_bearing(b, r.file());
  return b;
}

/// profile = "polar" | "ellipse" | "list"; a list's points profile_points = [{angle_deg, radius_mm}, ...] over a half
/// turn from the major axis (increasing in [0, 180), 4 or more) set w0 = radius at 0° − bore radius, which a given
/// radial_deformation_mm must match.
void read_cam_profile(TableReader& r, Cam& cam, WaveGeneratorParams& w, double bore_radius_m) {
  const std::string profile = r.choice("profile", "polar", {"polar", "ellipse", "list"});
  cam.profile = profile == "ellipse" ? CamProfile::Ellipse : profile == "list" ? CamProfile::List : CamProfile::Polar;
  const toml::array* list = r.array("profile_points");
  if (cam.profile != CamProfile::List) {
    if (list) r.fail("profile_points", *list, "is for profile = \"list\" only");
    return;
  }
  if (!list || list->size() < 4)
    throw InputError(r.file() + ": wave_generator.profile_points is missing or has fewer than 4 points; profile = "
                                "\"list\" needs [{angle_deg = 0, radius_mm = ...}, ...] over a half turn (0 to < 180)");
  for (std::size_t i = 0; i < list->size(); ++i) {
    const toml::table* t = list->get(i)->as_table();
    if (!t) r.fail("profile_points", *list->get(i), "expected tables {angle_deg = ..., radius_mm = ...}");
    TableReader p(*t, r.name() + ".profile_points[" + std::to_string(i) + "]", r.file());
    CamPoint point;
    const auto angle = p.number("angle_deg");
    const auto radius = p.number("radius_mm");
    if (!angle || !radius)
      throw InputError(r.file() + ": " + p.name() + " needs angle_deg and radius_mm");
    if (!(*angle >= 0 && *angle < 180)) p.fail_value("angle_deg", *angle, "must be in [0, 180) (a half turn from the major axis)");
    if (!cam.points.empty() && !(*angle * kDeg > cam.points.back().angle_rad))
      p.fail_value("angle_deg", *angle, "must be larger than the point before's (increasing angles)");
    if (!(*radius > 0)) p.fail_value("radius_mm", *radius, "must be > 0");
    p.reject_unknown();
    point.angle_rad = *angle * kDeg;
    point.radius_m = *radius * kMm;
    cam.points.push_back(point);
  }
  const double w0 = cam_list_w0_m(cam.points, bore_radius_m);
  if (!(w0 > 0))
    throw InputError(r.file() + ": wave_generator.profile_points: the radius at 0 deg (" + format_number((bore_radius_m + w0) / kMm) +
                     " mm) must exceed the bore radius " + format_number(bore_radius_m / kMm) + " mm (w0 > 0)");
  if (const auto given = r.number("radial_deformation_mm"); given && std::abs(*given * kMm - w0) > 1e-7 * kMm)
    r.fail_value("radial_deformation_mm", *given,
                 "must match the listed cam's radius at 0 deg less the bore radius, " + format_number(w0 / kMm) +
                     " mm (or be left out)");
  w.radial_deformation_m = w0;
}

/// beta_deg of the four forces and the rollers, in (0, 90).
double read_beta(TableReader& r) {
  const double beta = r.number("beta_deg", 30.0);
  if (!(beta > 0.0 && beta < 90.0)) r.fail_value("beta_deg", beta, "must be in (0, 90)");
  return beta * kDeg;
}

/// forces = [{angle_deg, weight}, ...] of model = "forces".
GivenForces read_given_forces(TableReader& r) {
  const toml::array* list = r.array("forces");
  if (!list || list->empty())
    throw InputError(r.file() + ": wave_generator.forces is missing or empty; model = \"forces\" needs a list "
                                "like [{angle_deg = 30, weight = 1.0}, ...]");
  GivenForces g;
  for (std::size_t i = 0; i < list->size(); ++i) {
    const toml::table* t = list->get(i)->as_table();
    if (!t) r.fail("forces", *list->get(i), "expected tables {angle_deg = ..., weight = ...}");
    TableReader f(*t, r.name() + ".forces[" + std::to_string(i) + "]", r.file());
    WaveGeneratorForce force;
    force.angle_rad = f.number("angle_deg", 0.0) * kDeg;
    force.weight = f.positive("weight", 1.0);
    f.reject_unknown();
    g.forces.push_back(force);
  }
  return g;
}

/// The model's own keys, in the order the file reads them (beta_deg before radial_deformation_mm, a cam's profile
/// after it): the model with them.
GeneratorModel read_generator_model(TableReader& r, const std::string& model) {
  if (model == "four_force") return FourForce{read_beta(r)};
  if (model == "rollers") return Rollers{read_beta(r)};
  if (model == "two_force") return TwoForce{};
  if (model == "forces") return GivenForces{};  // its list is read after the common keys, as before
  return Cam{};
}

WaveGeneratorParams read_wave_generator(TableReader r, double bore_radius_m) {
  WaveGeneratorParams w;
  const std::string model = r.choice("model", "four_force", {"four_force", "two_force", "forces", "cam", "rollers"});
  w.model = read_generator_model(r, model);
  const bool body = pushes_only(w.model);
  if (auto w0 = r.number("radial_deformation_mm")) {
    if (!(*w0 > 0)) r.fail_value("radial_deformation_mm", *w0, "must be > 0");
    w.radial_deformation_m = *w0 * kMm;
  }
  if (!body) w.force_N = r.positive("force_N", w.force_N);
  Cam* cam = std::get_if<Cam>(&w.model);
  if (cam) read_cam_profile(r, *cam, w, bore_radius_m);
  if (body && !w.radial_deformation_m)
    throw InputError(r.file() + ": wave_generator.radial_deformation_mm is missing; model = \"" + model +
                     "\" is set out to reach it");
  w.axial_position_m = r.non_negative("axial_position_mm", w.axial_position_m / kMm) * kMm;
  w.band_width_m = r.positive("band_width_mm", w.band_width_m / kMm) * kMm;
  if (cam) {
    cam->clearance_m = r.number("fit_um", 0.0) * 1e-6;
    if (!(std::abs(cam->clearance_m) < *w.radial_deformation_m))
      r.fail_value("fit_um", cam->clearance_m * 1e6,
                   "must be smaller in size than radial_deformation_mm (a clearance > 0 or an interference < 0, µm)");
  }
  if (std::holds_alternative<GivenForces>(w.model)) w.model = read_given_forces(r);
  if (const toml::table* t = r.table("bearing"))
    w.bearing = read_bearing(TableReader(*t, r.name() + ".bearing", r.file()), bore_radius_m);
  r.reject_unknown();
  return w;
}

LoadParams read_load(TableReader r) {
  LoadParams l;
  l.torque_Nm = r.number("torque_Nm", l.torque_Nm);
  const std::string how = r.choice("torque_loading", "engagement_zones", {"engagement_zones", "uniform"});
  l.torque_loading = how == "uniform" ? TorqueLoading::Uniform : TorqueLoading::EngagementZones;
  const double half = r.number("engagement_half_angle_deg", 20.0);
  if (!(half > 0.0 && half <= 90.0)) r.fail_value("engagement_half_angle_deg", half, "must be in (0, 90]");
  l.engagement_half_angle_rad = half * kDeg;
  if (auto rated = r.number("rated_torque_Nm")) {
    if (!(*rated > 0)) r.fail_value("rated_torque_Nm", *rated, "must be > 0 (the torque the drive is loaded to, both ways)");
    l.rated_torque_Nm = *rated;
    l.rated_torque_from = "the case file";
  }
  r.reject_unknown();
  return l;
}

/// The keys the table gives; derive_mesh (mesh/flexspline_params.hpp) derives the others from the flexspline.
MeshParams read_mesh(TableReader r, const FlexsplineParams& f) {
  // size_mm, wall_layers and corner_levels: their ranges are the mesh's (mesh/shapes.hpp wall_size,
  // mesh/flexspline.hpp corner_levels), checked with the flexspline's. kLeftOut marks a key the table does not give.
  constexpr int kLeftOut = std::numeric_limits<int>::min();
  MeshKeysGiven given;
  if (const auto size = r.number("size_mm")) given.size_m = *size * kMm;
  if (const int v = r.integer("wall_layers", kLeftOut, kLeftOut + 1); v != kLeftOut) given.wall_layers = v;
  if (const int v = r.integer("corner_levels", kLeftOut, kLeftOut + 1); v != kLeftOut) given.corner_levels = v;
  MeshParams m = derive_mesh(f, given);
  m.max_radius_edge_ratio = r.number("max_radius_edge_ratio", m.max_radius_edge_ratio);
  if (!(m.max_radius_edge_ratio >= 1.1)) r.fail_value("max_radius_edge_ratio", m.max_radius_edge_ratio, "must be >= 1.1");
  m.min_dihedral_deg = r.number("min_dihedral_deg", m.min_dihedral_deg);
  if (!(m.min_dihedral_deg >= 0.0 && m.min_dihedral_deg < 20.0))
    r.fail_value("min_dihedral_deg", m.min_dihedral_deg, "must be in [0, 20) (TetGen cannot guarantee more)");
  r.reject_unknown();
  return m;
}

SolverParams read_solver(TableReader r) {
  SolverParams s;
  s.method = r.choice("method", "tet10", {"tet10", "fourier"}) == "fourier" ? SolverMethod::Fourier : SolverMethod::Tet10;
  s.harmonics = r.integer("harmonics", s.harmonics, 0);
  if (s.harmonics > 4096) r.fail_value("harmonics", s.harmonics, "must be <= 4096");
  const bool petsc = r.choice("backend", "cholmod", {"cholmod", "petsc"}) == "petsc";
  s.backend = petsc ? SolverBackend::Petsc : SolverBackend::Cholmod;
  r.reject_unknown();
  return s;
}

/// [catalog] size: a size of design/catalog.hpp's table.
int read_catalog(TableReader r) {
  const int size = r.integer("size", 0, 1);
  r.reject_unknown();
  if (size == 0) throw InputError(r.file() + ": catalog.size is missing; [catalog] names a catalog size (" +
                                  catalog_sizes_text() + ")");
  if (!catalog_drive(size))
    r.fail_value("size", size, "must be a listed catalog size (" + catalog_sizes_text() + ")");
  return size;
}

/// [circular_spline] (optional keys over the design rule's defaults, contact/circular_spline.hpp).
CircularSplineParams read_circular_spline(TableReader r, const GearParams& gear, double face_width_m) {
  CircularSplineParams c = default_circular_spline(gear, face_width_m);
  c.outer_radius_m = r.positive("outer_radius_mm", c.outer_radius_m / kMm) * kMm;
  c.width_m = r.positive("width_mm", c.width_m / kMm) * kMm;
  r.reject_unknown();
  double root_m = 0;
  try {
    root_m = gear_radii(gear).root_c;
  } catch (const InputError& e) {  // a set that cannot be cut: say which file
    throw InputError(r.file() + ": " + e.what());
  }
  validate_circular_spline(c, root_m, r.file());
  return c;
}

/// [contact] face_slices (its range: contact/contact_params.hpp, checked by parse_case with the key's line).
ContactParams read_contact(TableReader r) {
  ContactParams p;
  p.face_slices = r.integer("face_slices", p.face_slices, std::numeric_limits<int>::min());
  r.reject_unknown();
  return p;
}

/// [dynamics]: the keys' types here; their ranges are the dynamics stage's own (dynamics/model.hpp validate), checked
/// by parse_case with the key's line.
DynamicsParams read_dynamics(TableReader r) {
  DynamicsParams d;
  const std::string conf = r.choice("configuration", to_string(d.configuration),
                                    {"cs_fixed", "fs_fixed", "wg_fixed", "all_free"});
  d.configuration = *parse_configuration(conf);
  d.ramp_shape = *parse_ramp_shape(r.choice("ramp", "paper", {"paper", "cubic"}));
  d.pair_motion = r.choice("pairs", "moving", {"moving", "frozen"}) == "moving" ? PairMotion::Moving : PairMotion::Frozen;
  d.pair_stiffness =
      r.choice("pair_stiffness", "teeth", {"teeth", "constant"}) == "teeth" ? PairStiffness::Teeth : PairStiffness::Constant;
  d.rim = r.choice("rim", "fem", {"fem", "rigid"}) == "fem" ? RimCoupling::Fem : RimCoupling::Rigid;
  d.compliance_phases = r.integer("compliance_phases", d.compliance_phases, std::numeric_limits<int>::min());
  d.oversampling = r.integer("oversampling", d.oversampling, std::numeric_limits<int>::min());
  d.drive_speed_rpm = r.number("drive_speed_rpm", d.drive_speed_rpm);
  d.drive_ramp_start_s = r.number("drive_ramp_start_s", d.drive_ramp_start_s);
  d.drive_ramp_end_s = r.number("drive_ramp_end_s", d.drive_ramp_end_s);
  d.load_torque_Nm = r.number("load_torque_Nm", d.load_torque_Nm);
  d.load_ramp_start_s = r.number("load_ramp_start_s", d.load_ramp_start_s);
  d.load_ramp_end_s = r.number("load_ramp_end_s", d.load_ramp_end_s);
  d.stiffness_N_per_m = r.number("stiffness_N_per_m", d.stiffness_N_per_m);
  d.stiffness_variation_N_per_m = r.number("stiffness_variation_N_per_m", d.stiffness_variation_N_per_m);
  d.stiffness_phase_deg = r.number("stiffness_phase_deg", d.stiffness_phase_deg);
  d.damping_Ns_per_m = r.number("damping_Ns_per_m", d.damping_Ns_per_m);
  d.exponent_stiffness = r.number("exponent_stiffness", d.exponent_stiffness);
  d.exponent_damping = r.number("exponent_damping", d.exponent_damping);
  d.exponent_indentation = r.number("exponent_indentation", d.exponent_indentation);
  d.flexspline_compliance_rad_per_Nm = r.number("flexspline_compliance_rad_per_Nm", d.flexspline_compliance_rad_per_Nm);
  d.flexspline_torsion_damping_Nms_per_rad =
      r.number("flexspline_torsion_damping_Nms_per_rad", d.flexspline_torsion_damping_Nms_per_rad);
  d.circular_spline_drag_Nms_per_rad = r.number("circular_spline_drag_Nms_per_rad", d.circular_spline_drag_Nms_per_rad);
  d.load_inertia_kgm2 = r.number("load_inertia_kgm2", d.load_inertia_kgm2);
  d.output_drag_coulomb_Nm = r.number("output_drag_coulomb_Nm", d.output_drag_coulomb_Nm);
  d.output_drag_viscous_Nms_per_rad = r.number("output_drag_viscous_Nms_per_rad", d.output_drag_viscous_Nms_per_rad);
  d.drag_smoothing_rad_per_s = r.number("drag_smoothing_rad_per_s", d.drag_smoothing_rad_per_s);
  d.circular_spline_outer_radius_m = r.number("circular_spline_outer_radius_mm", 0.0) * kMm;
  d.circular_spline_width_m = r.number("circular_spline_width_mm", 0.0) * kMm;
  d.base_clearance_m = r.number("base_clearance_mm", 0.0) * kMm;
  d.duration_s = r.number("duration_s", d.duration_s);
  d.output_step_s = r.number("output_step_s", d.output_step_s);
  d.steady_from_s = r.number("steady_from_s", d.steady_from_s);
  d.relative_tolerance = r.number("relative_tolerance", d.relative_tolerance);
  d.absolute_tolerance_rad = r.number("absolute_tolerance_rad", d.absolute_tolerance_rad);
  r.reject_unknown();
  return d;
}

/// Refuses a non-ASCII character outside comments, and any control character but tab, CR and LF. Every case key and
/// value is ASCII, so this loses nothing; comments keep their symbols. The reason: toml++ 3.3 (Debian 12) asks whether
/// such a character is whitespace, and for U+00A1..U+0499, U+2C6E..U+3067 and U+FE7F.. that question reaches
/// TOML_UNREACHABLE, i.e. undefined behaviour (upstream marzer/tomlplusplus#190 and #295, fixed after 3.3). Fuzzing
/// reached it after a bare key, inside a string after a NUL and inside a literal string in an array.
void require_ascii_syntax(const std::string& text, const std::string& path) {
  enum class In { Code, Comment, Basic, Literal, MultiBasic, MultiLiteral };
  In in = In::Code;
  int line = 1;
  std::size_t line_start = 0;
  auto fail = [&](std::size_t i, const std::string& what) {
    throw InputError(path + ":" + std::to_string(line) + ":" + std::to_string(i - line_start + 1) +
                     ": malformed TOML: " + what);
  };
  auto quotes_at = [&](std::size_t i, char q) {
    std::size_t n = 0;
    while (i + n < text.size() && text[i + n] == q) ++n;
    return n;
  };
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char ch = text[i];
    if (ch == '\n') {
      ++line;
      line_start = i + 1;
      if (in == In::Comment || in == In::Basic || in == In::Literal) in = In::Code;
      continue;
    }
    const auto byte = static_cast<unsigned char>(ch);
    if ((byte < 0x20 && ch != '\t' && ch != '\r') || byte == 0x7F) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "0x%02X", byte);
      fail(i, "control character " + std::string(hex) + "; TOML allows only tab, CR and LF");
    }
    if (byte >= 0x80 && in != In::Comment)
      fail(i, "non-ASCII character outside a comment; keys and values of a case are ASCII");
    switch (in) {
      case In::Code:
        if (ch == '#') in = In::Comment;
        else if (ch == '"' || ch == '\'') {
          const bool multi = quotes_at(i, ch) >= 3;
          in = ch == '"' ? (multi ? In::MultiBasic : In::Basic) : (multi ? In::MultiLiteral : In::Literal);
          if (multi) i += 2;
        }
        break;
      case In::Comment: break;
      case In::Basic:
        if (ch == '\\' && i + 1 < text.size() && text[i + 1] != '\n') ++i;
        else if (ch == '"') in = In::Code;
        break;
      case In::Literal:
        if (ch == '\'') in = In::Code;
        break;
      case In::MultiBasic:
      case In::MultiLiteral: {
        const char q = in == In::MultiBasic ? '"' : '\'';
        if (in == In::MultiBasic && ch == '\\' && i + 1 < text.size() && text[i + 1] != '\n') {
          ++i;  // an escape: \" \\ ...
        } else if (ch == q) {
          const std::size_t n = quotes_at(i, q);  // up to two quotes before the closing three belong to the string
          if (n >= 3) in = In::Code;
          i += std::min<std::size_t>(n, 5) - 1;
        }
        break;
      }
    }
  }
}

/// Calls f(); an InputError it throws about a key of the file ("table.key = value; ...", a stage's own validation)
/// gets the file and the key's line in front, as the reader's own messages have them.
template <class F>
void locating_key(const toml::table& root, const std::string& path, F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    const std::string what = e.what();
    const std::size_t dot = what.find('.'), eq = what.find(" = ");
    std::string line;
    if (dot != std::string::npos && eq != std::string::npos && dot < eq)
      if (const toml::node* table = root.get(what.substr(0, dot)); table && table->is_table())
        if (const toml::node* key = table->as_table()->get(what.substr(dot + 1, eq - dot - 1)); key && key->source().begin)
          line = ":" + std::to_string(key->source().begin.line);
    throw InputError(path + line + ": " + what);
  }
}

}  // namespace

Case parse_case(const std::string& toml_text, const std::string& path) {
  require_ascii_syntax(toml_text, path);
  toml::table root;
  try {
    root = toml::parse(toml_text, path);
  } catch (const toml::parse_error& e) {
    const auto& at = e.source().begin;
    throw InputError(path + ":" + std::to_string(at.line) + ":" + std::to_string(at.column) +
                     ": malformed TOML: " + std::string(e.description()));
  }
  Case c;
  c.path = path;
  c.stem = std::filesystem::path(path).stem().string();
  static const std::set<std::string> kTables = {"gear", "flexspline", "material", "wave_generator", "load", "mesh",
                                                "solver", "catalog", "circular_spline", "contact", "dynamics"};
  for (const auto& [key, node] : root) {
    if (!kTables.count(std::string(key.str())))
      throw InputError(path + ":" + std::to_string(node.source().begin.line) + ": [" + std::string(key.str()) +
                       "] is not a known table (allowed: [gear], [flexspline], [material], [wave_generator], "
                       "[load], [mesh], [solver], [catalog], [circular_spline], [contact], [dynamics])");
  }
  static const toml::table kEmpty;
  auto table = [&](const char* name) -> const toml::table* { return sub_table(root, name, path); };
  if (auto t = table("gear")) c.gear = read_gear(TableReader(*t, "gear", path));
  if (!table("flexspline")) throw InputError(path + ": [flexspline] is missing; every case describes its flexspline");
  c.flexspline = read_flexspline(TableReader(*table("flexspline"), "flexspline", path));
  c.material = read_material(TableReader(table("material") ? *table("material") : kEmpty, "material", path));
  if (auto t = table("wave_generator"))
    c.wave_generator = read_wave_generator(TableReader(*t, "wave_generator", path), c.flexspline.inner_radius_m);
  c.load = read_load(TableReader(table("load") ? *table("load") : kEmpty, "load", path));
  c.mesh = read_mesh(TableReader(table("mesh") ? *table("mesh") : kEmpty, "mesh", path), c.flexspline);
  c.solver = read_solver(TableReader(table("solver") ? *table("solver") : kEmpty, "solver", path));
  if (auto t = table("catalog")) c.catalog_size = read_catalog(TableReader(*t, "catalog", path));
  if (!c.load.rated_torque_Nm && c.catalog_size && catalog_drive(*c.catalog_size)->has_rated_torque()) {
    c.load.rated_torque_Nm = catalog_drive(*c.catalog_size)->rated_torque_Nm;
    c.load.rated_torque_from = "catalog size " + std::to_string(*c.catalog_size);
  }
  if (c.gear)
    c.circular_spline = read_circular_spline(
        TableReader(table("circular_spline") ? *table("circular_spline") : kEmpty, "circular_spline", path), *c.gear,
        c.flexspline.rim_width_m);
  else if (table("circular_spline"))
    throw InputError(path + ": [circular_spline] needs a [gear] table (its root circle comes from the teeth)");
  if (auto t = table("contact")) {
    c.contact = read_contact(TableReader(*t, "contact", path));
    locating_key(root, path, [&] { validate_contact_params(c.contact); });
  }
  if (auto t = table("dynamics")) {
    c.dynamics = read_dynamics(TableReader(*t, "dynamics", path));
    locating_key(root, path, [&] { validate(*c.dynamics, ""); });
  }
  if (c.flexspline.teeth != TeethModel::None && !c.gear)
    throw InputError(path + ": flexspline.teeth = \"" +
                     std::string(c.flexspline.teeth == TeethModel::Ring ? "ring" : "explicit") +
                     "\" needs a [gear] table (module and teeth), or set teeth = \"none\"");
  locating_key(root, path, [&] { validate_flexspline(c.flexspline, c.mesh); });
  if (c.solver.method == SolverMethod::Fourier && c.flexspline.teeth == TeethModel::Explicit)
    throw InputError(path + ": solver.method = \"fourier\" needs a body of revolution; flexspline.teeth = \"explicit\" "
                            "is not one (use teeth = \"ring\" or \"none\", or method = \"tet10\")");
  if (c.solver.method == SolverMethod::Fourier && c.solver.backend == SolverBackend::Petsc)
    throw InputError(path + ": solver.backend = \"petsc\" solves the TET10 model; solver.method = \"fourier\" runs in "
                            "one process (use method = \"tet10\", or backend = \"cholmod\")");
  if (c.wave_generator && c.wave_generator->axial_position_m > c.flexspline.length_m)
    throw InputError(path + ": wave_generator.axial_position_mm = " +
                     format_number(c.wave_generator->axial_position_m / kMm) +
                     "; must be <= flexspline.length_mm = " + format_number(c.flexspline.length_m / kMm));
  return c;
}

Case load_case(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open the case file (does it exist?)");
  std::stringstream text;
  text << in.rdbuf();
  return parse_case(text.str(), path);
}

namespace {

void describe_cam(std::ostringstream& s, const Cam& cam) {
  static const char* kProfiles[] = {"polar", "ellipse", "list"};
  s << "profile = \"" << kProfiles[static_cast<int>(cam.profile)] << "\"\nfit_um = " << cam.clearance_m * 1e6 << "\n";
  if (cam.points.empty()) return;
  s << "profile_points = [";
  for (std::size_t i = 0; i < cam.points.size(); ++i)
    s << (i ? ",\n  " : "\n  ") << "{angle_deg = " << cam.points[i].angle_rad / kDeg
      << ", radius_mm = " << cam.points[i].radius_m / kMm << "}";
  s << "]\n";
}

void describe_gear(std::ostringstream& s, const GearParams& g) {
  const auto mm = [](double m) { return m / kMm; };
  s << "[gear]\nmodule_mm = " << mm(g.module_m) << "\nteeth_flexspline = " << g.teeth_flexspline
    << "\nteeth_circular = " << g.teeth_circular << "\npressure_angle_deg = " << g.pressure_angle_rad / kDeg
    << "\nprofile_shift_flexspline = " << g.profile_shift_flexspline
    << "\nprofile_shift_circular = " << g.profile_shift_circular << "\ncutter_teeth = " << g.cutter_teeth
    << "\naddendum_coefficient_flexspline = " << g.addendum_coefficient_flexspline
    << "\naddendum_coefficient_circular = " << g.addendum_coefficient_circular
    << "\ndedendum_coefficient_flexspline = " << g.dedendum_coefficient_flexspline
    << "\ndedendum_coefficient_circular = " << g.dedendum_coefficient_circular
    << "\ntip_rounding_flexspline_mm = " << mm(g.tip_rounding_flexspline_m)
    << "\ntip_rounding_circular_mm = " << mm(g.tip_rounding_circular_m) << "\n";
}

void describe_wave_generator(std::ostringstream& s, const WaveGeneratorParams& w) {
  const auto mm = [](double m) { return m / kMm; };
  s << "[wave_generator]\nmodel = \"" << model_name(w.model) << "\"\n";
  std::visit(overloaded{[&](const FourForce& f) { s << "beta_deg = " << f.beta_rad / kDeg << "\n"; },
                        [&](const Rollers& r) { s << "beta_deg = " << r.beta_rad / kDeg << "\n"; },
                        [](const TwoForce&) {}, [](const GivenForces&) {}, [](const Cam&) {}},
             w.model);
  if (w.radial_deformation_m) s << "radial_deformation_mm = " << mm(*w.radial_deformation_m) << "\n";
  else s << "force_N = " << w.force_N << "\n";
  s << "axial_position_mm = " << mm(w.axial_position_m) << "\nband_width_mm = " << mm(w.band_width_m) << "\n";
  if (const Cam* cam = cam_of(w)) describe_cam(s, *cam);
  if (const auto* g = std::get_if<GivenForces>(&w.model))
    for (const auto& force : g->forces)
      s << "forces += {angle_deg = " << force.angle_rad / kDeg << ", weight = " << force.weight << "}\n";
  if (w.bearing)
    s << "bearing = {balls = " << w.bearing->balls << ", ball_diameter_mm = " << mm(w.bearing->ball_diameter_m)
      << ", inner_groove_conformity = " << w.bearing->inner_groove_conformity
      << ", outer_groove_conformity = " << w.bearing->outer_groove_conformity << "}  # pitch radius "
      << mm(w.bearing->pitch_radius_m) << " mm from the bore\n";
  else
    s << "# no bearing: the generator is rigid\n";
}

}  // namespace

std::string describe_case(const Case& c) {
  std::ostringstream s;
  const auto mm = [](double m) { return m / kMm; };
  s << "# resolved case " << c.path << " (lengths in mm, defaults filled in)\n";
  if (c.gear) describe_gear(s, *c.gear);
  const auto& f = c.flexspline;
  const bool cup = f.shape == FlexsplineShape::Cup;
  s << "[flexspline]\nshape = \"" << (cup ? "cup" : "tube") << "\"\ninner_radius_mm = " << mm(f.inner_radius_m)
    << "\nwall_thickness_mm = " << mm(f.wall_thickness_m) << "\nlength_mm = " << mm(f.length_m)
    << "\nrim_width_mm = " << mm(f.rim_width_m) << "\nrim_thickness_mm = " << mm(f.rim_thickness_m) << "\nteeth = \""
    << (f.teeth == TeethModel::None ? "none" : f.teeth == TeethModel::Ring ? "ring" : "explicit") << "\"\n";
  if (cup)
    s << "diaphragm_thickness_mm = " << mm(f.diaphragm_thickness_m) << "\nboss_radius_mm = " << mm(f.boss_radius_m)
      << "\nfillet_radius_mm = " << mm(f.fillet_radius_m) << "\n";
  s << "[material]\nyoungs_modulus_Pa = " << c.material.youngs_modulus_Pa << "\npoisson_ratio = "
    << c.material.poisson_ratio << "\ndensity_kg_m3 = " << c.material.density_kg_m3 << "\n";
  if (c.material.fatigue_limit_Pa)
    s << "fatigue_limit_MPa = " << *c.material.fatigue_limit_Pa / 1e6 << "\nultimate_strength_MPa = "
      << *c.material.ultimate_strength_Pa / 1e6 << "\n";
  if (c.wave_generator) describe_wave_generator(s, *c.wave_generator);
  s << "[load]\ntorque_Nm = " << c.load.torque_Nm << "\ntorque_loading = \""
    << (c.load.torque_loading == TorqueLoading::Uniform ? "uniform" : "engagement_zones")
    << "\"\nengagement_half_angle_deg = " << c.load.engagement_half_angle_rad / kDeg << "\n";
  if (c.load.rated_torque_Nm)
    s << "rated_torque_Nm = " << *c.load.rated_torque_Nm << "  # from " << c.load.rated_torque_from << "\n";
  if (c.catalog_size) s << "[catalog]\nsize = " << *c.catalog_size << "\n";
  if (c.circular_spline)
    s << "[circular_spline]\nouter_radius_mm = " << mm(c.circular_spline->outer_radius_m)
      << "\nwidth_mm = " << mm(c.circular_spline->width_m) << "\n";
  if (c.contact.face_slices != 1) s << "[contact]\nface_slices = " << c.contact.face_slices << "\n";
  const auto derived = [](const std::string& from) { return from.empty() ? from : "  # derived: " + from; };
  s << "[mesh]\nsize_mm = " << mm(c.mesh.size_m) << derived(c.mesh.size_from) << "\nwall_layers = "
    << c.mesh.wall_layers << derived(c.mesh.wall_layers_from) << "\ncorner_levels = " << c.mesh.corner_levels
    << derived(c.mesh.corner_levels_from) << "\nmax_radius_edge_ratio = " << c.mesh.max_radius_edge_ratio
    << "\nmin_dihedral_deg = " << c.mesh.min_dihedral_deg << "\n";
  s << "[solver]\nmethod = \"" << (c.solver.method == SolverMethod::Fourier ? "fourier" : "tet10") << "\"\n";
  if (c.solver.method == SolverMethod::Fourier) s << "harmonics = " << c.solver.harmonics << "\n";
  else s << "backend = \"" << (c.solver.backend == SolverBackend::Petsc ? "petsc" : "cholmod") << "\"\n";
  if (c.dynamics) s << describe(*c.dynamics);
  return s.str();
}

}  // namespace sw
