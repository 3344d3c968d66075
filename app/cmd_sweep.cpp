// `strainwave sweep CASE.toml --set KEY=FROM:TO:N [...] [--shard K/N] [--contact]`: the case over a grid of one or
// more keys. Each point is a case file of its own (the base case with the keys set) under point_NNNN/, solved by
// `strainwave fem` in a child process (points run in parallel, --jobs at a time), its result.json kept; with --contact
// by `strainwave contact` (which solves the FEM itself), its contact.json kept beside result.json. A point whose files
// are there for the same case text is finished and not rerun, so an interrupted sweep resumes; --shard K/N runs the
// points i with i mod N = K − 1 only (a cluster's job array), and a call without --shard then runs what is left and
// merges everything into sweep.csv and sweep.svg.
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <numbers>
#include <optional>
#include <sstream>
#include <thread>

#include <CLI/CLI.hpp>

#include "app/commands.hpp"
#include "app/fem_job.hpp"
#include "common/constants.hpp"
#include "common/error.hpp"
#include "common/progress.hpp"
#include "common/svg_plot.hpp"
#include "contact/loaded_contact.hpp"
#include "io/atomic_file.hpp"
#include "io/case.hpp"
#include "io/case_edit.hpp"
#include "io/contact_output.hpp"
#include "io/datasheet_output.hpp"
#include "io/fem_output.hpp"

extern char** environ;

