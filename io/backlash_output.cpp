#include "io/backlash_output.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

#include <nlohmann/json.hpp>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataWriter.h>

#include "common/constants.hpp"
#include "common/error.hpp"
#include "common/svg_plot.hpp"
#include "io/atomic_file.hpp"
#include "io/json_file.hpp"

namespace sw {

namespace {


double change_percent(double basic, double comp) { return basic != 0 ? 100.0 * (comp - basic) / std::abs(basic) : 0.0; }


BacklashResult::Side side_figures(const FlankClearance& c) {
  return {c.clearance_m * 1e6, c.lever_arm_m * 1e3, std::string(part_name(c.part_f)) + " / " + part_name(c.part_c)};
}

BacklashResult::Pair pair_figures(const PairClearance& p) {
  BacklashResult::Pair o;
  o.phi_deg = p.phi_rad * kDeg;
  o.in_mesh = p.engaged;
  o.depth_mm = p.depth_m * 1e3;
  o.j_t1_mm = p.ccw.clearance_m * 1e3;
  o.j_t2_mm = p.cw.clearance_m * 1e3;
  o.total_play_um = p.total_play_m() * 1e6;
  o.t1 = side_figures(p.ccw);
  o.t2 = side_figures(p.cw);
  return o;
}

BacklashResult::Geometry geometry_figures(const GeometryCheck& g) {
  const auto& r = g.radii;
  BacklashResult::Geometry o;
  o.flexspline = {r.tip_f * 1e3, r.root_f * 1e3, r.form_f * 1e3};
  o.circular_spline = {r.tip_c * 1e3, r.root_c * 1e3, r.form_c * 1e3};
  o.w_major_axis_mm = g.w_major_m * 1e3;
  o.w_minor_axis_mm = g.w_minor_m * 1e3;
  o.working_depth_mm = g.working_depth_m * 1e3;
  o.two_w0_mm = g.two_w0_m * 1e3;
  o.minor_axis_tip_clearance_mm = g.minor_axis_tip_clearance_m * 1e3;
  o.major_axis_tip_to_root_mm = g.major_axis_tip_root_m * 1e3;
  o.major_axis_root_to_tip_mm = g.major_axis_root_tip_m * 1e3;
  o.major_axis_pair = pair_figures(g.major_axis);
  o.major_axis_play_arcmin = g.major_axis_play_rad * kArcmin;
  o.interference_at_rest = g.interference;
  o.smallest_clearance_um = g.worst_clearance_m * 1e6;
  o.smallest_clearance_at = pair_figures(g.worst);
  if (g.interference)
    o.remedy = BacklashResult::Remedy{
        g.addendum_scale_free, g.addendum_free_flexspline, g.addendum_free_circular,
        {g.w0_scale_free_lo, g.w0_scale_free_hi},
        "largest common factor on both addenda, and the range of factors on the generator's deformation w0, that "
        "leave no interference (0: none found)"};
  return o;
}

BacklashResult::Row table_row(const BacklashTableRow& row, double module_m) {
  BacklashResult::Row e;
  e.position_deg = row.position_deg;
  e.in_mesh = row.basic.engaged;
  if (row.basic.engaged) {
    const double b = row.basic.backlash_m() / module_m, c = row.compensated.backlash_m() / module_m;
    e.basic_over_m = b;
    e.compensated_over_m = c;
    e.change_percent = change_percent(b, c);
    e.compensated_state = b < 0 ? "interference (basic model)" : c <= 0 ? "loaded flank in contact" : "clearance";
  } else {
    e.compensated_state = "not in mesh";  // the teeth face tip to tip: there is no backlash
  }
  e.basic = pair_figures(row.basic);
  e.compensated = pair_figures(row.compensated);
  return e;
}

BacklashResult::MeshAt mesh_at(const MeshState& st) {
  BacklashResult::MeshAt m;
  m.wg_deg = st.wg_angle_rad * kDeg;
  m.pairs_in_mesh = st.engaged_pairs;
  m.min_backlash_um = st.min_backlash_m * 1e6;
  m.angular_play_arcmin = st.angular_play_rad() * kArcmin;
  m.closing_t1_arcmin = st.closing_ccw_rad * kArcmin;
  m.closing_t2_arcmin = st.closing_cw_rad * kArcmin;
  m.pairs_within_1_5_10_um_t1 = {st.near_ccw[0], st.near_ccw[1], st.near_ccw[2]};
  m.pairs_within_1_5_10_um_t2 = {st.near_cw[0], st.near_cw[1], st.near_cw[2]};
  return m;
}

BacklashResult::Revolution revolution_figures(const RevolutionSweep& rb, const RevolutionSweep& rc) {
  BacklashResult::Revolution v;
  v.steps = rb.wg_angle_rad.size();
  v.distinct_positions = rb.distinct_positions;
  v.min_basic_at_wg_deg = rb.min_at_rad * kDeg;
  v.min_compensated_at_wg_deg = rc.min_at_rad * kDeg;
  v.engaged_pairs = {rb.engaged_pairs_min, rb.engaged_pairs_max};
  v.definition = "min over pairs in the mesh zone (flexspline tip beyond the circular-spline tip circle) of "
                 "min(j_t1, j_t2), then min/max over the revolution";
  for (const MeshState& st : rb.period) v.period_basic.push_back(mesh_at(st));
  return v;
}

/// Where the unloaded teeth (basic model) interfere, over the pairs in the mesh zone.
std::vector<BacklashResult::Location> interference_locations(const std::vector<PairClearance>& positions) {
  std::vector<BacklashResult::Location> locs;
  for (const auto& p : positions)
    if (p.engaged)
      for (const auto& i : interferences(p))
        locs.push_back({i.phi_rad * kDeg, p.position_deg, i.where, i.depth_m * 1e6, i.point.x() * 1e3,
                        i.point.y() * 1e3});
  return locs;
}

}  // namespace

namespace {

/// Angle of a tooth from the nearer end of the major axis, degrees, signed (counter-clockwise positive).
double from_major_axis_deg(double phi_rad) {
  const double a = std::abs(phi_rad) > 0.5 * kPi ? std::remainder(phi_rad - kPi, 2.0 * kPi) : phi_rad;
  return a * kDeg;
}

}  // namespace

std::string geometry_check_text(const GeometryCheck& g, double module_m) {
  const auto& r = g.radii;
  char buf[2048];
  std::string out;
  auto line = [&](const char* fmt, auto... args) {
    std::snprintf(buf, sizeof buf, fmt, args...);
    out += buf;
  };
  line("  geometry check (basic model, no load):\n");
  line("    tip / root radius: flexspline %.4f / %.4f mm, circular spline %.4f / %.4f mm\n", r.tip_f * 1e3,
       r.root_f * 1e3, r.tip_c * 1e3, r.root_c * 1e3);
  line("    neutral curve w: %+.4f mm at the major axis, %+.4f mm at the minor axis\n", g.w_major_m * 1e3,
       g.w_minor_m * 1e3);
  line("    working depth at the major axis %.4f mm (%.2f m) against 2*w0 = %.4f mm; tips %s at the minor axis "
       "(%+.4f mm)\n", g.working_depth_m * 1e3, g.working_depth_m / module_m, g.two_w0_m * 1e3,
       g.minor_axis_tip_clearance_m > 0 ? "clear" : "DO NOT clear", g.minor_axis_tip_clearance_m * 1e3);
  line("    radial clearance at the major axis: flexspline tip to circular-spline root %+.4f mm, circular-spline "
       "tip to flexspline root %+.4f mm\n", g.major_axis_tip_root_m * 1e3, -g.major_axis_root_tip_m * 1e3);
  line("    major-axis pair: j_t1 %.3f um, j_t2 %.3f um, dead band %.3f arcmin of output rotation\n",
       g.major_axis.ccw.clearance_m * 1e6, g.major_axis.cw.clearance_m * 1e6, g.major_axis_play_rad * kArcmin);
  if (!g.interference) {
    line("    no interference at rest: smallest clearance %.3f um (pair %+.2f deg from the major axis, %s / %s)\n",
         g.worst_clearance_m * 1e6, from_major_axis_deg(g.worst.phi_rad),
         part_name((g.worst.ccw.clearance_m < g.worst.cw.clearance_m ? g.worst.ccw : g.worst.cw).part_f),
         part_name((g.worst.ccw.clearance_m < g.worst.cw.clearance_m ? g.worst.ccw : g.worst.cw).part_c));
    return out;
  }
  const FlankClearance& w = g.worst.ccw.clearance_m < g.worst.cw.clearance_m ? g.worst.ccw : g.worst.cw;
  line("    INTERFERENCE at rest: %.3f um deep, pair %+.2f deg from the major axis (flexspline %s into "
       "circular-spline %s)\n", -g.worst_clearance_m * 1e6, from_major_axis_deg(g.worst.phi_rad), part_name(w.part_f),
       part_name(w.part_c));
  if (g.addendum_scale_free > 0)
    line("    remedy: addenda x %.3f or less (addendum_coefficient_flexspline <= %.3f, _circular <= %.3f)\n",
         g.addendum_scale_free, g.addendum_free_flexspline, g.addendum_free_circular);
  else
    line("    remedy: no common addendum reduction down to x 0.3 removes it\n");
  if (g.w0_scale_free_hi > 0)
    line("    remedy: w0 between %.2f and %.2f times the case's value\n", g.w0_scale_free_lo, g.w0_scale_free_hi);
  else
    line("    remedy: no w0 between 0.5 and 1.5 times the case's value removes it\n");
  return out;
}

BacklashResult backlash_result(const BacklashReport& r) {
  BacklashResult o;
  o.case_path = r.case_path;
  o.provenance = r.provenance;
  o.neutral_curve = r.curve_source;
  o.module_mm = r.module_m * 1e3;
  o.phi0_rad = r.phi0_rad;
  o.phi0_source = r.phi0_source;
  o.torque_Nm = r.torque_Nm;
  o.compliance_rad_per_Nm = r.compliance_rad_per_Nm;
  o.geometry_check = geometry_figures(r.geometry);
  o.table_model = "the backlash paper's model: teeth rigid, the rim turned rigidly by phi0 (compensated); "
                  "backlash = min(j_t1, j_t2) of the pair in the mesh zone";
  for (const auto& row : r.table) o.table.push_back(table_row(row, r.module_m));
  const auto& rb = r.revolution_basic;
  const auto& rc = r.revolution_compensated;
  o.min_backlash_basic_mm = rb.min_m * 1e3;
  o.min_backlash_compensated_mm = rc.min_m * 1e3;
  o.max_backlash_basic_mm = rb.max_m * 1e3;
  o.max_backlash_compensated_mm = rc.max_m * 1e3;
  o.angular_play_arcmin = {
      rb.angular_play_min_rad * kArcmin, rb.angular_play_max_rad * kArcmin,
      {rc.angular_play_min_rad * kArcmin, rc.angular_play_max_rad * kArcmin},
      "geometric play: free rotation of the output (circular spline fixed, generator locked, teeth and rim rigid) "
      "from first contact one way to first contact the other, the sum of the two smallest closing angles over the "
      "pairs in mesh; not the catalog's lost motion, which includes the elastic twist at +-4 % of rated torque. A "
      "rigid turn phi0 does not change it."};
  o.revolution = revolution_figures(rb, rc);
  o.interference_locations = interference_locations(r.positions_basic);
  // Interference is a property of the unloaded geometry (basic model). A compensated clearance at or below zero is
  // the loaded flank in contact, not interference.
  o.interference = r.geometry.interference || !o.interference_locations.empty() || rb.min_m < 0;
  return o;
}

// ---- backlash.json's field tables: its keys, each with the member that holds it

static auto fields(std::type_identity<BacklashResult::Side>) {
  using T = BacklashResult::Side;
  return std::tuple{field("clearance_um", &T::clearance_um), field("lever_arm_mm", &T::lever_arm_mm),
                    field("nearest", &T::nearest)};
}

static auto fields(std::type_identity<BacklashResult::Pair>) {
  using T = BacklashResult::Pair;
  return std::tuple{field("phi_deg", &T::phi_deg), field("in_mesh", &T::in_mesh), field("depth_mm", &T::depth_mm),
                    field("j_t1_mm", &T::j_t1_mm),  field("j_t2_mm", &T::j_t2_mm), field("total_play_um", &T::total_play_um),
                    field("t1", &T::t1),            field("t2", &T::t2)};
}

static auto fields(std::type_identity<BacklashResult::Radii>) {
  using T = BacklashResult::Radii;
  return std::tuple{field("tip_radius_mm", &T::tip_radius_mm), field("root_radius_mm", &T::root_radius_mm),
                    field("form_radius_mm", &T::form_radius_mm)};
}

static auto fields(std::type_identity<BacklashResult::Remedy>) {
  using T = BacklashResult::Remedy;
  return std::tuple{field("addendum_scale_free_of_interference", &T::addendum_scale_free_of_interference),
                    field("addendum_coefficient_flexspline_max", &T::addendum_coefficient_flexspline_max),
                    field("addendum_coefficient_circular_max", &T::addendum_coefficient_circular_max),
                    field("w0_scale_free_of_interference", &T::w0_scale_free_of_interference),
                    field("definition", &T::definition)};
}

static auto fields(std::type_identity<BacklashResult::Geometry>) {
  using T = BacklashResult::Geometry;
  return std::tuple{field("flexspline", &T::flexspline), field("circular_spline", &T::circular_spline),
                    field("w_major_axis_mm", &T::w_major_axis_mm), field("w_minor_axis_mm", &T::w_minor_axis_mm),
                    field("working_depth_mm", &T::working_depth_mm), field("two_w0_mm", &T::two_w0_mm),
                    field("minor_axis_tip_clearance_mm", &T::minor_axis_tip_clearance_mm),
                    field("major_axis_tip_to_root_mm", &T::major_axis_tip_to_root_mm),
                    field("major_axis_root_to_tip_mm", &T::major_axis_root_to_tip_mm),
                    field("major_axis_pair", &T::major_axis_pair),
                    field("major_axis_play_arcmin", &T::major_axis_play_arcmin),
                    field("interference_at_rest", &T::interference_at_rest),
                    field("smallest_clearance_um", &T::smallest_clearance_um),
                    field("smallest_clearance_at", &T::smallest_clearance_at), field("remedy", &T::remedy)};
}

static auto fields(std::type_identity<BacklashResult::Row>) {
  using T = BacklashResult::Row;
  return std::tuple{field("position_deg", &T::position_deg), field("in_mesh", &T::in_mesh),
                    null_when_absent("basic_over_m", &T::basic_over_m),
                    null_when_absent("compensated_over_m", &T::compensated_over_m),
                    field("change_percent", &T::change_percent), field("compensated_state", &T::compensated_state),
                    field("basic", &T::basic), field("compensated", &T::compensated)};
}

static auto fields(std::type_identity<BacklashResult::AngularPlay>) {
  using T = BacklashResult::AngularPlay;
  return std::tuple{field("min", &T::min), field("max", &T::max), field("with_phi0", &T::with_phi0),
                    field("definition", &T::definition)};
}

static auto fields(std::type_identity<BacklashResult::MeshAt>) {
  using T = BacklashResult::MeshAt;
  return std::tuple{field("wg_deg", &T::wg_deg), field("pairs_in_mesh", &T::pairs_in_mesh),
                    field("min_backlash_um", &T::min_backlash_um), field("angular_play_arcmin", &T::angular_play_arcmin),
                    field("closing_t1_arcmin", &T::closing_t1_arcmin), field("closing_t2_arcmin", &T::closing_t2_arcmin),
                    field("pairs_within_1_5_10_um_t1", &T::pairs_within_1_5_10_um_t1),
                    field("pairs_within_1_5_10_um_t2", &T::pairs_within_1_5_10_um_t2)};
}

static auto fields(std::type_identity<BacklashResult::Revolution>) {
  using T = BacklashResult::Revolution;
  return std::tuple{field("steps", &T::steps), field("distinct_positions", &T::distinct_positions),
                    field("min_basic_at_wg_deg", &T::min_basic_at_wg_deg),
                    field("min_compensated_at_wg_deg", &T::min_compensated_at_wg_deg),
                    field("engaged_pairs", &T::engaged_pairs), field("definition", &T::definition),
                    field("period_basic", &T::period_basic)};
}

static auto fields(std::type_identity<BacklashResult::Location>) {
  using T = BacklashResult::Location;
  return std::tuple{field("phi_deg", &T::phi_deg), field("position_deg", &T::position_deg), field("where", &T::where),
                    field("depth_um", &T::depth_um), field("x_mm", &T::x_mm), field("y_mm", &T::y_mm)};
}

static auto fields(std::type_identity<BacklashResult>) {
  using T = BacklashResult;
  return std::tuple{field("neutral_curve", &T::neutral_curve),
                    field("module_mm", &T::module_mm), field("phi0_rad", &T::phi0_rad),
                    field("phi0_source", &T::phi0_source), field("torque_Nm", &T::torque_Nm),
                    field("compliance_rad_per_Nm", &T::compliance_rad_per_Nm),
                    field("geometry_check", &T::geometry_check), field("table_model", &T::table_model),
                    field("table", &T::table), field("min_backlash_basic_mm", &T::min_backlash_basic_mm),
                    field("min_backlash_compensated_mm", &T::min_backlash_compensated_mm),
                    field("max_backlash_basic_mm", &T::max_backlash_basic_mm),
                    field("max_backlash_compensated_mm", &T::max_backlash_compensated_mm),
                    field("angular_play_arcmin", &T::angular_play_arcmin), field("revolution", &T::revolution),
                    field("interference", &T::interference),
                    field("interference_locations", &T::interference_locations),
                    field("case_file", &T::case_path), flattened(&T::provenance)};
}

std::string backlash_json(const BacklashResult& r) { return to_json_object(r).dump(2) + "\n"; }

BacklashResult read_backlash_result(const std::filesystem::path& path) {
  return read_object<BacklashResult>(
      JsonIn::open(path, "cannot open; give the backlash.json written by `strainwave backlash CASE.toml`",
                   "the backlash.json of `strainwave backlash`"));
}

std::string backlash_csv(const BacklashReport& r) {
  std::ostringstream s;
  s.precision(10);
  s << "phi_deg,position_deg,in_mesh,depth_mm,j_t1_basic_mm,j_t2_basic_mm,j_t1_comp_mm,j_t2_comp_mm,"
       "total_play_basic_mm,backlash_basic_over_m,backlash_comp_over_m,lever_arm_t1_mm,lever_arm_t2_mm\n";
  for (size_t i = 0; i < r.positions_basic.size(); ++i) {
    const auto& b = r.positions_basic[i];
    const auto& c = r.positions_compensated[i];
    s << b.phi_rad * kDeg << "," << b.position_deg << "," << (b.engaged ? 1 : 0) << "," << b.depth_m * 1e3 << ","
      << b.ccw.clearance_m * 1e3 << "," << b.cw.clearance_m * 1e3 << "," << c.ccw.clearance_m * 1e3 << ","
      << c.cw.clearance_m * 1e3 << "," << b.total_play_m() * 1e3 << ",";
    if (b.engaged) s << b.backlash_m() / r.module_m << "," << c.backlash_m() / r.module_m;
    else s << ",";  // out of the mesh zone: no backlash
    s << "," << b.ccw.lever_arm_m * 1e3 << "," << b.cw.lever_arm_m * 1e3 << "\n";
  }
  return s.str();
}

std::string backlash_svg(const BacklashReport& r) {
  // The pairs in mesh over a half revolution, −90° to +90° from the major axis; a gap where a pair is out of mesh.
  auto curve = [&](const std::vector<PairClearance>& ps, const char* label, const char* colour, bool dashed) {
    PlotSeries s;
    s.label = label;
    s.colour = colour;
    s.dashed = dashed;
    s.line_width = 2;
    for (const auto& p : ps) {
      if (std::abs(p.phi_rad) > kPi / 2) continue;
      s.x.push_back(p.phi_rad * kDeg);
      s.y.push_back(p.engaged ? p.backlash_m() / r.module_m : NAN);
    }
    return s;
  };
  LinePlot p;
  p.title = "Backlash j/m of a tooth pair vs its position";
  p.x_label = "material angle of the tooth from the major axis (deg); 0 = major axis, ±90 = minor axis; table "
              "position = 90 − |angle|";
  p.y_label = "j / m";
  p.width = 900;
  p.height = 460;
  p.x_range = {-90.0, 90.0};
  p.series = {curve(r.positions_basic, "basic (phi0 = 0)", "#1f77b4", false),
              curve(r.positions_compensated, "compensated (phi0)", "#d62728", true)};
  // The table's positions as dots on both curves.
  for (const auto& [which, colour] : {std::pair{0, "#1f77b4"}, std::pair{1, "#d62728"}}) {
    PlotSeries dots;
    dots.colour = colour;
    dots.markers = true;
    dots.marker_radius = 4;
    for (const auto& row : r.table) {
      const PairClearance& c = which == 0 ? row.basic : row.compensated;
      if (!c.engaged) continue;
      dots.x.push_back(90.0 - row.position_deg);
      dots.y.push_back(c.backlash_m() / r.module_m);
    }
    p.series.push_back(dots);
  }
  std::ostringstream head, foot;
  head << r.curve_source << "; compensated: phi0 = " << r.phi0_rad
       << " rad; j = min(j_t1, j_t2); compensated at or below 0 = loaded flank in contact";
  foot << "min over a revolution: basic " << r.revolution_basic.min_m * 1e3 << " mm, compensated "
       << r.revolution_compensated.min_m * 1e3 << " mm; geometric angular play "
       << r.revolution_basic.angular_play_min_rad * kArcmin << "–" << r.revolution_basic.angular_play_max_rad * kArcmin
       << " arcmin; only pairs in mesh are drawn";
  Figure f;
  f.header = {"Backlash of " + r.case_path, head.str()};
  f.panels = {p};
  f.footer = {foot.str()};
  return svg_figure(f);
}

void write_profiles_vtp(const std::filesystem::path& path, const BacklashModel& m, double phi0_rad) {
  vtkNew<vtkPoints> pts;
  vtkNew<vtkCellArray> lines;
  vtkNew<vtkIntArray> part;
  part->SetName("part");
  auto add_line = [&](const std::vector<Eigen::Vector2d>& poly, int p) {
    lines->InsertNextCell(static_cast<vtkIdType>(poly.size()));
    for (const auto& q : poly) lines->InsertCellPoint(pts->InsertNextPoint(q.x() * 1e3, q.y() * 1e3, 0.0));
    part->InsertNextValue(p);
  };
  const int n = 16;
  const Involute& f = m.flank_f;
  std::vector<Eigen::Vector2d> tooth;  // cw flank up, tip, ccw flank down (tooth 0, flexspline frame)
  for (int i = 0; i <= n; ++i) {
    const Eigen::Vector2d q = involute_point(f, f.u_min + (f.u_max - f.u_min) * i / n);
    tooth.emplace_back(q.x(), -q.y());
  }
  for (int i = n; i >= 0; --i) tooth.push_back(involute_point(f, f.u_min + (f.u_max - f.u_min) * i / n));
  for (int k = 0; k < m.gear.teeth_flexspline; ++k) {
    const double phi = tooth_material_angle(m.gear, k, 0.0);
    for (int which = 0; which < 2; ++which) {
      const ToothPlacement t = place_tooth(m.curve, phi, which == 0 ? 0.0 : phi0_rad);
      const double c = std::cos(t.angle_rad), s = std::sin(t.angle_rad);
      std::vector<Eigen::Vector2d> poly;
      for (const auto& q : tooth) poly.emplace_back(c * q.x() - s * q.y() + t.offset_m.x(), s * q.x() + c * q.y() + t.offset_m.y());
      add_line(poly, which);
    }
  }
  const Involute& cs = m.flank_c;
  for (int j = 0; j < m.gear.teeth_circular; ++j) {
    const double a = 2.0 * kPi * j / m.gear.teeth_circular, c = std::cos(a), s = std::sin(a);
    std::vector<Eigen::Vector2d> poly;  // space j: cw side from tip out to the form radius, back in on the ccw side
    for (int i = 0; i <= n; ++i) {
      const Eigen::Vector2d q = involute_point(cs, cs.u_min + (cs.u_max - cs.u_min) * i / n);
      poly.emplace_back(c * q.x() + s * q.y(), s * q.x() - c * q.y());
    }
    for (int i = n; i >= 0; --i) {
      const Eigen::Vector2d q = involute_point(cs, cs.u_min + (cs.u_max - cs.u_min) * i / n);
      poly.emplace_back(c * q.x() - s * q.y(), s * q.x() + c * q.y());
    }
    add_line(poly, 2);
  }
  vtkNew<vtkPolyData> pd;
  pd->SetPoints(pts);
  pd->SetLines(lines);
  pd->GetCellData()->AddArray(part);
  write_via_temp(path, [&](const std::filesystem::path& tmp) {
    vtkNew<vtkXMLPolyDataWriter> w;
    w->SetFileName(tmp.string().c_str());
    w->SetInputData(pd);
    w->SetDataModeToAscii();
    if (w->Write() != 1) throw InputError(path.string() + ": VTK could not write the file");
  });
}

}  // namespace sw
