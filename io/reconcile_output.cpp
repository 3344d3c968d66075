#include "io/reconcile_output.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "common/error.hpp"
#include "io/json_file.hpp"

namespace sw {

namespace {

using nlohmann::json;
using reconcile::Report;
using reconcile::ReportCatalog;
using reconcile::ReportCatalogReference;
using reconcile::ReportEffect;
using reconcile::ReportLocation;

// ---- writing ------------------------------------------------------------------------------------------------------

json effect_json(const ReportEffect& e) {
  json params = json::object(), ci = json::object(), fixed = json::object();
  if (e.order) params["order"] = *e.order;
  for (const auto& [name, v] : e.params) params[name] = v;
  for (const auto& [name, range] : e.ci95) ci[name] = {range.first, range.second};
  for (const auto& [name, from] : e.fixed) fixed[name] = {{"from", from}};
  json j = {{"name", e.name}, {"physics", e.physics}, {"params", params}, {"ci95", ci}, {"fixed", fixed},
            {"delta_bic", e.delta_bic}, {"p_value", e.p_value}};
  if (!e.meaning.empty()) j["meaning"] = e.meaning;
  if (e.model_runs > 0) {
    j["model_discrepancy"] = e.model_discrepancy;
    j["model_runs"] = e.model_runs;
  }
  return j;
}

json reference_json(const ReportCatalogReference& r) {
  return {{"size", r.size},
          {"K1_Nm_per_rad", r.k1_Nm_per_rad},
          {"K2_Nm_per_rad", r.k2_Nm_per_rad},
          {"K3_Nm_per_rad", r.k3_Nm_per_rad},
          {"T1_Nm", r.t1_Nm},
          {"T2_Nm", r.t2_Nm},
          {"rated_torque_Nm", r.rated_torque_Nm},
          {"hysteresis_loss_max_arcmin", r.hysteresis_loss_max_arcmin},
          {"lost_motion_max_arcmin", r.lost_motion_max_arcmin}};
}

json catalog_json(const ReportCatalog& c) {
  json j = {{"segments", c.segments},
            {"K1_Nm_per_rad", c.k1_Nm_per_rad},
            {"K2_Nm_per_rad", c.k2_Nm_per_rad},
            {"K3_Nm_per_rad", c.k3_Nm_per_rad},
            {"T1_Nm", c.t1_Nm},
            {"T2_Nm", c.t2_Nm},
            {"rated_torque_Nm", c.rated_torque_Nm},
            {"rated_torque_from", c.rated_torque_from},
            {"hysteresis_loss_arcmin", c.hysteresis_loss_arcmin},
            {"play_width_arcmin", c.play_width_arcmin},
            {"catalog_lost_motion_arcmin", c.catalog_lost_motion_arcmin},
            {"note", c.note}};
  if (c.reference) j["reference"] = reference_json(*c.reference);
  if (c.k1_segment_twist_over_noise) j["K1_segment_twist_over_noise"] = *c.k1_segment_twist_over_noise;
  return j;
}

// ---- reading ------------------------------------------------------------------------------------------------------

/// A number of the file; NaN where the writer had none to write (JSON null).
double number(const json& j) { return j.is_null() ? NAN : j.get<double>(); }

ReportEffect effect_from(const json& j) {
  ReportEffect e;
  e.name = j.at("name").get<std::string>();
  e.physics = j.at("physics").get<std::string>();
  for (const auto& [name, v] : j.at("params").items()) {
    if (name == "order") e.order = v.get<int>();
    else e.params[name] = number(v);
  }
  for (const auto& [name, v] : j.at("ci95").items())  // an end the data do not bound is written null (JSON has no inf)
    e.ci95[name] = {v.at(0).is_null() ? -INFINITY : number(v.at(0)), v.at(1).is_null() ? INFINITY : number(v.at(1))};
  if (j.contains("fixed"))
    for (const auto& [name, v] : j.at("fixed").items()) e.fixed[name] = v.at("from").get<std::string>();
  if (j.contains("meaning")) e.meaning = j.at("meaning").get<std::string>();
  if (j.contains("model_runs")) {
    e.model_discrepancy = number(j.at("model_discrepancy"));
    e.model_runs = static_cast<int>(number(j.at("model_runs")));
  }
  e.delta_bic = number(j.at("delta_bic"));
  e.p_value = number(j.at("p_value"));
  return e;
}

ReportCatalogReference reference_from(const json& j) {
  return {j.at("size").get<int>(),           number(j.at("K1_Nm_per_rad")),
          number(j.at("K2_Nm_per_rad")),     number(j.at("K3_Nm_per_rad")),
          number(j.at("T1_Nm")),             number(j.at("T2_Nm")),
          number(j.at("rated_torque_Nm")),   number(j.at("hysteresis_loss_max_arcmin")),
          number(j.at("lost_motion_max_arcmin"))};
}

ReportCatalog catalog_from(const json& j) {
  ReportCatalog c;
  c.segments = j.at("segments").get<int>();
  c.k1_Nm_per_rad = number(j.at("K1_Nm_per_rad"));
  c.k2_Nm_per_rad = number(j.at("K2_Nm_per_rad"));
  c.k3_Nm_per_rad = number(j.at("K3_Nm_per_rad"));
  c.t1_Nm = number(j.at("T1_Nm"));
  c.t2_Nm = number(j.at("T2_Nm"));
  c.rated_torque_Nm = number(j.at("rated_torque_Nm"));
  c.rated_torque_from = j.at("rated_torque_from").get<std::string>();
  c.hysteresis_loss_arcmin = number(j.at("hysteresis_loss_arcmin"));
  c.play_width_arcmin = number(j.at("play_width_arcmin"));
  c.catalog_lost_motion_arcmin = number(j.at("catalog_lost_motion_arcmin"));
  c.note = j.at("note").get<std::string>();
  if (j.contains("reference")) c.reference = reference_from(j.at("reference"));
  if (j.contains("K1_segment_twist_over_noise"))
    c.k1_segment_twist_over_noise = number(j.at("K1_segment_twist_over_noise"));
  return c;
}

Report report_from(const json& j, const std::string& where) {
  Report r;
  const std::string kind = j.at("kind").get<std::string>();
  const auto k = reconcile::kind_from_name(kind);
  if (!k) throw InputError(where + ": kind = '" + kind + "'; expected torsion, transmission, backlash or dynamics");
  r.kind = *k;
  r.samples = j.at("samples").get<int>();
  const json& base = j.at("baseline");
  r.baseline_model = base.at("model").get<std::string>();
  if (base.contains("source")) r.baseline_source = base.at("source").get<std::string>();
  r.baseline_rms = number(base.at("rms"));
  r.baseline_heldout_rms = number(base.at("heldout_rms"));
  r.significant = j.at("mismatch").at("significant").get<bool>();
  for (const auto& l : j.at("mismatch").at("locations"))
    r.locations.push_back({l.at("domain").get<std::string>(), l.at("description").get<std::string>(),
                           number(l.at("p_value"))});
  for (const auto& e : j.at("effects")) r.effects.push_back(effect_from(e));
  for (const auto& x : j.at("rejected"))
    r.rejected.push_back({x.at("name").get<std::string>(), x.at("reason").get<std::string>()});
  r.final_rms = number(j.at("final").at("rms"));
  r.final_heldout_rms = number(j.at("final").at("heldout_rms"));
  if (j.contains("refit"))
    r.refit = reconcile::ReportRefit{number(j.at("refit").at("rms")), number(j.at("refit").at("heldout_rms"))};
  if (j.contains("catalog")) r.catalog = catalog_from(j.at("catalog"));
  r.verdict = j.at("verdict").get<std::string>();
  return r;
}

}  // namespace

std::string reconcile_json(const Report& r, const std::optional<Provenance>& provenance) {
  json j;
  if (provenance) j.update(to_json_object(*provenance));
  j["kind"] = reconcile::kind_name(r.kind);
  j["samples"] = r.samples;
  j["baseline"] = {{"model", r.baseline_model}, {"rms", r.baseline_rms}, {"heldout_rms", r.baseline_heldout_rms}};
  if (!r.baseline_source.empty()) j["baseline"]["source"] = r.baseline_source;
  json locations = json::array();
  for (const auto& l : r.locations)
    locations.push_back({{"domain", l.domain}, {"description", l.description}, {"p_value", l.p_value}});
  j["mismatch"] = {{"significant", r.significant}, {"locations", locations}};
  json effects = json::array();
  for (const auto& e : r.effects) effects.push_back(effect_json(e));
  j["effects"] = effects;
  json rejected = json::array();
  for (const auto& x : r.rejected) rejected.push_back({{"name", x.name}, {"reason", x.reason}});
  j["rejected"] = rejected;
  j["final"] = {{"rms", r.final_rms}, {"heldout_rms", r.final_heldout_rms}};
  if (r.refit) j["refit"] = {{"rms", r.refit->rms}, {"heldout_rms", r.refit->heldout_rms}};
  if (r.catalog) j["catalog"] = catalog_json(*r.catalog);
  j["verdict"] = r.verdict;
  return j.dump(2) + "\n";
}

Report parse_reconcile_json(const std::string& text, const std::string& where) {
  try {
    return report_from(json::parse(text), where);
  } catch (const json::exception& e) {
    throw InputError(where + ": not the reconcile.json of `strainwave reconcile` (" + std::string(e.what()) + ")");
  }
}

Report read_reconcile_json(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path.string() + ": cannot open; give the reconcile.json written by `strainwave reconcile`");
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_reconcile_json(ss.str(), path.string());
}

}  // namespace sw
