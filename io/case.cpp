#include "io/case.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <numbers>
#include <set>
#include <sstream>
#include <tuple>

#include <nlohmann/json.hpp>
#include <toml++/toml.h>

#include "common/error.hpp"
#include "common/overloaded.hpp"
#include "design/catalog.hpp"
#include "dynamics/model.hpp"
#include "fem/fourier_solver.hpp"
#include "generator/cam_profile.hpp"
#include "gear/tooth_profile.hpp"
#include "io/json_file.hpp"
#include "mesh/flexspline.hpp"

namespace sw {
namespace {

constexpr double kMm = 1e-3;
constexpr double kRadPerDeg = std::numbers::pi / 180.0;

std::string format_number(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

/// ":line" of a node in the file, "" for a node without one (a table made from an output's stored case).
std::string where(const toml::node* node) {
  if (!node || !node->source().begin) return "";
  return ":" + std::to_string(node->source().begin.line);
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
  /// Whether the file gives `key` in this table.
  bool given(const std::string& key) const { return table_.get(key) != nullptr; }

private:
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
    throw InputError(file + where(node) + ": " + name + " must be a table ([" + name + "])");
  return node->as_table();
}

GearParams read_gear(TableReader r) {
  GearParams g;
  g.module_m = r.number("module_mm", g.module_m / kMm) * kMm;
  g.teeth_flexspline = r.integer("teeth_flexspline", g.teeth_flexspline, 4);
  g.teeth_circular = r.integer("teeth_circular", g.teeth_circular, 5);
  g.pressure_angle_rad = r.number("pressure_angle_deg", g.pressure_angle_rad / kRadPerDeg) * kRadPerDeg;
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
  if (auto sy = r.number("yield_strength_MPa")) {
    if (!(*sy > 0)) r.fail_value("yield_strength_MPa", *sy, "must be > 0");
    if (m.ultimate_strength_Pa && !(*sy * 1e6 <= *m.ultimate_strength_Pa))
      r.fail_value("yield_strength_MPa", *sy,
                   "must be <= material.ultimate_strength_MPa = " + format_number(*m.ultimate_strength_Pa / 1e6));
    m.yield_strength_Pa = *sy * 1e6;
  }
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
    if (!cam.points.empty() && !(*angle * kRadPerDeg > cam.points.back().angle_rad))
      p.fail_value("angle_deg", *angle, "must be larger than the point before's (increasing angles)");
    if (!(*radius > 0)) p.fail_value("radius_mm", *radius, "must be > 0");
    p.reject_unknown();
    point.angle_rad = *angle * kRadPerDeg;
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
  return beta * kRadPerDeg;
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
    force.angle_rad = f.number("angle_deg", 0.0) * kRadPerDeg;
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
  l.engagement_half_angle_rad = half * kRadPerDeg;
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

/// [solver]: method "auto" (the default) takes the harmonic solver for a body of revolution and TET10 for explicit
/// teeth or the petsc backend; harmonics left out are the case's need (fem/fourier_solver.hpp default_harmonics). Both
/// resolved against the model read so far, their origins recorded in `derived`.
SolverParams read_solver(TableReader r, const FlexsplineModel& model, std::map<std::string, std::string>& derived) {
  SolverParams s;
  const std::string method = r.choice("method", "auto", {"auto", "tet10", "fourier"});
  const bool petsc = r.choice("backend", "cholmod", {"cholmod", "petsc"}) == "petsc";
  s.backend = petsc ? SolverBackend::Petsc : SolverBackend::Cholmod;
  const bool explicit_teeth = model.flexspline.teeth == TeethModel::Explicit;
  if (method == "auto") {
    s.method = explicit_teeth || petsc ? SolverMethod::Tet10 : SolverMethod::Fourier;
    derived["solver.method"] = std::string("\"auto\": ") +
                               (explicit_teeth ? "explicit teeth are no body of revolution"
                                : petsc        ? "the petsc backend solves the TET10 model"
                                               : "the flexspline is a body of revolution (teeth \"ring\" or \"none\")");
  } else {
    s.method = method == "fourier" ? SolverMethod::Fourier : SolverMethod::Tet10;
  }
  s.harmonics = r.integer("harmonics", default_harmonics(model), 0);
  if (s.harmonics > 4096) r.fail_value("harmonics", s.harmonics, "must be <= 4096");
  if (!r.given("harmonics")) derived["solver.harmonics"] = default_harmonics_origin(model);
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

/// [circular_spline] (optional keys over the design rule's defaults, contact/circular_spline.hpp); the defaults a
/// file leaves out are entered in `derived`. Its ranges: validate_circular_spline, checked by parse_case.
CircularSplineParams read_circular_spline(TableReader r, const GearParams& gear, double face_width_m,
                                          std::map<std::string, std::string>& derived) {
  const CircularSplineParams rule = default_circular_spline(gear, face_width_m);
  CircularSplineParams c;
  c.outer_radius_m = r.number("outer_radius_mm", rule.outer_radius_m / kMm) * kMm;
  c.width_m = r.number("width_mm", rule.width_m / kMm) * kMm;
  const bool outer = r.choice("mounting", to_string(rule.mounting), {"outer", "bolted_face"}) == "outer";
  c.mounting = outer ? CircularSplineMounting::Outer : CircularSplineMounting::BoltedFace;
  const double root = gear_radii(gear).root_c;
  const auto [inner, outer_bolt] = default_bolt_circles_m(root, c.outer_radius_m);
  for (const auto& [key, fraction, fallback, to] :
       {std::tuple{"bolt_circle_inner_mm", kBoltCircleInnerFraction, inner, &c.bolt_circle_inner_m},
        std::tuple{"bolt_circle_outer_mm", kBoltCircleOuterFraction, outer_bolt, &c.bolt_circle_outer_m}}) {
    if (outer && r.given(key))
      r.fail_value(key, r.number(key, 0.0), "applies to mounting = \"bolted_face\" only (mounting = \"outer\" holds "
                                            "the outside cylinder); remove it or set mounting = \"bolted_face\"");
    if (outer) continue;
    *to = r.number(key, fallback / kMm) * kMm;
    if (!r.given(key))
      derived[std::string("circular_spline.") + key] =
          format_number(fraction) + " of the way from the circular spline's root circle (r = " +
          format_number(root / kMm) + " mm) to its outer radius (design rule: the bolt heads' footprint)";
  }
  r.reject_unknown();
  if (!r.given("outer_radius_mm"))
    derived["circular_spline.outer_radius_mm"] =
        format_number(kCircularSplineOuterDiameterPerPitchDiameter / 2) + " x the pitch diameter z_c m (design rule)";
  if (!r.given("width_mm"))
    derived["circular_spline.width_mm"] = "flexspline.rim_width_mm = " + format_number(face_width_m / kMm) +
                                          " (the toothed face width)";
  return c;
}

/// The circular spline's ranges (its root circle from [gear]).
void check_circular_spline(const CircularSplineParams& c, const GearParams& gear) {
  validate_circular_spline(c, gear_radii(gear).root_c);
}

/// [contact] face_slices and friction_coefficient (their ranges: contact/contact_params.hpp, checked by parse_case with
/// the key's line).
ContactParams read_contact(TableReader r) {
  ContactParams p;
  p.face_slices = r.integer("face_slices", p.face_slices, std::numeric_limits<int>::min());
  p.friction_coefficient = r.number("friction_coefficient", p.friction_coefficient);
  r.reject_unknown();
  return p;
}

/// [lubricant]: every key but kind (default "grease") given; the ranges are common/lubricant.hpp's (validate_lubricant),
/// checked by parse_case with the key's line.
Lubricant read_lubricant(TableReader r) {
  Lubricant l;
  l.kind = r.choice("kind", l.kind, {"grease", "oil"});
  for (const char* key : {"viscosity_40C_mm2_s", "viscosity_100C_mm2_s", "temperature_C"})
    if (!r.given(key))
      throw InputError(r.file() + ": lubricant." + key + " is missing; [lubricant] gives the base oil's kinematic "
                                  "viscosities at 40 and 100 C and the temperature it works at");
  l.viscosity_40C_mm2_s = *r.number("viscosity_40C_mm2_s");
  l.viscosity_100C_mm2_s = *r.number("viscosity_100C_mm2_s");
  l.temperature_C = *r.number("temperature_C");
  r.reject_unknown();
  return l;
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

/// Calls f(); an InputError it throws about a key ("table.key = value; ...", a stage's own validation) gets the file
/// and the key's line in front, as the reader's own messages have them; about a key the file leaves out, what its
/// value was derived from and the key to write.
template <class F>
void locating_key(const toml::table& root, const std::string& path, const std::map<std::string, std::string>& derived,
                  F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    const std::string what = e.what();
    const std::size_t dot = what.find('.'), eq = what.find(" = "), semi = what.find("; ", eq);
    if (dot == std::string::npos || eq == std::string::npos || dot > eq) throw InputError(path + ": " + what);
    const std::string key = what.substr(0, eq);
    const toml::node* table = root.get(key.substr(0, dot));
    const toml::node* node = table && table->is_table() ? table->as_table()->get(key.substr(dot + 1)) : nullptr;
    if (node && node->source().begin) throw InputError(path + ":" + std::to_string(node->source().begin.line) + ": " + what);
    const auto from = derived.find(key);
    if (node || from == derived.end() || semi == std::string::npos) throw InputError(path + ": " + what);
    throw InputError(path + ": " + what.substr(0, semi) + " (not in the file: derived from " + from->second + ")" +
                     what.substr(semi) + "; write " + key + " to set it");
  }
}

toml::table parse_toml(const std::string& toml_text, const std::string& path) {
  require_ascii_syntax(toml_text, path);
  try {
    return toml::parse(toml_text, path);
  } catch (const toml::parse_error& e) {
    const auto& at = e.source().begin;
    throw InputError(path + ":" + std::to_string(at.line) + ":" + std::to_string(at.column) +
                     ": malformed TOML: " + std::string(e.description()));
  }
}

/// The case the tables of a case file give (the file's TOML, or an output's stored case).
Case case_of(const toml::table& root, const std::string& path) {
  Case c;
  c.path = path;
  c.stem = std::filesystem::path(path).stem().string();
  static const std::set<std::string> kTables = {"gear", "flexspline", "material", "wave_generator", "load", "mesh",
                                                "solver", "catalog", "circular_spline", "contact", "lubricant",
                                                "dynamics"};
  for (const auto& [key, node] : root) {
    if (!kTables.count(std::string(key.str())))
      throw InputError(path + where(&node) + ": [" + std::string(key.str()) +
                       "] is not a known table (allowed: [gear], [flexspline], [material], [wave_generator], "
                       "[load], [mesh], [solver], [catalog], [circular_spline], [contact], [lubricant], "
                       "[dynamics])");
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
  c.solver = read_solver(TableReader(table("solver") ? *table("solver") : kEmpty, "solver", path),
                         flexspline_model(c), c.derived_from);
  if (auto t = table("catalog")) c.catalog_size = read_catalog(TableReader(*t, "catalog", path));
  if (!c.load.rated_torque_Nm && c.catalog_size && catalog_drive(*c.catalog_size)->has_rated_torque()) {
    c.load.rated_torque_Nm = catalog_drive(*c.catalog_size)->rated_torque_Nm;
    c.load.rated_torque_from = "catalog size " + std::to_string(*c.catalog_size);
  }
  if (c.gear && (table("circular_spline") || c.flexspline.rim_width_m > 0)) {
    c.circular_spline = read_circular_spline(
        TableReader(table("circular_spline") ? *table("circular_spline") : kEmpty, "circular_spline", path), *c.gear,
        c.flexspline.rim_width_m, c.derived_from);
    locating_key(root, path, c.derived_from, [&] { check_circular_spline(*c.circular_spline, *c.gear); });
  } else if (table("circular_spline")) {
    throw InputError(path + ": [circular_spline] needs a [gear] table (its root circle comes from the teeth)");
  }
  if (auto t = table("contact")) {
    c.contact = read_contact(TableReader(*t, "contact", path));
    locating_key(root, path, c.derived_from, [&] { validate_contact_params(c.contact); });
  }
  if (auto t = table("lubricant")) {
    c.lubricant = read_lubricant(TableReader(*t, "lubricant", path));
    locating_key(root, path, c.derived_from, [&] { validate_lubricant(*c.lubricant, "lubricant"); });
  }
  if (auto t = table("dynamics")) {
    c.dynamics = read_dynamics(TableReader(*t, "dynamics", path));
    locating_key(root, path, c.derived_from, [&] { validate(*c.dynamics, ""); });
  }
  if (c.flexspline.teeth != TeethModel::None && !c.gear)
    throw InputError(path + ": flexspline.teeth = \"" +
                     std::string(c.flexspline.teeth == TeethModel::Ring ? "ring" : "explicit") +
                     "\" needs a [gear] table (module and teeth), or set teeth = \"none\"");
  locating_key(root, path, c.derived_from, [&] { validate_flexspline(c.flexspline, c.mesh); });
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

// ---- An output of the tool as a case file: the resolved case it stores under "case" (written by case_json below)
// goes through the same table readers, as the TOML values a case file would hold.

toml::table toml_table(const JsonIn& object);
toml::array toml_array(const JsonIn& list);

constexpr auto kInt64Max = static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max());

/// Hands `put` the TOML value of a JSON value of a stored case: objects as tables, lists as arrays, numbers as
/// integers or floats as written. null, which no case key takes, is refused naming the key.
template <class Put>
void put_toml_value(const JsonIn& v, Put&& put) {
  const nlohmann::json& j = v.value();
  if (j.is_object()) {
    put(toml_table(v));
  } else if (j.is_array()) {
    put(toml_array(v));
  } else if (j.is_string()) {
    put(j.get<std::string>());
  } else if (j.is_boolean()) {
    put(j.get<bool>());
  } else if (j.is_number_float()) {
    put(j.get<double>());
  } else if (j.is_number_integer() && (!j.is_number_unsigned() || j.get<std::uint64_t>() <= kInt64Max)) {
    put(j.get<std::int64_t>());
  } else {
    v.fail("a number, text, true/false, list or table (the value of a case key)");
  }
}

toml::table toml_table(const JsonIn& object) {
  toml::table t;
  for (const auto& item : object.value().items())
    put_toml_value(object[item.key()], [&](auto&& x) { t.insert(item.key(), std::forward<decltype(x)>(x)); });
  return t;
}

toml::array toml_array(const JsonIn& list) {
  toml::array a;
  for (const JsonIn& e : list.elements())
    put_toml_value(e, [&a](auto&& x) { a.push_back(std::forward<decltype(x)>(x)); });
  return a;
}

/// The resolved case an output of the tool stores under "case" (result.json, backlash.json, contact.json,
/// dynamics.json, reconcile.json), named after the run's folder (where a run without --out writes again).
Case load_stored_case(const std::string& path) {
  const JsonIn stored =
      JsonIn::open(path, "cannot open the output file (does it exist?)",
                   "an output of strainwave holding its resolved case (\"case\")")["case"];
  if (!stored.value().is_object())
    stored.fail("the resolved case, a table of tables (an output written before outputs stored their case names the "
                "case file only: run that file)");
  Case c = case_of(toml_table(stored), path);
  c.stem = std::filesystem::absolute(path).parent_path().filename().string();
  return c;
}

bool is_output_json(const std::string& path) { return std::filesystem::path(path).extension() == ".json"; }

std::string read_case_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open the case file (does it exist?)");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

Case parse_case(const std::string& toml_text, const std::string& path) {
  return case_of(parse_toml(toml_text, path), path);
}

Case load_case(const std::string& path) {
  if (is_output_json(path)) return load_stored_case(path);
  return parse_case(read_case_text(path), path);
}

std::string case_file_toml(const std::string& path) {
  return is_output_json(path) ? describe_case(load_stored_case(path)) : read_case_text(path);
}

// ---- The writer: the resolved case as the tables the reader reads, every key it accepts with its value (defaults
// included) in the file's units, nothing it would refuse. An ordered JSON value holds them, so tables and keys keep
// the reader's order; describe_case prints them as TOML, case_json as JSON, and both read back to the same case.

namespace {

using Tables = nlohmann::ordered_json;

/// A value in the file's unit (the reader multiplies what it reads by `unit`): the shortest decimal the reader turns
/// back into `si` exactly. A value no decimal reaches (a default derived in SI) becomes the shortest decimal of the
/// value nearest to it that one reaches (1 ulp away), which is written the same again once read back.
double file_value(double si, double unit = 1.0) {
  const double exact = si / unit;
  for (const double target : {si, exact * unit})
    for (int digits = 1; digits <= 17; ++digits) {
      char text[32];
      std::snprintf(text, sizeof text, "%.*g", digits, exact);
      if (const double v = std::strtod(text, nullptr); v * unit == target) return v;
    }
  return exact;  // not reached: `exact` itself, at 17 digits, reaches exact * unit
}

Tables gear_table(const GearParams& g) {
  return Tables::object({{"module_mm", file_value(g.module_m, kMm)},
                         {"teeth_flexspline", g.teeth_flexspline},
                         {"teeth_circular", g.teeth_circular},
                         {"pressure_angle_deg", file_value(g.pressure_angle_rad, kRadPerDeg)},
                         {"profile_shift_flexspline", g.profile_shift_flexspline},
                         {"profile_shift_circular", g.profile_shift_circular},
                         {"cutter_teeth", g.cutter_teeth},
                         {"addendum_coefficient_flexspline", g.addendum_coefficient_flexspline},
                         {"addendum_coefficient_circular", g.addendum_coefficient_circular},
                         {"dedendum_coefficient_flexspline", g.dedendum_coefficient_flexspline},
                         {"dedendum_coefficient_circular", g.dedendum_coefficient_circular},
                         {"tip_rounding_flexspline_mm", file_value(g.tip_rounding_flexspline_m, kMm)},
                         {"tip_rounding_circular_mm", file_value(g.tip_rounding_circular_m, kMm)}});
}

/// A tube has no diaphragm, boss or fillet: the reader refuses those keys for it.
Tables flexspline_table(const FlexsplineParams& f) {
  const bool cup = f.shape == FlexsplineShape::Cup;
  Tables t = Tables::object({{"shape", cup ? "cup" : "tube"},
                             {"inner_radius_mm", file_value(f.inner_radius_m, kMm)},
                             {"wall_thickness_mm", file_value(f.wall_thickness_m, kMm)},
                             {"length_mm", file_value(f.length_m, kMm)},
                             {"teeth", teeth_name(f.teeth)},
                             {"rim_width_mm", file_value(f.rim_width_m, kMm)},
                             {"rim_thickness_mm", file_value(f.rim_thickness_m, kMm)}});
  if (cup) {
    t["diaphragm_thickness_mm"] = file_value(f.diaphragm_thickness_m, kMm);
    t["boss_radius_mm"] = file_value(f.boss_radius_m, kMm);
    t["fillet_radius_mm"] = file_value(f.fillet_radius_m, kMm);
  }
  return t;
}

Tables material_table(const Material& m) {
  Tables t = Tables::object({{"youngs_modulus_Pa", m.youngs_modulus_Pa},
                             {"poisson_ratio", m.poisson_ratio},
                             {"density_kg_m3", m.density_kg_m3}});
  if (m.fatigue_limit_Pa && m.ultimate_strength_Pa) {  // both or neither (the reader's rule)
    t["fatigue_limit_MPa"] = file_value(*m.fatigue_limit_Pa, 1e6);
    t["ultimate_strength_MPa"] = file_value(*m.ultimate_strength_Pa, 1e6);
  }
  if (m.yield_strength_Pa) t["yield_strength_MPa"] = file_value(*m.yield_strength_Pa, 1e6);
  return t;
}

Tables bearing_table(const GeneratorBearing& b) {
  return Tables::object({{"balls", b.balls},
                         {"ball_diameter_mm", file_value(b.ball_diameter_m, kMm)},
                         {"inner_groove_conformity", b.inner_groove_conformity},
                         {"outer_groove_conformity", b.outer_groove_conformity}});
}

/// A list of key tables, one per element of `items`.
template <class T, class F>
Tables list_of(const std::vector<T>& items, F&& table) {
  Tables a = Tables::array();
  for (const T& item : items) a.push_back(table(item));
  return a;
}

/// The model's own keys: β of the four forces and the rollers, the given forces' list, the cam's profile (its points
/// for a list) and fit.
void put_model_keys(Tables& t, const GeneratorModel& model) {
  static const char* kProfiles[] = {"polar", "ellipse", "list"};
  const auto force = [](const WaveGeneratorForce& f) {
    return Tables::object({{"angle_deg", file_value(f.angle_rad, kRadPerDeg)}, {"weight", f.weight}});
  };
  const auto point = [](const CamPoint& p) {
    return Tables::object({{"angle_deg", file_value(p.angle_rad, kRadPerDeg)}, {"radius_mm", file_value(p.radius_m, kMm)}});
  };
  std::visit(overloaded{[&](const FourForce& f) { t["beta_deg"] = file_value(f.beta_rad, kRadPerDeg); },
                        [&](const Rollers& r) { t["beta_deg"] = file_value(r.beta_rad, kRadPerDeg); },
                        [](const TwoForce&) {},
                        [&](const GivenForces& g) { t["forces"] = list_of(g.forces, force); },
                        [&](const Cam& cam) {
                          t["profile"] = kProfiles[static_cast<int>(cam.profile)];
                          if (cam.profile == CamProfile::List) t["profile_points"] = list_of(cam.points, point);
                          t["fit_um"] = file_value(cam.clearance_m, 1e-6);
                        }},
             model);
}

/// A list cam's w0 is its radius at 0° less the bore (read back from the points, the written key matches it); only
/// the given forces take force_N.
Tables wave_generator_table(const WaveGeneratorParams& w) {
  Tables t = Tables::object({{"model", model_name(w.model)}});
  if (w.radial_deformation_m) t["radial_deformation_mm"] = file_value(*w.radial_deformation_m, kMm);
  if (!pushes_only(w.model)) t["force_N"] = w.force_N;
  t["axial_position_mm"] = file_value(w.axial_position_m, kMm);
  t["band_width_mm"] = file_value(w.band_width_m, kMm);
  put_model_keys(t, w.model);
  if (w.bearing) t["bearing"] = bearing_table(*w.bearing);
  return t;
}

Tables load_table(const LoadParams& l) {
  Tables t = Tables::object(
      {{"torque_Nm", l.torque_Nm},
       {"torque_loading", l.torque_loading == TorqueLoading::Uniform ? "uniform" : "engagement_zones"},
       {"engagement_half_angle_deg", file_value(l.engagement_half_angle_rad, kRadPerDeg)}});
  if (l.rated_torque_Nm) t["rated_torque_Nm"] = *l.rated_torque_Nm;
  return t;
}

Tables mesh_table(const MeshParams& m) {
  return Tables::object({{"size_mm", file_value(m.size_m, kMm)},
                         {"wall_layers", m.wall_layers},
                         {"corner_levels", m.corner_levels},
                         {"max_radius_edge_ratio", m.max_radius_edge_ratio},
                         {"min_dihedral_deg", m.min_dihedral_deg}});
}

Tables solver_table(const SolverParams& s) {
  return Tables::object({{"method", s.method == SolverMethod::Fourier ? "fourier" : "tet10"},
                         {"harmonics", s.harmonics},
                         {"backend", s.backend == SolverBackend::Petsc ? "petsc" : "cholmod"}});
}

Tables dynamics_table(const DynamicsParams& d) {
  return Tables::object(
      {{"configuration", to_string(d.configuration)},
       {"ramp", to_string(d.ramp_shape)},
       {"pairs", to_string(d.pair_motion)},
       {"pair_stiffness", to_string(d.pair_stiffness)},
       {"rim", to_string(d.rim)},
       {"compliance_phases", d.compliance_phases},
       {"oversampling", d.oversampling},
       {"drive_speed_rpm", d.drive_speed_rpm},
       {"drive_ramp_start_s", d.drive_ramp_start_s},
       {"drive_ramp_end_s", d.drive_ramp_end_s},
       {"load_torque_Nm", d.load_torque_Nm},
       {"load_ramp_start_s", d.load_ramp_start_s},
       {"load_ramp_end_s", d.load_ramp_end_s},
       {"stiffness_N_per_m", d.stiffness_N_per_m},
       {"stiffness_variation_N_per_m", d.stiffness_variation_N_per_m},
       {"stiffness_phase_deg", d.stiffness_phase_deg},
       {"damping_Ns_per_m", d.damping_Ns_per_m},
       {"exponent_stiffness", d.exponent_stiffness},
       {"exponent_damping", d.exponent_damping},
       {"exponent_indentation", d.exponent_indentation},
       {"flexspline_compliance_rad_per_Nm", d.flexspline_compliance_rad_per_Nm},
       {"flexspline_torsion_damping_Nms_per_rad", d.flexspline_torsion_damping_Nms_per_rad},
       {"circular_spline_drag_Nms_per_rad", d.circular_spline_drag_Nms_per_rad},
       {"load_inertia_kgm2", d.load_inertia_kgm2},
       {"output_drag_coulomb_Nm", d.output_drag_coulomb_Nm},
       {"output_drag_viscous_Nms_per_rad", d.output_drag_viscous_Nms_per_rad},
       {"drag_smoothing_rad_per_s", d.drag_smoothing_rad_per_s},
       {"circular_spline_outer_radius_mm", file_value(d.circular_spline_outer_radius_m, kMm)},
       {"circular_spline_width_mm", file_value(d.circular_spline_width_m, kMm)},
       {"base_clearance_mm", file_value(d.base_clearance_m, kMm)},
       {"duration_s", d.duration_s},
       {"output_step_s", d.output_step_s},
       {"steady_from_s", d.steady_from_s},
       {"relative_tolerance", d.relative_tolerance},
       {"absolute_tolerance_rad", d.absolute_tolerance_rad}});
}

/// [circular_spline]: the bolt circles only for a ring bolted by its face.
Tables circular_spline_table(const CircularSplineParams& c) {
  Tables t = Tables::object({{"outer_radius_mm", file_value(c.outer_radius_m, kMm)},
                             {"width_mm", file_value(c.width_m, kMm)},
                             {"mounting", to_string(c.mounting)}});
  if (c.mounting == CircularSplineMounting::BoltedFace) {
    t["bolt_circle_inner_mm"] = file_value(c.bolt_circle_inner_m, kMm);
    t["bolt_circle_outer_mm"] = file_value(c.bolt_circle_outer_m, kMm);
  }
  return t;
}

/// Every table of the case in the order of a case file, optional tables when the case has them.
Tables case_tables(const Case& c) {
  Tables t = Tables::object();
  if (c.gear) t["gear"] = gear_table(*c.gear);
  t["flexspline"] = flexspline_table(c.flexspline);
  t["material"] = material_table(c.material);
  if (c.wave_generator) t["wave_generator"] = wave_generator_table(*c.wave_generator);
  t["load"] = load_table(c.load);
  if (c.catalog_size) t["catalog"] = Tables::object({{"size", *c.catalog_size}});
  if (c.circular_spline) t["circular_spline"] = circular_spline_table(*c.circular_spline);
  t["contact"] = Tables::object(
      {{"face_slices", c.contact.face_slices}, {"friction_coefficient", c.contact.friction_coefficient}});
  if (c.lubricant)
    t["lubricant"] = Tables::object({{"kind", c.lubricant->kind},
                                     {"viscosity_40C_mm2_s", c.lubricant->viscosity_40C_mm2_s},
                                     {"viscosity_100C_mm2_s", c.lubricant->viscosity_100C_mm2_s},
                                     {"temperature_C", c.lubricant->temperature_C}});
  t["mesh"] = mesh_table(c.mesh);
  t["solver"] = solver_table(c.solver);
  if (c.dynamics) t["dynamics"] = dynamics_table(*c.dynamics);
  return t;
}

/// A value of the tables as TOML: a number as the shortest text that reads back to it, an object as an inline table,
/// a list one element to a line.
std::string toml_text(const Tables& v) {
  if (v.is_number_float()) {
    char text[32];
    return std::string(text, std::to_chars(text, text + sizeof text, v.get<double>()).ptr);
  }
  if (v.is_object()) {
    std::string s;
    for (const auto& item : v.items()) s += (s.empty() ? "{" : ", ") + item.key() + " = " + toml_text(item.value());
    return s.empty() ? "{}" : s + "}";
  }
  if (v.is_array()) {
    std::string s = "[";
    for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ",\n  " : "\n  ") + toml_text(v[i]);
    return s + "]";
  }
  return v.dump();  // text, integers, true/false: JSON and TOML spell them alike
}

/// Where a value came from, printed beside its key ("table.key" -> note).
std::map<std::string, std::string> case_notes(const Case& c) {
  std::map<std::string, std::string> notes;
  if (c.load.rated_torque_Nm) notes["load.rated_torque_Nm"] = "from " + c.load.rated_torque_from;
  if (c.wave_generator && c.wave_generator->bearing)
    notes["wave_generator.bearing"] =
        "pitch radius " + format_number(c.wave_generator->bearing->pitch_radius_m / kMm) + " mm from the bore";
  else if (c.wave_generator)
    notes["wave_generator.model"] = "no bearing: the generator is rigid";
  for (const auto& [key, from] : c.derived_from) notes[key] = "derived from " + from;
  for (const auto& [key, from] : {std::pair{"mesh.size_mm", &c.mesh.size_from},
                                  std::pair{"mesh.wall_layers", &c.mesh.wall_layers_from},
                                  std::pair{"mesh.corner_levels", &c.mesh.corner_levels_from}})
    if (!from->empty()) notes[key] = "derived: " + *from;
  return notes;
}

}  // namespace

std::string describe_case(const Case& c) {
  const std::map<std::string, std::string> notes = case_notes(c);
  const Tables tables = case_tables(c);
  std::string s = "# resolved case " + c.path + " (lengths in mm, defaults filled in)\n";
  for (const auto& table : tables.items()) {
    s += "[" + table.key() + "]\n";
    for (const auto& key : table.value().items()) {
      s += key.key() + " = " + toml_text(key.value());
      if (const auto note = notes.find(table.key() + "." + key.key()); note != notes.end()) s += "  # " + note->second;
      s += "\n";
    }
  }
  return s;
}

std::string describe_derived(const Case& c) {
  const Tables tables = case_tables(c);
  std::string s;
  for (const auto& [key, note] : case_notes(c)) {
    const std::size_t dot = key.find('.');
    const std::string table = key.substr(0, dot), name = key.substr(dot + 1);
    if (!tables.contains(table) || !tables[table].contains(name)) continue;  // a table the case does not have
    if (note == "from the case file") continue;                              // given, only said where
    s += "  " + key + " = " + toml_text(tables[table][name]) + "  # " + note + "\n";
  }
  return s;
}

std::string case_json(const Case& c) { return case_tables(c).dump(); }

}  // namespace sw
