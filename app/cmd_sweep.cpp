// `strainwave sweep CASE.toml --set KEY=FROM:TO:N [...] [--shard K/N]`: the case over a grid of one or more keys.
// Each point is a case file of its own (the base case with the keys set) under point_NNNN/, solved by `strainwave fem`
// in a child process (points run in parallel, --jobs at a time), its result.json kept. A point whose result.json is
// there for the same case text is finished and not rerun, so an interrupted sweep resumes; --shard K/N runs the points
// i with i mod N = K − 1 only (a cluster's job array), and a call without --shard then runs what is left and merges
// everything into sweep.csv and sweep.svg.
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <thread>

#include <toml++/toml.h>

#include "app/commands.hpp"
#include "app/fem_job.hpp"
#include "common/error.hpp"
#include "common/progress.hpp"
#include "io/atomic_file.hpp"
#include "io/case.hpp"
#include "io/fem_output.hpp"
#include "common/svg_plot.hpp"

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

/// The base case's TOML with the point's values set; whole values stay integers where the base had an integer.
std::string point_case_text(const toml::table& base, const std::vector<SweepAxis>& axes, const std::vector<double>& v) {
  toml::table t = base;
  for (std::size_t k = 0; k < axes.size(); ++k) {
    toml::node* table = t.get(axes[k].table);
    if (!table) {
      t.insert(axes[k].table, toml::table{});
      table = t.get(axes[k].table);
    }
    if (!table->is_table())
      throw InputError("--set " + axes[k].name() + ": " + axes[k].table + " is not a table of the case");
    auto& tt = *table->as_table();
    const toml::node* old = tt.get(axes[k].key);
    if (old && old->is_integer() && v[k] == std::round(v[k])) {
      tt.insert_or_assign(axes[k].key, static_cast<int64_t>(std::llround(v[k])));
    } else {  // a key that takes integers only rejects a fraction with the case parser's message
      tt.insert_or_assign(axes[k].key, v[k]);
    }
  }
  std::ostringstream s;
  s << "# a point of a strainwave sweep (written by `strainwave sweep`)\n" << t << "\n";
  return s.str();
}

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  if (!in) return {};
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// A finished point: its result.json reads and was made from this case text.
bool finished(const fs::path& dir, const std::string& case_text) {
  if (read_text(dir / "case.toml") != case_text || !fs::exists(dir / "result.json")) return false;
  try {
    (void)read_fem_result(dir / "result.json");
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

/// Runs `strainwave fem` on every point in `todo`, `jobs` at a time; returns the points that failed.
std::vector<const Point*> run_points(const std::vector<const Point*>& todo, int jobs, const std::string& solver) {
  std::vector<const Point*> failed;
  std::map<pid_t, const Point*> running;
  const std::string self = fs::read_symlink("/proc/self/exe").string();
  // Threads per child: the cores shared out.
  const int cores = std::max(1u, std::thread::hardware_concurrency());
  const std::string threads = std::to_string(std::max(1, cores / std::max(1, jobs)));
  std::vector<std::string> env_s;
  for (char** e = environ; *e; ++e)
    if (std::string(*e).rfind("OPENBLAS_NUM_THREADS=", 0) != 0) env_s.emplace_back(*e);
  env_s.push_back("OPENBLAS_NUM_THREADS=" + threads);
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
      std::vector<std::string> args = {self, "fem", (p->dir / "case.toml").string(), "--out", p->dir.string(),
                                       "--no-vtk", "--quiet"};
      if (!solver.empty()) args.insert(args.end(), {"--solver", solver});
      std::vector<char*> argv;
      for (auto& a : args) argv.push_back(a.data());
      argv.push_back(nullptr);
      posix_spawn_file_actions_t fa;
      posix_spawn_file_actions_init(&fa);
      const std::string log = (p->dir / "fem.log").string();
      posix_spawn_file_actions_addopen(&fa, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      posix_spawn_file_actions_adddup2(&fa, 1, 2);
      pid_t pid = 0;
      const int rc = posix_spawn(&pid, self.c_str(), &fa, nullptr, argv.data(), env.data());
      posix_spawn_file_actions_destroy(&fa);
      if (rc != 0) throw std::runtime_error("cannot start " + self + " for " + p->dir.string());
      running[pid] = p;
    }
    if (!running.empty()) wait_one();
  }
  return failed;
}

/// A figure of a point's result; NaN where the point has none (no generator).
using ResultFigure = double (*)(const FemResult&);

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
  ResultFigure value;
};
const std::vector<Column> kColumns = {
    {"phi0_rad", phi0},
    {"compliance_rad_per_Nm", compliance},
    {"max_hoop_stress_Pa", max_hoop_stress},
    {"min_hoop_stress_Pa", min_hoop_stress},
    {"generator_total_radial_force_N", generator_force},
    {"generator_w0_mm", generator_w0},
    {"total_s", total_time},
};

std::string sweep_csv(const std::vector<SweepAxis>& axes, const std::vector<Point>& points,
                      const std::vector<FemResult>& results) {
  std::ostringstream s;
  s << "point";
  for (const auto& a : axes) s << "," << a.name();
  for (const auto& c : kColumns) s << "," << c.name;
  s << "\n";
  char buf[64];
  for (std::size_t i = 0; i < points.size(); ++i) {
    s << i;
    for (double v : points[i].values) {
      std::snprintf(buf, sizeof buf, ",%.10g", v);
      s << buf;
    }
    for (const auto& c : kColumns) {
      std::snprintf(buf, sizeof buf, ",%.9e", c.value(results[i]));
      s << buf;
    }
    s << "\n";
  }
  return s.str();
}

