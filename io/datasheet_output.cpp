#include "io/datasheet_output.hpp"

#include <cmath>
#include <cstdio>
#include <limits>

#include <nlohmann/json.hpp>

#include "common/svg_plot.hpp"
#include "io/json_file.hpp"
#include "io/provenance.hpp"

namespace sw {
namespace {

constexpr const char* kDatasheetCannotOpen = "cannot be read; give the datasheet.json written by `strainwave datasheet CASE.toml`";
constexpr const char* kDatasheetExpected = "the datasheet.json of `strainwave datasheet`";

nlohmann::json number_or_null(const std::optional<double>& v) {
  return v && std::isfinite(*v) ? nlohmann::json(*v) : nlohmann::json(nullptr);
}

std::string value_text(const std::optional<double>& v) {
  if (!v) return "not computed";
  if (std::isinf(*v)) return "beyond the search";
  char buf[32];
  const double a = std::abs(*v);
  std::snprintf(buf, sizeof buf, a != 0 && (a >= 1e5 || a < 1e-2) ? "%.3g" : "%.4g", *v);
  return buf;
}

/// The efficiency against input speed per load, against temperature at rated torque, and the no-load running torque
/// against speed per temperature: the catalogs' efficiency curves, with what they count under them.
std::string loss_map_svg(const Datasheet& d) {
  const LossMap& m = *d.loss_map;
  static const char* colours[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2"};
  const auto colour = [](std::size_t i) { return colours[i % 7]; };
  char buf[160];
  LinePlot by_speed;
  std::snprintf(buf, sizeof buf, "efficiency against input speed at %.4g °C", m.temperature_C);
  by_speed.title = buf;
  by_speed.x_label = "input speed (rpm)";
  by_speed.y_label = "efficiency (%)";
  for (std::size_t k = 0; k < m.load_fractions.size(); ++k) {
    PlotSeries s;
    std::snprintf(buf, sizeof buf, "%.0f %% of rated torque", 100 * m.load_fractions[k]);
    s.label = buf;
    s.x = m.speeds_rpm;
    for (const double e : m.efficiency[k]) s.y.push_back(100 * e);
    s.colour = colour(k);
    s.markers = false;
    by_speed.series.push_back(s);
  }
  LinePlot by_temperature;
  std::snprintf(buf, sizeof buf, "efficiency at rated torque and %.0f rpm against temperature", m.rated_speed_rpm);
  by_temperature.title = buf;
  by_temperature.x_label = "lubricant temperature (°C)";
  by_temperature.y_label = "efficiency (%)";
  PlotSeries t;
  t.x = m.temperatures_C;
  for (const double e : m.efficiency_at_rated) t.y.push_back(100 * e);
  by_temperature.series.push_back(t);
  LinePlot no_load;
  no_load.title = "no-load running torque at the input against speed";
  no_load.x_label = "input speed (rpm)";
  no_load.y_label = "no-load running torque (mN·m)";
  for (std::size_t k = 0; k < m.temperatures_C.size(); ++k) {
    PlotSeries s;
    std::snprintf(buf, sizeof buf, "%.4g °C", m.temperatures_C[k]);
    s.label = buf;
    s.x = m.speeds_rpm;
    for (const double v : m.no_load_torque_Nm[k]) s.y.push_back(1e3 * v);
    s.colour = colour(k);
    no_load.series.push_back(s);
  }
  Figure f;
  f.header = {"Where the power goes"};
  f.panels = {by_speed, by_temperature, no_load};
  return svg_figure(f);
}

}  // namespace

std::string datasheet_json(const Datasheet& d, const Case& c) {
  nlohmann::json j = nlohmann::json::object();
  j["case_file"] = c.path;
  const Provenance p = provenance_of(c);
  j["case"] = nlohmann::json::parse(p.resolved_case);
  j["version"] = p.version;
  j["catalog_size"] = d.catalog_size ? nlohmann::json(*d.catalog_size) : nlohmann::json(nullptr);
  j["ratio"] = d.ratio;
  nlohmann::json figures = nlohmann::json::object();
  nlohmann::json order = nlohmann::json::array();
  for (const DatasheetFigure& f : d.figures) {
    figures[f.name] = {{"label", f.label},
                       {"value", number_or_null(f.value)},
                       {"computed", f.value.has_value()},
                       {"unit", f.unit},
                       {"method", f.method},
                       {"published", number_or_null(f.published)},
                       {"published_source", f.published_source}};
    order.push_back(f.name);
  }
  j["figures"] = figures;
  j["order"] = order;
  j["idealisations"] = d.idealisations;
  if (d.loss_map) {
    const LossMap& m = *d.loss_map;
    j["loss_map"] = {{"counts", d.loss_map_counts},
                     {"temperature_C", m.temperature_C},
                     {"speeds_rpm", m.speeds_rpm},
                     {"load_fractions", m.load_fractions},
                     {"temperatures_C", m.temperatures_C},
                     {"rated_speed_rpm", m.rated_speed_rpm},
                     {"efficiency", m.efficiency},
                     {"efficiency_at_rated", m.efficiency_at_rated},
                     {"no_load_torque_Nm", m.no_load_torque_Nm}};
  } else {
    j["loss_map"] = nullptr;
  }
  return j.dump(2) + "\n";
}

Datasheet read_datasheet(const std::filesystem::path& path) {
  const JsonIn j = JsonIn::open(path, kDatasheetCannotOpen, kDatasheetExpected);
  Datasheet d;
  if (!j["catalog_size"].is_null()) d.catalog_size = static_cast<int>(j["catalog_size"].integer());
  d.ratio = static_cast<int>(j["ratio"].integer());
  const JsonIn figures = j["figures"];
  for (const JsonIn& name : j["order"].elements()) {
    const JsonIn f = figures[name.text()];
    DatasheetFigure out;
    out.name = name.text();
    out.label = f["label"].text();
    out.unit = f["unit"].text();
    out.method = f["method"].text();
    out.published_source = f["published_source"].text();
    const bool computed = f["computed"].flag();
    if (computed) out.value = f["value"].is_null() ? std::numeric_limits<double>::infinity() : f["value"].number();  // null: beyond the search
    if (!f["published"].is_null()) out.published = f["published"].number();
    d.figures.push_back(std::move(out));
  }
  for (const JsonIn& s : j["idealisations"].elements()) d.idealisations.push_back(s.text());
  if (const std::optional<JsonIn> lm = j.find("loss_map"); lm && !lm->is_null()) {
    LossMap m;
    d.loss_map_counts = (*lm)["counts"].text();
    m.temperature_C = (*lm)["temperature_C"].finite();
    m.speeds_rpm = (*lm)["speeds_rpm"].numbers();
    m.load_fractions = (*lm)["load_fractions"].numbers();
    m.temperatures_C = (*lm)["temperatures_C"].numbers();
    m.rated_speed_rpm = (*lm)["rated_speed_rpm"].finite();
    m.efficiency.clear();
    for (const JsonIn& row : (*lm)["efficiency"].elements(m.load_fractions.size()))
      m.efficiency.push_back(row.numbers());
    m.efficiency_at_rated = (*lm)["efficiency_at_rated"].numbers();
    for (const JsonIn& row : (*lm)["no_load_torque_Nm"].elements(m.temperatures_C.size()))
      m.no_load_torque_Nm.push_back(row.numbers());
    d.loss_map = std::move(m);
  }
  return d;
}

std::string datasheet_table(const Datasheet& d) {
  std::string out;
  char buf[512];
  for (const DatasheetFigure& f : d.figures) {
    std::string published = f.published ? value_text(f.published) + " (" + f.published_source + ")" : "";
    std::snprintf(buf, sizeof buf, "  %-40s %14s %-8s %s\n", f.label.c_str(), value_text(f.value).c_str(),
                  f.unit.c_str(), published.empty() ? "" : ("published " + published).c_str());
    out += buf;
  }
  return out;
}

std::string datasheet_html(const Datasheet& d, const Case& c) {
  std::string h =
      "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>strainwave datasheet: " + html_escape(c.path) +
      "</title>\n<style>body{font-family:sans-serif;margin:2em;max-width:75em}table{border-collapse:collapse}"
      "td,th{border:1px solid #bbb;padding:.3em .6em;vertical-align:top}th{background:#eee}td.n{text-align:right;"
      "white-space:nowrap}td.m{font-size:90%;color:#333}</style></head><body>\n";
  h += "<h1>Datasheet of " + html_escape(c.path) + "</h1>\n<p>Ratio " + std::to_string(d.ratio);
  if (d.catalog_size) h += "; the case stands for catalog size " + std::to_string(*d.catalog_size) +
                           " (published figures beside, compared and never fitted)";
  h += ".</p>\n<table><tr><th>figure</th><th>computed</th><th>unit</th><th>published</th><th>how it was computed"
       "</th></tr>\n";
  for (const DatasheetFigure& f : d.figures) {
    h += "<tr><td>" + html_escape(f.label) + "</td><td class=\"n\">" + html_escape(value_text(f.value)) +
         "</td><td>" + html_escape(f.unit) + "</td><td class=\"n\">" +
         (f.published ? html_escape(value_text(f.published)) + "<br><small>" + html_escape(f.published_source) +
                            "</small>"
                      : "") +
         "</td><td class=\"m\">" + html_escape(f.method) + "</td></tr>\n";
  }
  h += "</table>\n";
  if (d.loss_map)
    h += "<h2>Where the power goes, over speed, load and temperature</h2>\n<p>Each point is the power balance at the "
         "loaded contact's torque step nearest the load; it " + html_escape(d.loss_map_counts) + ".</p>\n" +
         loss_map_svg(d) + "\n";
  h += "<h2>What the figures take as given</h2>\n<ul>\n";
  for (const std::string& s : d.idealisations) h += "<li>" + html_escape(s) + "</li>\n";
  h += "</ul>\n</body></html>\n";
  return h;
}

}  // namespace sw
