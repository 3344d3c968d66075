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
#include "fem/flexspline_model.hpp"
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

  /// An integer the table gives (its range is the schema's, checked by the stage's validation), else nullopt.
  std::optional<int> integer(const std::string& key) {
    if (!given(key)) {
      used_.insert(key);
      return std::nullopt;
    }
    return integer(key, 0, std::numeric_limits<int>::min());
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

/// Reads key `k` of the schema into `t` when the table gives it, as the key's type (number, integer, one of its
/// words); its range is the stage's validation's, which case_of runs after the table is read (locating_key).
template <class T>
void read_key(TableReader& r, T& t, const CaseKey<T>& k) {
  switch (k.kind) {
    case KeyKind::Number:
      if (const auto v = r.number(k.name)) k.set(t, *v);
      break;
    case KeyKind::Integer:
      if (const auto v = r.integer(k.name)) k.set(t, static_cast<long long>(*v));
      break;
    case KeyKind::Choice:
      if (const std::string w = r.choice(k.name, "", k.choices); !w.empty()) k.set(t, w);
      break;
    case KeyKind::List:
    case KeyKind::Table:
      throw std::logic_error("case key " + k.name + " is read by its table's own reader");
  }
}

/// Every key of the schema that applies to `t` as read so far, in the schema's order.
template <class T>
void read_keys(TableReader& r, T& t, const std::vector<CaseKey<T>>& keys) {
  for (const CaseKey<T>& k : keys)
    if (k.applies_to(t)) read_key(r, t, k);
}

/// Throws "<file>: <table>.<key> is missing; <why>" for the first key the schema requires that the table leaves out.
template <class T>
void require_keys(const TableReader& r, const std::vector<CaseKey<T>>& keys, const std::string& why) {
  for (const CaseKey<T>& k : keys)
    if (k.required() && !r.given(k.name))
      throw InputError(r.file() + ": " + r.name() + "." + k.name + " is missing; " + why);
}

GearParams read_gear(TableReader r) {
  GearParams g;
  read_keys(r, g, gear_keys());
  r.reject_unknown();
  return g;
}

FlexsplineParams read_flexspline(TableReader r) {
  const auto& keys = flexspline_keys();
  FlexsplineParams f;
  // Ranges and consistency: mesh/flexspline_params.hpp validate_flexspline, once the mesh table is read (parse_case).
  for (const char* key : {"shape", "inner_radius_mm", "wall_thickness_mm", "length_mm"})
    read_key(r, f, key_named(keys, key));
  f.teeth = f.shape == FlexsplineShape::Cup ? TeethModel::Ring : TeethModel::None;
  read_key(r, f, key_named(keys, "teeth"));
  if (f.teeth != TeethModel::None) {
    for (const char* key : {"rim_width_mm", "rim_thickness_mm"}) read_key(r, f, key_named(keys, key));
  } else {  // without teeth there is no rim: its keys are accepted when >= 0 and not used
    f.rim_width_m = r.non_negative("rim_width_mm", 0.0) * kMm;
    const auto t = r.number("rim_thickness_mm");
    if (t && !(*t >= 0)) r.fail_value("rim_thickness_mm", *t, "must be >= 0");
    f.rim_thickness_m = t ? *t * kMm : f.wall_thickness_m;
  }
  // A tube has no diaphragm, boss or fillet: those keys do not apply to it and are rejected as unknown.
  for (const char* key : {"diaphragm_thickness_mm", "boss_radius_mm", "fillet_radius_mm"})
    if (key_named(keys, key).applies_to(f)) read_key(r, f, key_named(keys, key));
  r.reject_unknown();
  return f;
}

Material read_material(TableReader r) {
  Material m;
  read_keys(r, m, material_keys());
  r.reject_unknown();
  return m;
}

/// wave_generator.bearing = {balls, ball_diameter_mm, inner_groove_conformity, outer_groove_conformity}; the pitch
/// radius follows from the flexspline's bore (generator/generator_bearing.hpp), and the bearing checks itself.
GeneratorBearing read_bearing(TableReader r, double bore_radius_m) {
  GeneratorBearing b;
  require_keys(r, generator_bearing_keys(), "a bearing needs balls and ball_diameter_mm");
  read_keys(r, b, generator_bearing_keys());
  r.reject_unknown();
  b.pitch_radius_m = bearing_pitch_radius_m(bore_radius_m, b.ball_diameter_m);
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
  read_keys(r, l, load_keys());
  if (l.rated_torque_Nm) l.rated_torque_from = "the case file";
  r.reject_unknown();
  return l;
}

/// The keys the table gives; derive_mesh (mesh/flexspline_params.hpp) derives the others from the flexspline.
MeshParams read_mesh(TableReader r, const FlexsplineParams& f) {
  // size_mm, wall_layers and corner_levels: their ranges are the mesh's (mesh/flexspline_params.hpp wall_size,
  // mesh/flexspline_sizes.hpp corner_levels), checked with the flexspline's.
  MeshKeysGiven given;
  if (const auto size = r.number("size_mm")) given.size_m = *size * kMm;
  given.wall_layers = r.integer("wall_layers");
  given.corner_levels = r.integer("corner_levels");
  MeshParams m = derive_mesh(f, given);
  for (const char* quality : {"max_radius_edge_ratio", "min_dihedral_deg"})
    read_key(r, m, key_named(mesh_keys(), quality));  // their ranges: validate_mesh, with the flexspline's
  r.reject_unknown();
  return m;
}

/// [solver]: method "auto" (the default) takes the harmonic solver for a body of revolution and TET10 for explicit
/// teeth or the petsc backend; harmonics left out are the case's need (fem/flexspline_model.hpp default_harmonics).
/// Both resolved against the model read so far, their origins recorded in `derived`.
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
                                               : "the flexspline is a body of revolution (teeth \"ring\", \"layer\" "
                                                 "or \"none\")");
  } else {
    s.method = method == "fourier" ? SolverMethod::Fourier : SolverMethod::Tet10;
  }
  s.harmonics = default_harmonics(model);
  read_key(r, s, key_named(solver_keys(), "harmonics"));
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
  read_keys(r, p, contact_keys());
  r.reject_unknown();
  return p;
}