/// Four panels (φ₀, C_τ, max hoop stress, generator force) against the first key; one line per combination of the
/// other keys.
std::string sweep_svg(const std::vector<SweepAxis>& axes, const std::vector<Point>& points,
                      const std::vector<FemResult>& results) {
  struct Panel {
    std::string title;
    ResultFigure value;
    double scale;  ///< to the unit in the title
  };
  const std::vector<Panel> panels = {{"φ₀ (rad)", phi0, 1.0},
                                     {"C_τ (rad/(N·m))", compliance, 1.0},
                                     {"max hoop stress (MPa)", max_hoop_stress, 1e-6},
                                     {"generator radial force (N)", generator_force, 1.0}};
  static const char* kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2"};
  const std::size_t per_line = axes[0].values.size(), lines = points.size() / per_line;
  Figure f;
  std::string head = "sweep over " + axes[0].name();
  for (std::size_t k = 1; k < axes.size(); ++k) head += (k == 1 ? " (lines: " : ", ") + axes[k].name();
  f.header = {head + (axes.size() > 1 ? ")" : "")};
  f.columns = 2;
  for (const auto& panel : panels) {
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

/// The grid's points, first key slowest; each point's case is validated before anything runs.
std::vector<Point> grid_points(const toml::table& base, const std::vector<SweepAxis>& axes, const fs::path& dir,
                               const std::string& case_path, const std::string& solver) {
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
    p.case_text = point_case_text(base, axes, p.values);
    Case pc = parse_case(p.case_text, "--set (point " + std::to_string(i) + " of " + case_path + ")");
    apply_solver_option(pc, solver);
    points.push_back(std::move(p));
  }
  return points;
}

/// The points of this shard not finished before, each with its case.toml written and an old result.json removed.
std::vector<const Point*> points_to_run(const std::vector<Point>& points, std::pair<int, int> shard,
                                       std::size_t& skipped) {
  std::vector<const Point*> todo;
  for (const auto& p : points) {
    if (static_cast<int>(p.index % static_cast<std::size_t>(shard.second)) != shard.first - 1) continue;
    if (finished(p.dir, p.case_text)) {
      ++skipped;
      continue;
    }
    fs::create_directories(p.dir);
    fs::remove(p.dir / "result.json");
    write_file_atomic(p.dir / "case.toml", p.case_text);
    todo.push_back(&p);
  }
  return todo;
}

/// One line naming how many points failed and the last line of the first one's log.
InputError failed_points(const std::vector<const Point*>& failed) {
  std::string lines = read_text(failed.front()->dir / "fem.log");
  while (!lines.empty() && lines.back() == '\n') lines.pop_back();
  const auto last = lines.rfind('\n');
  return InputError("sweep: " + std::to_string(failed.size()) + " point(s) failed, e.g. " +
                    failed.front()->dir.string() + ": " + (last == std::string::npos ? lines : lines.substr(last + 1)));
}

/// Every point's result.json merged into sweep.csv and sweep.svg.
void merge_points(const fs::path& dir, const std::vector<SweepAxis>& axes, const std::vector<Point>& points) {
  std::vector<FemResult> results;
  for (const auto& p : points) results.push_back(read_fem_result(p.dir / "result.json"));
  OutputSet outputs(dir, {"sweep.csv", "sweep.svg"});  // each point's folder is a set of its own (`strainwave fem`)
  write_file_atomic(outputs.staging() / "sweep.csv", sweep_csv(axes, points, results));
  write_file_atomic(outputs.staging() / "sweep.svg", sweep_svg(axes, points, results));
  outputs.commit();
  std::printf("  wrote %s (sweep.csv, sweep.svg, %zu points' result.json)\n", dir.string().c_str(), points.size());
}

struct SweepOptions {
  std::string case_path, out, shard, solver;
  std::vector<std::string> sets;
  int jobs = 0;
};

void run_sweep(const SweepOptions& o) {
  Case base_case = load_case(o.case_path);  // the base case must be valid itself
  toml::table base;
  try {
    base = toml::parse(case_file_toml(o.case_path), o.case_path);
  } catch (const toml::parse_error& e) {
    throw InputError(o.case_path + ": malformed TOML: " + std::string(e.description()));
  }
  std::vector<SweepAxis> axes;
  for (const auto& s : o.sets) axes.push_back(parse_set(s));
  const std::pair<int, int> shard = parse_shard(o.shard);
  const int jobs = o.jobs > 0 ? o.jobs : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const fs::path dir = o.out.empty() ? fs::path(default_out_dir(base_case).string() + "_sweep") : fs::path(o.out);

  const std::vector<Point> points = grid_points(base, axes, dir, o.case_path, o.solver);
  fs::create_directories(dir);
  std::size_t skipped = 0;
  const std::vector<const Point*> todo = points_to_run(points, shard, skipped);
  progress("sweep: " + std::to_string(points.size()) + " points, " + std::to_string(skipped) +
           " finished before, " + std::to_string(todo.size()) + " to run, " + std::to_string(jobs) + " at a time");
  const double t0 = elapsed_s();
  const auto failed = run_points(todo, jobs, o.solver);
  const double wall = elapsed_s() - t0;
  if (!failed.empty()) throw failed_points(failed);
  std::printf("sweep %s: %zu points run in %.2f s (%zu finished before)\n", o.case_path.c_str(), todo.size(), wall,
              skipped);
  if (shard.second > 1) {
    std::printf("  shard %d/%d done; run again without --shard to merge into sweep.csv\n", shard.first, shard.second);
    return;
  }
  merge_points(dir, axes, points);
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
  cmd->add_option("--out", o.out, "output directory (default out/<case stem>_sweep/)");
  cmd->callback([] { run_sweep(o); });
}

}  // namespace sw::app
