#include "app/reconcile_model.hpp"

#include <algorithm>
#include <cstdio>
#include <memory>
#include <set>
#include <sstream>

#include "app/contact_job.hpp"
#include "common/error.hpp"
#include "common/format.hpp"
#include "contact/harmonic_body.hpp"
#include "fem/fourier_analysis.hpp"
#include "fem/fourier_solver.hpp"
#include "io/case_edit.hpp"
#include "io/contact_output.hpp"

namespace sw::app {

using reconcile::ModelCandidate;
using reconcile::ModelKeyValues;

namespace {

/// Keys the series parts (series_parts: tooth pairs, generator bearing, circular spline ring) do not read: a re-run
/// that changes only these keeps the base case's parts (the tooth's FEM and the ring are most of a run).
bool leaves_series_parts(const std::string& key) {
  static const std::set<std::string> kBodyKeys = {
      "flexspline.wall_thickness_mm", "flexspline.diaphragm_thickness_mm", "flexspline.length_mm",
      "flexspline.boss_radius_mm",    "flexspline.fillet_radius_mm",       "wave_generator.radial_deformation_mm",
      "wave_generator.axial_position_mm", "wave_generator.band_width_mm",  "contact.friction_coefficient"};
  return kBodyKeys.count(key) > 0;
}

/// The drive's torque-twist curve of a case: the FEM on the harmonic solver and the loaded contact, in memory, read
/// as contact.json would be.
ContactCurve contact_curve_of(const Case& c, const SeriesParts& series, const ModelRunOptions& options) {
  const FlexsplineModel model = flexspline_model(c);
  const FourierSolution fourier = analyse_flexspline_fourier(model, contact_band_request(model, c.contact.face_slices));
  const HarmonicBody body(model, fourier);
  ContactOptions o = contact_options(c, series);
  o.steps = options.contact_steps;
  const ContactAnalysis a = naming_file(c.path, [&] { return analyse_contact(model, body, fem_readout(fourier.figures), o); });
  return parse_contact_curve(contact_json(contact_result(a, c, catalog_reference(c))), c.path + " (re-run)");
}

/// A prediction of the case: the contact curve through make_baseline (the same reading as contact.json), or C_tau.
reconcile::Prediction prediction_of(const Case& c, BaselineSources src, const SeriesParts& series,
                                    const ModelRunOptions& options) {
  std::vector<std::string> notes;
  if (src.torsion == TorsionBaseline::Contact) {
    src.contact_curve = contact_curve_of(c, series, options);
    src.contact_result = c.path + " (re-run)";
  } else {
    src.compliance = analyse_flexspline_fourier(flexspline_model(c)).figures.compliance_rad_per_Nm;
    src.fem_result.clear();
  }
  return make_baseline(reconcile::Kind::Torsion, src, notes).prediction;
}

/// The tool's candidates as a table: key, physics, range as fractions of the case value (lo, hi) or absolute (for
/// a key whose case value may be 0), and where it applies.
struct CandidateRow {
  const char* key;
  const char* physics;
  double lo, hi;
  bool relative;
  bool contact_only;
};

const std::vector<CandidateRow>& candidate_table() {
  static const std::vector<CandidateRow> rows = {
      {"flexspline.rim_thickness_mm", "the rim under the teeth is thinner or thicker than drawn: the flexspline twists "
       "more or less under torque", 0.7, 1.3, true, false},
      {"flexspline.wall_thickness_mm", "the cup's body wall is thinner or thicker than drawn: the body twists more or "
       "less", 0.7, 1.3, true, false},
      {"flexspline.diaphragm_thickness_mm", "the diaphragm is thinner or thicker than drawn: the cup's bottom winds up "
       "more or less", 0.7, 1.3, true, false},
      {"wave_generator.radial_deformation_mm", "the wave generator deflects the flexspline more or less than designed "
       "(cam ovality, bearing fit): the teeth engage deeper or shallower", 0.8, 1.2, true, true},
      {"circular_spline.bolt_circle_inner_mm", "the circular spline is held on another annulus than drawn (bolt "
       "circle, housing face): it ovalises more or less under the tooth forces", 0.96, 1.04, true, true},
      {"circular_spline.bolt_circle_outer_mm", "the circular spline is held on another annulus than drawn (bolt "
       "circle, housing face): it ovalises more or less under the tooth forces", 0.96, 1.04, true, true},
      {"gear.tip_rounding_flexspline_mm", "the flexspline's tooth tips are rounded more than drawn: teeth at the mesh "
       "zones' edges touch later and carry less", 0.0, 0.05, false, true},
      {"contact.friction_coefficient", "friction on the tooth flanks: the loading and unloading branches part",
       0.0, 0.3, false, true}};
  return rows;
}

/// Does the case have this candidate (a number for the key, and for the bolt circles a bolted face)?
std::optional<double> candidate_value(const Case& c, const std::string& key) {
  if (key.rfind("circular_spline.bolt_circle", 0) == 0 &&
      (!c.circular_spline || c.circular_spline->mounting != CircularSplineMounting::BoltedFace))
    return std::nullopt;
  if (key == "flexspline.diaphragm_thickness_mm" && c.flexspline.shape != FlexsplineShape::Cup) return std::nullopt;
  if (key.rfind("gear.", 0) == 0 && !c.gear) return std::nullopt;
  if (key.rfind("wave_generator.", 0) == 0 && !c.wave_generator) return std::nullopt;
  return case_number(c, key);
}

ModelCandidate candidate_of(const CandidateRow& row, double value) {
  return {row.key, row.physics, row.relative ? row.lo * value : row.lo, row.relative ? row.hi * value : row.hi, value};
}

}  // namespace

Case case_with(const Case& c, const ModelKeyValues& values) {
  return parse_case(case_text_with(describe_case(c), c.path, values, "model re-run"), c.path);
}

reconcile::Baseline model_baseline(const Case& c, const BaselineSources& src, const ModelRunOptions& options) {
  if (c.solver.method != SolverMethod::Fourier)
    throw InputError(c.path + ": solver.method = \"tet10\"; the model is re-run for its case keys on the harmonic "
                     "solver (method = \"fourier\", or \"auto\" for a body of revolution)");
  const auto series = std::make_shared<SeriesParts>(series_parts(c));
  reconcile::Baseline b;
  b.model = src.torsion == TorsionBaseline::Contact ? "contact" : "fem";
  b.source = c.path + " (the model run now, re-run for its case keys)";
  b.prediction = prediction_of(c, src, *series, options);
  b.model_run = [c, src, series, options](const ModelKeyValues& values) {
    const Case changed = case_with(c, values);
    const bool same_parts = std::all_of(values.begin(), values.end(), [](const auto& kv) { return leaves_series_parts(kv.first); });
    return prediction_of(changed, src, same_parts ? *series : series_parts(changed), options);
  };
  return reconcile::with_remembered_model_runs(b);
}

std::vector<ModelCandidate> default_candidates(const Case& c, TorsionBaseline baseline) {
  std::vector<ModelCandidate> out;
  for (const CandidateRow& row : candidate_table()) {
    if (row.contact_only && baseline != TorsionBaseline::Contact) continue;
    if (const auto v = candidate_value(c, row.key)) out.push_back(candidate_of(row, *v));
  }
  return out;
}

ModelCandidate parse_candidate(const Case& c, const std::string& spec, TorsionBaseline baseline) {
  const auto eq = spec.find('=');
  const std::string key = spec.substr(0, eq);
  const auto value = case_number(c, key);
  if (!value)
    throw InputError("--candidate " + spec + ": " + c.path + " has no numeric key " + key +
                     "; expected TABLE.KEY[=LO:HI] naming a number of the case (e.g. flexspline.rim_thickness_mm)");
  ModelCandidate cand{key, "the case's " + key + " differs from the drive's", 0.8 * *value, 1.2 * *value, *value};
  for (const ModelCandidate& d : default_candidates(c, baseline))
    if (d.key == key) cand = d;
  if (eq != std::string::npos) {
    std::stringstream range(spec.substr(eq + 1));
    std::string lo_s, hi_s;
    char* end = nullptr;
    if (!std::getline(range, lo_s, ':') || !std::getline(range, hi_s)) lo_s.clear();
    cand.lo = std::strtod(lo_s.c_str(), &end);
    const bool lo_ok = !lo_s.empty() && *end == '\0';
    cand.hi = std::strtod(hi_s.c_str(), &end);
    if (!lo_ok || hi_s.empty() || *end != '\0')
      throw InputError("--candidate " + spec + ": expected TABLE.KEY=LO:HI with numbers LO < HI");
  }
  if (!(cand.lo < cand.hi) || !(*value >= cand.lo && *value <= cand.hi))
    throw InputError("--candidate " + spec + ": the range [" + six_digits(cand.lo) + ", " + six_digits(cand.hi) + "] must have LO < HI" +
                     " and hold the case value " + six_digits(*value));
  return cand;
}

std::vector<ModelCandidate> model_candidates(const Case& c, TorsionBaseline baseline,
                                             const std::vector<std::string>& specs) {
  std::vector<ModelCandidate> out = default_candidates(c, baseline);
  for (const std::string& s : specs) {
    const ModelCandidate cand = parse_candidate(c, s, baseline);
    const auto it = std::find_if(out.begin(), out.end(), [&](const ModelCandidate& d) { return d.key == cand.key; });
    if (it != out.end()) *it = cand;
    else out.push_back(cand);
  }
  return out;
}

std::string reconciled_case_text(const Case& c, const reconcile::Refit& refit) {
  std::string head = "# " + c.path + " with the values reconcile fitted to the recording (the model re-run with them\n"
                     "# explains it; the other keys resolved as in the case):\n";
  for (const reconcile::RefitValue& v : refit.values)
    head += "#   " + v.key + " = " + six_digits(v.value) + " (95 % interval [" + six_digits(v.lo) + ", " + six_digits(v.hi) +
            "]; the case had " + six_digits(v.case_value) + ")\n";
  return head + case_text_with(describe_case(c), c.path, refit.key_values, "reconciled case");
}

}  // namespace sw::app