/// [lubricant]: every key but kind (default "grease") given; the ranges are common/lubricant.hpp's (validate_lubricant),
/// checked by parse_case with the key's line.
Lubricant read_lubricant(TableReader r) {
  Lubricant l;
  require_keys(r, lubricant_keys(), "[lubricant] gives the base oil's kinematic viscosities at 40 and 100 C and the "
                                    "temperature it works at");
  read_keys(r, l, lubricant_keys());
  r.reject_unknown();
  return l;
}

/// [dynamics]: the keys' types here; their ranges are the dynamics stage's own (dynamics/model.hpp validate), checked
/// by parse_case with the key's line.
DynamicsParams read_dynamics(TableReader r) {
  DynamicsParams d;
  read_keys(r, d, dynamics_keys());
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
    const toml::node* node = &root;  // down the key's dotted path: table.key, table.inline_table.key
    for (std::size_t from = 0; node && from <= key.size();) {
      const std::size_t to = std::min(key.find('.', from), key.size());
      node = node->is_table() ? node->as_table()->get(key.substr(from, to - from)) : nullptr;
      from = to + 1;
    }
    if (const std::string at = where(node); !at.empty()) throw InputError(path + at + ": " + what);
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
  // Each stage validates what its table gave (ranges from its schema, then its rules between keys); a message about a
  // key gets the file and the key's line in front (locating_key).
  const auto validated = [&](auto&& validate) { locating_key(root, path, c.derived_from, validate); };
  if (auto t = table("gear")) {
    c.gear = read_gear(TableReader(*t, "gear", path));
    validated([&] { validate_gear(*c.gear); });  // gear/ owns the ranges and the consistency of a set that can be made
  }
  if (!table("flexspline")) throw InputError(path + ": [flexspline] is missing; every case describes its flexspline");
  c.flexspline = read_flexspline(TableReader(*table("flexspline"), "flexspline", path));
  c.material = read_material(TableReader(table("material") ? *table("material") : kEmpty, "material", path));
  validated([&] { validate_material(c.material); });
  if (auto t = table("wave_generator")) {
    c.wave_generator = read_wave_generator(TableReader(*t, "wave_generator", path), c.flexspline.inner_radius_m);
    if (c.wave_generator->bearing) validated([&] { validate_generator_bearing(*c.wave_generator->bearing); });
  }
  c.load = read_load(TableReader(table("load") ? *table("load") : kEmpty, "load", path));
  validated([&] { check_key_ranges(c.load, load_keys(), "load"); });
  c.mesh = read_mesh(TableReader(table("mesh") ? *table("mesh") : kEmpty, "mesh", path), c.flexspline);
  c.solver = read_solver(TableReader(table("solver") ? *table("solver") : kEmpty, "solver", path),
                         flexspline_model(c), c.derived_from);
  validated([&] { check_key_ranges(c.solver, solver_keys(), "solver"); });
  if (auto t = table("catalog")) c.catalog_size = read_catalog(TableReader(*t, "catalog", path));
  if (!c.load.rated_torque_Nm && c.catalog_size && catalog_drive(*c.catalog_size)->has_rated_torque()) {
    c.load.rated_torque_Nm = catalog_drive(*c.catalog_size)->rated_torque_Nm;
    c.load.rated_torque_from = "catalog size " + std::to_string(*c.catalog_size);
  }
  if (c.gear && (table("circular_spline") || c.flexspline.rim_width_m > 0)) {
    c.circular_spline = read_circular_spline(
        TableReader(table("circular_spline") ? *table("circular_spline") : kEmpty, "circular_spline", path), *c.gear,
        c.flexspline.rim_width_m, c.derived_from);
    validated([&] { check_circular_spline(*c.circular_spline, *c.gear); });
  } else if (table("circular_spline")) {
    throw InputError(path + ": [circular_spline] needs a [gear] table (its root circle comes from the teeth)");
  }
  if (auto t = table("contact")) {
    c.contact = read_contact(TableReader(*t, "contact", path));
    validated([&] { validate_contact_params(c.contact); });
  }
  if (auto t = table("lubricant")) {
    c.lubricant = read_lubricant(TableReader(*t, "lubricant", path));
    validated([&] { validate_lubricant(*c.lubricant, "lubricant"); });
  }
  if (auto t = table("dynamics")) {
    c.dynamics = read_dynamics(TableReader(*t, "dynamics", path));
    validated([&] { validate(*c.dynamics, ""); });
  }
  if (c.flexspline.teeth != TeethModel::None && !c.gear)
    throw InputError(path + ": flexspline.teeth = \"" +
                     std::string(teeth_name(c.flexspline.teeth)) +
                     "\" needs a [gear] table (module and teeth), or set teeth = \"none\"");
  validated([&] { validate_flexspline(c.flexspline, c.mesh); });
  if (c.solver.method == SolverMethod::Fourier && c.flexspline.teeth == TeethModel::Explicit)
    throw InputError(path + ": solver.method = \"fourier\" needs a body of revolution; flexspline.teeth = \"explicit\" "
                            "is not one (use teeth = \"ring\" or \"none\", or method = \"tet10\")");
  if (c.solver.method == SolverMethod::Tet10 && c.flexspline.teeth == TeethModel::Layer)
    throw InputError(path + ": solver.method = \"tet10\" meshes the teeth as solids or a ring; flexspline.teeth = "
                            "\"layer\" is the harmonic solver's (use method = \"fourier\", or teeth = \"explicit\")");
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

/// The keys of the schema that apply to `t`, with their values in the file's units, in the schema's order.
template <class T>
Tables key_table(const T& t, const std::vector<CaseKey<T>>& keys) {
  Tables o = Tables::object();
  for (const CaseKey<T>& k : keys)
    if (k.applies_to(t))
      if (const std::optional<KeyValue> v = k.get(t)) std::visit([&](const auto& x) { o[k.name] = x; }, *v);
  return o;
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
    return Tables::object({{"angle_deg", file_units(f.angle_rad, kRadPerDeg)}, {"weight", f.weight}});
  };
  const auto point = [](const CamPoint& p) {
    return Tables::object({{"angle_deg", file_units(p.angle_rad, kRadPerDeg)}, {"radius_mm", file_units(p.radius_m, kMm)}});
  };
  std::visit(overloaded{[&](const FourForce& f) { t["beta_deg"] = file_units(f.beta_rad, kRadPerDeg); },
                        [&](const Rollers& r) { t["beta_deg"] = file_units(r.beta_rad, kRadPerDeg); },
                        [](const TwoForce&) {},
                        [&](const GivenForces& g) { t["forces"] = list_of(g.forces, force); },
                        [&](const Cam& cam) {
                          t["profile"] = kProfiles[static_cast<int>(cam.profile)];
                          if (cam.profile == CamProfile::List) t["profile_points"] = list_of(cam.points, point);
                          t["fit_um"] = file_units(cam.clearance_m, 1e-6);
                        }},
             model);
}