namespace sw::app {

namespace fs = std::filesystem;

namespace {

struct SweepAxis {
  std::string table, key;  ///< "flexspline", "wall_thickness_mm"
  std::vector<double> values;
  std::string name() const { return table + "." + key; }
};

SweepAxis parse_set(const std::string& spec) {
  const std::string expect = "expected TABLE.KEY=FROM:TO:N (e.g. flexspline.wall_thickness_mm=0.4:0.8:9)";
  const auto eq = spec.find('='), dot = spec.find('.');
  if (eq == std::string::npos || dot == std::string::npos || dot > eq) throw InputError("--set " + spec + "; " + expect);
  SweepAxis a;
  a.table = spec.substr(0, dot);
  a.key = spec.substr(dot + 1, eq - dot - 1);
  std::stringstream range(spec.substr(eq + 1));
  std::string from_s, to_s, n_s;
  if (!std::getline(range, from_s, ':') || !std::getline(range, to_s, ':') || !std::getline(range, n_s) ||
      a.key.empty() || a.key.find('.') != std::string::npos)
    throw InputError("--set " + spec + "; " + expect);
  double from = 0, to = 0;
  long n = 0;
  try {
    std::size_t used = 0;
    from = std::stod(from_s, &used);
    if (used != from_s.size()) throw std::invalid_argument("from");
    to = std::stod(to_s, &used);
    if (used != to_s.size()) throw std::invalid_argument("to");
    n = std::stol(n_s, &used);
    if (used != n_s.size()) throw std::invalid_argument("n");
  } catch (const std::exception&) {
    throw InputError("--set " + spec + "; " + expect);
  }
  if (n < 1 || (n == 1 && from != to))
    throw InputError("--set " + spec + "; N = " + n_s + " must be >= 1 (N = 1 needs FROM = TO)");
  for (long i = 0; i < n; ++i) a.values.push_back(n == 1 ? from : from + (to - from) * static_cast<double>(i) / (n - 1));
  return a;
}

/// The base case's TOML (`base` of the file `path`) with the point's values set (io/case_edit.hpp case_text_with).
std::string point_case_text(const std::string& base, const std::string& path, const std::vector<SweepAxis>& axes,
                            const std::vector<double>& v) {
  CaseKeyValues values;
  for (std::size_t k = 0; k < axes.size(); ++k) values.emplace_back(axes[k].name(), v[k]);
  return "# a point of a strainwave sweep (written by `strainwave sweep`)\n" +
         case_text_with(base, path, values, "--set");
}

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  if (!in) return {};
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

struct SweepOptions {
  std::string case_path, out, shard, solver;
  std::vector<std::string> sets;
  int jobs = 0;
  bool contact = false;  ///< each point runs `strainwave contact` (the FEM and the drive's loaded contact)
  bool datasheet = false;  ///< each point runs `strainwave datasheet` (the drive's catalog sheet)
};

/// The command each point runs.
std::string point_command(const SweepOptions& o) { return o.datasheet ? "datasheet" : o.contact ? "contact" : "fem"; }

/// A point's files: result.json (with --contact also contact.json), or with --datasheet datasheet.json alone.
std::vector<std::string> point_files(const SweepOptions& o) {
  if (o.datasheet) return {"datasheet.json"};
  if (o.contact) return {"result.json", "contact.json"};
  return {"result.json"};
}

/// A finished point: its files read and were made from this case text.
bool finished(const fs::path& dir, const std::string& case_text, const SweepOptions& o) {
  if (read_text(dir / "case.toml") != case_text) return false;
  try {
    if (o.datasheet) {
      (void)read_datasheet(dir / "datasheet.json");
      return true;
    }
    (void)read_fem_result(dir / "result.json");
    if (o.contact) (void)read_contact_result(dir / "contact.json");
    return true;
  } catch (const InputError&) {
    return false;
  }
}

struct Point {
  std::size_t index = 0;
  std::vector<double> values;
  fs::path dir;
  std::string case_text;
};

std::string point_name(std::size_t i) {
  char b[32];
  std::snprintf(b, sizeof b, "point_%04zu", i);
  return b;
}

/// The point's log: what its child process printed (COMMAND.log in its folder).
fs::path point_log(const Point& p, const SweepOptions& o) { return p.dir / (point_command(o) + ".log"); }

/// This process's environment for the children, OPENBLAS_NUM_THREADS set to the cores shared out over `jobs`.
std::vector<std::string> child_environment(int jobs) {
  const int cores = std::max(1u, std::thread::hardware_concurrency());
  const std::string threads = std::to_string(std::max(1, cores / std::max(1, jobs)));
  std::vector<std::string> env;
  for (char** e = environ; *e; ++e)
    if (std::string(*e).rfind("OPENBLAS_NUM_THREADS=", 0) != 0) env.emplace_back(*e);
  env.push_back("OPENBLAS_NUM_THREADS=" + threads);
  return env;
}

/// Starts `strainwave fem` (with --contact `strainwave contact`) on the point in a child process writing its output
/// to the point's log; returns its process id.
pid_t start_point(const Point& p, const SweepOptions& o, const std::string& self, char* const* env) {
  std::vector<std::string> args = {self, point_command(o), (p.dir / "case.toml").string(), "--out", p.dir.string(),
                                   "--quiet"};
  if (!o.datasheet) args.push_back("--no-vtk");  // the sheet writes its one mode shape
  if (!o.solver.empty()) args.insert(args.end(), {"--solver", o.solver});
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  const std::string log = point_log(p, o).string();
  posix_spawn_file_actions_addopen(&fa, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&fa, 1, 2);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, self.c_str(), &fa, nullptr, argv.data(), env);
  posix_spawn_file_actions_destroy(&fa);
  if (rc != 0) throw std::runtime_error("cannot start " + self + " for " + p.dir.string());
  return pid;
}

/// Runs every point in `todo`, `jobs` at a time; returns the points that failed.
std::vector<const Point*> run_points(const std::vector<const Point*>& todo, int jobs, const SweepOptions& o) {
  std::vector<const Point*> failed;
  std::map<pid_t, const Point*> running;
  const std::string self = fs::read_symlink("/proc/self/exe").string();
  std::vector<std::string> env_s = child_environment(jobs);
  std::vector<char*> env;
  for (auto& s : env_s) env.push_back(s.data());
  env.push_back(nullptr);
  std::size_t next = 0, done = 0;
  const double t0 = elapsed_s();
  auto wait_one = [&] {
    int status = 0;
    const pid_t pid = waitpid(-1, &status, 0);
    if (pid <= 0) return;
    const Point* p = running.at(pid);
    running.erase(pid);
    ++done;
    if (!(WIFEXITED(status) && WEXITSTATUS(status) == 0)) failed.push_back(p);
    progress("sweep: " + std::to_string(done) + "/" + std::to_string(todo.size()) + " points, " +
             std::to_string(elapsed_s() - t0) + " s");
  };
  while (next < todo.size() || !running.empty()) {
    while (next < todo.size() && static_cast<int>(running.size()) < jobs) {
      const Point* p = todo[next++];
      running[start_point(*p, o, self, env.data())] = p;
    }
    if (!running.empty()) wait_one();
  }
  return failed;
}


/// A point's drive figures, from its contact.json (`strainwave contact`), in the file's units.
struct DriveFigures {
  double t1_Nm = 0, t2_Nm = 0;  ///< the three segments' breakpoints (contact.json `catalog`)
  double twist_at_t1_arcmin = 0, twist_at_t2_arcmin = 0, twist_at_rated_arcmin = 0;
  double k1_Nm_per_rad = 0, k2_Nm_per_rad = 0, k3_Nm_per_rad = 0;
  double lost_motion_arcmin = 0, play_arcmin = 0;
  double max_flank_force_at_rated_N = 0;  ///< the largest force on one flank at +rated torque
  double split_body = 0, split_teeth = 0, split_generator = 0, split_circular_spline = 0;
};

/// The drive figures of a contact.json: the twist at T1 and T2 read on the middle line of its torque–twist loop, the
/// rest as the file gives them. Throws InputError naming the file as its readers do.
DriveFigures drive_figures(const fs::path& contact_json) {
  const ContactResult r = read_contact_result(contact_json);
  const TorqueTwist curve = read_contact_curve(contact_json).middle_line;
  DriveFigures d;
  d.t1_Nm = r.catalog.T1_Nm;
  d.t2_Nm = r.catalog.T2_Nm;
  d.twist_at_t1_arcmin = naming_file(contact_json.string(), [&] { return twist_at(curve, d.t1_Nm); }) * kArcmin;
  d.twist_at_t2_arcmin = naming_file(contact_json.string(), [&] { return twist_at(curve, d.t2_Nm); }) * kArcmin;
  d.twist_at_rated_arcmin = r.twist_at_rated_arcmin;
  d.k1_Nm_per_rad = r.catalog.K1_Nm_per_rad;
  d.k2_Nm_per_rad = r.catalog.K2_Nm_per_rad;
  d.k3_Nm_per_rad = r.catalog.K3_Nm_per_rad;
  d.lost_motion_arcmin = r.lost_motion_arcmin;
  d.play_arcmin = r.play_arcmin;
  for (const auto& f : r.flanks)
    d.max_flank_force_at_rated_N = std::max(d.max_flank_force_at_rated_N, f.force_at_plus_rated_N);
  d.split_body = r.compliance_split.body;
  d.split_teeth = r.compliance_split.teeth;
  d.split_generator = r.compliance_split.generator;
  d.split_circular_spline = r.compliance_split.circular_spline;
  return d;
}

/// What a point gave: the FEM's result.json, and with --contact the drive's figures; with --datasheet its sheet alone.
struct PointResult {
  std::optional<FemResult> fem;
  std::optional<DriveFigures> drive;
  std::optional<Datasheet> sheet;
};

/// A figure of a point's result; NaN where the point has none (no generator).
using PointFigure = std::function<double(const PointResult&)>;

PointFigure of_fem(double (*figure)(const FemResult&)) {
  return [figure](const PointResult& r) { return r.fem ? figure(*r.fem) : std::nan(""); };
}
/// A figure of the sheet by its key: NaN when not computed, infinity beyond its search (the ratcheting torque).
PointFigure of_sheet(const std::string& name) {
  return [name](const PointResult& r) {
    const DatasheetFigure* f = r.sheet ? r.sheet->find(name) : nullptr;
    return f && f->value ? *f->value : std::nan("");
  };
}
PointFigure of_drive(double DriveFigures::*figure) {
  return [figure](const PointResult& r) { return r.drive ? (*r.drive).*figure : std::nan(""); };
}

double phi0(const FemResult& r) { return r.phi0_rad; }
double compliance(const FemResult& r) { return r.compliance_rad_per_Nm; }
double max_hoop_stress(const FemResult& r) { return r.max_hoop_stress_Pa; }
double min_hoop_stress(const FemResult& r) { return r.min_hoop_stress_Pa; }
double generator_force(const FemResult& r) {  // any model (a cam has no points)
  return r.generator ? r.generator->total_radial_force_N : std::nan("");
}
double generator_w0(const FemResult& r) { return r.wave_generator ? r.wave_generator->w0_reached_mm : std::nan(""); }
double total_time(const FemResult& r) { return r.timings_s.total; }

struct Column {
  std::string name;
  PointFigure value;
};

/// sweep.csv's figures: the FEM's, then with --contact the drive's (named as their keys in contact.json where the
/// file has them); with --datasheet every figure of the sheet, named as its key in datasheet.json.
std::vector<Column> csv_columns(const PointResult& first) {
  if (first.sheet) {
    std::vector<Column> c;
    for (const DatasheetFigure& f : first.sheet->figures) c.push_back({f.name, of_sheet(f.name)});
    return c;
  }
  const bool drive = first.drive.has_value();
  std::vector<Column> c = {{"phi0_rad", of_fem(phi0)},
                           {"compliance_rad_per_Nm", of_fem(compliance)},
                           {"max_hoop_stress_Pa", of_fem(max_hoop_stress)},
                           {"min_hoop_stress_Pa", of_fem(min_hoop_stress)},
                           {"generator_total_radial_force_N", of_fem(generator_force)},
                           {"generator_w0_mm", of_fem(generator_w0)},
                           {"total_s", of_fem(total_time)}};
  if (!drive) return c;
  using D = DriveFigures;
  for (const auto& [name, figure] : std::vector<std::pair<std::string, double D::*>>{
           {"catalog.T1_Nm", &D::t1_Nm},
           {"catalog.T2_Nm", &D::t2_Nm},
           {"twist_at_T1_arcmin", &D::twist_at_t1_arcmin},
           {"twist_at_T2_arcmin", &D::twist_at_t2_arcmin},
           {"twist_at_rated_arcmin", &D::twist_at_rated_arcmin},
           {"catalog.K1_Nm_per_rad", &D::k1_Nm_per_rad},
           {"catalog.K2_Nm_per_rad", &D::k2_Nm_per_rad},
           {"catalog.K3_Nm_per_rad", &D::k3_Nm_per_rad},
           {"lost_motion_arcmin", &D::lost_motion_arcmin},
           {"play_arcmin", &D::play_arcmin},
           {"max_flank_force_at_rated_N", &D::max_flank_force_at_rated_N},
           {"compliance_split.body", &D::split_body},
           {"compliance_split.teeth", &D::split_teeth},
           {"compliance_split.generator", &D::split_generator},
           {"compliance_split.circular_spline", &D::split_circular_spline}})
    c.push_back({name, of_drive(figure)});
  return c;
}

std::string sweep_csv(const std::vector<SweepAxis>& axes, const std::vector<Point>& points,
                      const std::vector<PointResult>& results) {
  const std::vector<Column> columns = csv_columns(results.front());
  std::ostringstream s;
  s << "point";
  for (const auto& a : axes) s << "," << a.name();
  for (const auto& c : columns) s << "," << c.name;
  s << "\n";
  char buf[64];
  for (std::size_t i = 0; i < points.size(); ++i) {
    s << i;
    for (double v : points[i].values) {
      std::snprintf(buf, sizeof buf, ",%.10g", v);
      s << buf;
    }
    for (const auto& c : columns) {
      std::snprintf(buf, sizeof buf, ",%.9e", c.value(results[i]));
      s << buf;
    }
    s << "\n";
  }
  return s.str();
}

struct Panel {
  std::string title;
  PointFigure value;
  double scale;  ///< to the unit in the title
};

/// sweep.svg's panels: φ₀, C_τ, max hoop stress, generator force; with --contact the twist at rated torque and K3;
/// with --datasheet the limits, K3, the bearing's life and the efficiency.
std::vector<Panel> svg_panels(const PointResult& first) {
  if (first.sheet)
    return {{"buckling torque (N·m)", of_sheet("buckling_torque_Nm"), 1.0},
            {"ratcheting torque (N·m)", of_sheet("ratcheting_torque_Nm"), 1.0},
            {"torque for infinite life (N·m)", of_sheet("infinite_life_torque_Nm"), 1.0},
            {"K3 (N·m/rad)", of_sheet("K3_Nm_per_rad"), 1.0},
            {"generator bearing L10 (h)", of_sheet("bearing_life_L10_h"), 1.0},
            {"efficiency, rated torque and 2,000 rpm (%)", of_sheet("efficiency"), 100.0}};
  const bool drive = first.drive.has_value();
  std::vector<Panel> panels = {{"φ₀ (rad)", of_fem(phi0), 1.0},
                               {"C_τ (rad/(N·m))", of_fem(compliance), 1.0},
                               {"max hoop stress (MPa)", of_fem(max_hoop_stress), 1e-6},
                               {"generator radial force (N)", of_fem(generator_force), 1.0}};
  if (drive) {
    panels.push_back({"twist at rated torque (arcmin)", of_drive(&DriveFigures::twist_at_rated_arcmin), 1.0});
    panels.push_back({"K3 (N·m/rad)", of_drive(&DriveFigures::k3_Nm_per_rad), 1.0});
  }
  return panels;
}

/// The panels against the first key; one line per combination of the other keys.
std::string sweep_svg(const std::vector<SweepAxis>& axes, const std::vector<Point>& points,
                      const std::vector<PointResult>& results) {
  static const char* kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2"};
  const std::size_t per_line = axes[0].values.size(), lines = points.size() / per_line;
  Figure f;
  std::string head = "sweep over " + axes[0].name();
  for (std::size_t k = 1; k < axes.size(); ++k) head += (k == 1 ? " (lines: " : ", ") + axes[k].name();
  f.header = {head + (axes.size() > 1 ? ")" : "")};
  f.columns = 2;
  for (const auto& panel : svg_panels(results.front())) {
    LinePlot p;
    p.title = panel.title;
    p.x_label = axes[0].name();
    p.y_label = panel.title;
    p.width = 440;
    p.height = 300;
    p.zero_line = false;
    for (std::size_t l = 0; l < lines; ++l) {
      PlotSeries s;
      s.colour = kColours[l % 7];
      s.line_width = 1.5;
      for (std::size_t k = 1; k < axes.size(); ++k) {  // the other keys' values on this line (point l: i = 0)
        char v[64];
        std::snprintf(v, sizeof v, "%s = %.4g", axes[k].name().c_str(), points[l].values[k]);
        s.label += (k == 1 ? "" : ", ") + std::string(v);
      }
      for (std::size_t i = 0; i < per_line; ++i) {
        // Points are numbered with the first key slowest: point = i·lines + l.
        const std::size_t idx = i * lines + l;
        s.x.push_back(points[idx].values[0]);
        s.y.push_back(panel.value(results[idx]) * panel.scale);
      }
      p.series.push_back(s);
    }
    f.panels.push_back(p);
  }
  return svg_figure(f);
}

/// --shard K/N as (K, N); (1, 1) when not given.
std::pair<int, int> parse_shard(const std::string& shard) {
  int shard_k = 1, shard_n = 1;
  if (shard.empty()) return {shard_k, shard_n};
  char slash = 0;
  std::stringstream ss(shard);
  if (!(ss >> shard_k >> slash >> shard_n) || slash != '/' || !ss.eof() || shard_n < 1 || shard_k < 1 ||
      shard_k > shard_n)
    throw InputError("--shard " + shard + "; expected K/N with 1 <= K <= N (e.g. 2/8)");
  return {shard_k, shard_n};
}

/// Refuses, in one line naming the case, a case `strainwave contact` cannot take (no [gear], no generator, no toothed
/// face, explicit teeth), as that command does before any work.
void check_contact_case(const Case& c) {
  naming_file(c.path, [&] { check_contact_model(flexspline_model(c)); });
}

/// The grid's points, first key slowest; each point's case is validated before anything runs (with --contact also
/// as `strainwave contact` takes it).
std::vector<Point> grid_points(const std::string& base, const std::vector<SweepAxis>& axes, const fs::path& dir,
                               const SweepOptions& o) {
  std::vector<Point> points;
  std::size_t total = 1;
  for (const auto& a : axes) total *= a.values.size();
  for (std::size_t i = 0; i < total; ++i) {
    Point p;
    p.index = i;
    std::size_t rest = i;
    p.values.resize(axes.size());
    for (std::size_t k = axes.size(); k-- > 0;) {
      p.values[k] = axes[k].values[rest % axes[k].values.size()];
      rest /= axes[k].values.size();
    }
    p.dir = dir / point_name(i);
    p.case_text = point_case_text(base, o.case_path, axes, p.values);
    Case pc = parse_case(p.case_text, "--set (point " + std::to_string(i) + " of " + o.case_path + ")");
    apply_solver_option(pc, o.solver);
    if (o.contact || o.datasheet) check_contact_case(pc);
    points.push_back(std::move(p));
  }
  return points;
}

/// The points of this shard not finished before, each with its case.toml written and its old outputs removed.
std::vector<const Point*> points_to_run(const std::vector<Point>& points, std::pair<int, int> shard,
                                       const SweepOptions& o, std::size_t& skipped) {
  std::vector<const Point*> todo;
  for (const auto& p : points) {
    if (static_cast<int>(p.index % static_cast<std::size_t>(shard.second)) != shard.first - 1) continue;
    if (finished(p.dir, p.case_text, o)) {
      ++skipped;
      continue;
    }
    fs::create_directories(p.dir);
    for (const char* f : {"result.json", "contact.json", "datasheet.json"}) fs::remove(p.dir / f);
    write_file_atomic(p.dir / "case.toml", p.case_text);
    todo.push_back(&p);
  }
  return todo;
}

/// One line naming how many points failed and the last line of the first one's log.
InputError failed_points(const std::vector<const Point*>& failed, const SweepOptions& o) {
  std::string lines = read_text(point_log(*failed.front(), o));
  while (!lines.empty() && lines.back() == '\n') lines.pop_back();
  const auto last = lines.rfind('\n');
  return InputError("sweep: " + std::to_string(failed.size()) + " point(s) failed, e.g. " +
                    failed.front()->dir.string() + ": " + (last == std::string::npos ? lines : lines.substr(last + 1)));
}

/// Every point's result.json (and contact.json) merged into sweep.csv and sweep.svg.
void merge_points(const fs::path& dir, const std::vector<SweepAxis>& axes, const std::vector<Point>& points,
                  const SweepOptions& o) {
  std::vector<PointResult> results;
  for (const auto& p : points) {
    PointResult r;
    if (o.datasheet) r.sheet = read_datasheet(p.dir / "datasheet.json");
    else r.fem = read_fem_result(p.dir / "result.json");
    if (o.contact) r.drive = drive_figures(p.dir / "contact.json");
    results.push_back(std::move(r));
  }
  // Each point's folder is a set of its own (`strainwave fem`, `contact` or `datasheet`).
  OutputSet outputs(dir, {"sweep.csv", "sweep.svg"});
  write_file_atomic(outputs.staging() / "sweep.csv", sweep_csv(axes, points, results));
  write_file_atomic(outputs.staging() / "sweep.svg", sweep_svg(axes, points, results));
  outputs.commit();
  std::string files;
  for (const std::string& f : point_files(o)) files += (files.empty() ? "" : " and ") + f;
  std::printf("  wrote %s (sweep.csv, sweep.svg, %zu points' %s)\n", dir.string().c_str(), points.size(),
              files.c_str());
}

void run_sweep(const SweepOptions& o) {
  if (o.datasheet && !o.solver.empty())
    throw InputError("--solver " + o.solver + " with --datasheet; the sheet reads the harmonic solver (drop --solver)");
  Case base_case = load_case(o.case_path);  // the base case must be valid itself
  if (o.contact || o.datasheet) check_contact_case(base_case);
  const std::string base = case_file_toml(o.case_path);
  std::vector<SweepAxis> axes;
  for (const auto& s : o.sets) axes.push_back(parse_set(s));
  const std::pair<int, int> shard = parse_shard(o.shard);
  const int jobs = o.jobs > 0 ? o.jobs : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const fs::path dir = o.out.empty() ? fs::path(default_out_dir(base_case).string() + "_sweep") : fs::path(o.out);

  const std::vector<Point> points = grid_points(base, axes, dir, o);
  fs::create_directories(dir);
  std::size_t skipped = 0;
  const std::vector<const Point*> todo = points_to_run(points, shard, o, skipped);
  progress("sweep: " + std::to_string(points.size()) + " points, " + std::to_string(skipped) +
           " finished before, " + std::to_string(todo.size()) + " to run, " + std::to_string(jobs) + " at a time");
  const double t0 = elapsed_s();
  const auto failed = run_points(todo, jobs, o);
  const double wall = elapsed_s() - t0;
  if (!failed.empty()) throw failed_points(failed, o);
  std::printf("sweep %s: %zu points run in %.2f s (%zu finished before)\n", o.case_path.c_str(), todo.size(), wall,
              skipped);
  if (shard.second > 1) {
    std::printf("  shard %d/%d done; run again without --shard to merge into sweep.csv\n", shard.first, shard.second);
    return;
  }
  merge_points(dir, axes, points, o);
}

}  // namespace