/// A list cam's w0 is its radius at 0° less the bore (read back from the points, the written key matches it); only
/// the given forces take force_N.
Tables wave_generator_table(const WaveGeneratorParams& w) {
  Tables t = Tables::object({{"model", model_name(w.model)}});
  if (w.radial_deformation_m) t["radial_deformation_mm"] = file_units(*w.radial_deformation_m, kMm);
  if (!pushes_only(w.model)) t["force_N"] = w.force_N;
  t["axial_position_mm"] = file_units(w.axial_position_m, kMm);
  t["band_width_mm"] = file_units(w.band_width_m, kMm);
  put_model_keys(t, w.model);
  if (w.bearing) t["bearing"] = key_table(*w.bearing, generator_bearing_keys());
  return t;
}

/// Every table of the case in the order of a case file, optional tables when the case has them.
Tables case_tables(const Case& c) {
  Tables t = Tables::object();
  if (c.gear) t["gear"] = key_table(*c.gear, gear_keys());
  t["flexspline"] = key_table(c.flexspline, flexspline_keys());
  t["material"] = key_table(c.material, material_keys());
  if (c.wave_generator) t["wave_generator"] = wave_generator_table(*c.wave_generator);
  t["load"] = key_table(c.load, load_keys());
  if (c.catalog_size) t["catalog"] = Tables::object({{"size", *c.catalog_size}});
  if (c.circular_spline) t["circular_spline"] = key_table(*c.circular_spline, circular_spline_keys());
  t["contact"] = key_table(c.contact, contact_keys());
  if (c.lubricant) t["lubricant"] = key_table(*c.lubricant, lubricant_keys());
  t["mesh"] = key_table(c.mesh, mesh_keys());
  t["solver"] = key_table(c.solver, solver_keys());
  if (c.dynamics) t["dynamics"] = key_table(*c.dynamics, dynamics_keys());
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

Provenance provenance_of(const Case& c) {  // keys sorted (nlohmann::json, not ordered_json)
  return {nlohmann::json::parse(case_json(c)).dump(), tool_version()};
}

namespace {

/// One table of the keys reference: a row per key with its unit, default, range and meaning.
template <class T>
std::string reference_table(const std::string& table, const std::string& about, const std::vector<CaseKey<T>>& keys) {
  std::string s = "## [" + table + "]\n\n" + about +
                  "\n\n| key | unit | default | range | meaning |\n|---|---|---|---|---|\n";
  const T defaults{};
  for (const CaseKey<T>& k : keys) {
    std::string range = k.range.text();
    if (k.kind == KeyKind::Choice) {
      range = "one of";
      for (std::size_t i = 0; i < k.choices.size(); ++i) range += (i ? ", \"" : " \"") + k.choices[i] + "\"";
    } else if (k.kind == KeyKind::List) {
      range = "a list of tables";
    } else if (k.kind == KeyKind::Table) {
      range = "a table";
    } else if (k.kind == KeyKind::Integer) {
      range = range.empty() ? "an integer" : "an integer " + range;
    }
    if (!k.range.why.empty()) range += " (" + k.range.why + ")";
    std::string fallback = k.default_rule;
    if (fallback.empty()) {
      const std::optional<KeyValue> v = k.get(defaults);
      fallback = v ? key_value_toml(*v) : "none";
    }
    std::string meaning = k.meaning;
    if (!k.applies_when.empty()) meaning += "; only with " + k.applies_when;
    auto cell = [](std::string text) {
      for (std::size_t at = text.find('|'); at != std::string::npos; at = text.find('|', at + 2))
        text.replace(at, 1, "\\|");
      return text;
    };
    s += "| `" + k.name + "` | " + cell(k.unit) + " | " + cell(fallback) + " | " + cell(range) + " | " + cell(meaning) +
         " |\n";
  }
  return s + "\n";
}

}  // namespace

std::string case_keys_reference() {
  std::string s =
      "# Case keys: the reference\n\n"
      "Every key of a case file, by table, as the tool's schema holds it (written by `strainwave keys`; a test holds "
      "this page to it). Units are the file's; a default in words is derived from other keys or tables. A key out of "
      "its range, of the wrong type or unknown to its table is refused naming the file, the line, the key, the "
      "value and what was expected. What the keys mean for the physics: [case-keys.md](case-keys.md).\n\n";
  s += reference_table("gear", "The gear set; defaults: the seed gear. Optional for a flexspline without teeth.",
                       gear_keys());
  s += reference_table("flexspline", "The flexspline's geometry (required); the ranges between its keys are checked "
                                     "together with the mesh's.",
                       flexspline_keys());
  s += reference_table("material", "The steel of the drive's parts.", material_keys());
  s += reference_table("wave_generator",
                       "The generator; optional (without it the flexspline is loaded by torque only).",
                       wave_generator_keys());
  s += reference_table("wave_generator.bearing", "Written inline: `bearing = {balls = 15, ball_diameter_mm = 3.175}`.",
                       generator_bearing_keys());
  s += reference_table("load", "The FEM's torque and the contact's rated torque.", load_keys());
  s += "## [catalog]\n\n| key | unit | default | range | meaning |\n|---|---|---|---|---|\n| `size` |  | required | "
       "one of " + catalog_sizes_text() + " | the catalog size the case is held against (its rated torque, T1, T2, "
       "stiffness) |\n\n";
  s += reference_table("circular_spline", "The circular spline's ring (needs [gear]); present by default when the "
                                          "flexspline has teeth.",
                       circular_spline_keys());
  s += reference_table("contact", "The loaded contact.", contact_keys());
  s += reference_table("lubricant", "Optional: the lubricant the losses are computed with.", lubricant_keys());
  s += reference_table("mesh", "The TET10 mesh and the harmonic section's grading.", mesh_keys());
  s += reference_table("solver", "How the flexspline is solved.", solver_keys());
  s += reference_table("dynamics", "Optional: the multibody run of `strainwave dynamics`.", dynamics_keys());
  return s;
}

}  // namespace sw