void add_sweep_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("sweep", "run a case over a grid of one or more keys (sweep.csv, sweep.svg)");
  static SweepOptions o;
  cmd->add_option("case", o.case_path, "case file (TOML)")->required();
  cmd->add_option("--set", o.sets, "TABLE.KEY=FROM:TO:N, N values from FROM to TO (repeat for a grid)")->required();
  cmd->add_option("--shard", o.shard, "K/N: run only the points i with i mod N = K - 1 (no sweep.csv)");
  cmd->add_option("--jobs", o.jobs, "points at a time (default: the machine's cores)");
  cmd->add_option("--solver", o.solver, "tet10 | fourier (overrides [solver] method)")
      ->check(CLI::IsMember({"tet10", "fourier"}));
  cmd->add_flag("--contact", o.contact,
                "run `strainwave contact` on each point (the FEM and the drive's loaded contact; the case needs [gear] "
                "and a generator): sweep.csv adds the twist at T1, T2 and rated torque, K1..K3, lost motion, play, "
                "the largest flank force and the compliance split, sweep.svg the twist at rated torque and K3");
  cmd->add_flag("--datasheet", o.datasheet,
                "run `strainwave datasheet` on each point (the drive's catalog sheet on the harmonic solver): "
                "sweep.csv has every figure of the sheet, sweep.svg the limits, K3, the bearing's life and the "
                "efficiency")
      ->excludes("--contact");
  cmd->add_option("--out", o.out, "output directory (default out/<case stem>_sweep/)");
  cmd->callback([] { run_sweep(o); });
}

}  // namespace sw::app
