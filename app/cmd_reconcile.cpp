// `strainwave reconcile CASE.toml RECORDING.csv [--fem DIR/result.json] [--compliance C]
// [--baseline fem|contact [--contact DIR/contact.json]] [--update-model] [--candidate KEY[=LO:HI]] [--out DIR]`:
// compare a recording with the simulation, locate the mismatch, name and fit the missing physics, and prove the
// improvement on held-out data. A torsion recording is held against C_tau T of the flexspline body (fem) or against the drive's torque-twist curve from the loaded tooth
// contact (contact). With --update-model (or --candidate) the case's physical keys are weighed beside the catalog
// effects, the model re-run for them and refitted (reconciled.toml). Writes reconcile.json and reconcile.html
// atomically; prints the verdict.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/commands.hpp"
#include "app/reconcile_baseline.hpp"
#include "app/reconcile_model.hpp"
#include "common/error.hpp"
#include "common/progress.hpp"
#include "io/atomic_file.hpp"
#include "io/case.hpp"
#include "io/provenance.hpp"
#include "io/reconcile_output.hpp"
#include "reconcile/reconcile.hpp"
#include "reconcile/verdict.hpp"

namespace sw::app {
namespace {

struct ReconcileArgs {
  std::string case_path, recording_path, fem, out, baseline = "fem", contact;
  double compliance = 0.0;
  bool update_model = false;
  std::vector<std::string> candidates;
  reconcile::Options options;
};

/// The analysis with the case's physical candidates (--update-model, --candidate): the baseline is the model run
/// now and re-run for its keys; the refit's case is returned in `reconciled` (empty without a refit).
reconcile::Result update_model(const ReconcileArgs& a, const Case& c, const reconcile::Recording& rec,
                               const BaselineSources& src, std::vector<std::string>& notes, reconcile::Experiment& e,
                               std::string& reconciled) {
  if (rec.kind != reconcile::Kind::Torsion)
    throw InputError("--update-model: " + rec.path + " is a " + reconcile::kind_name(rec.kind) +
                     " recording; the model is re-run for its case keys on torsion recordings");
  const auto candidates = model_candidates(c, src.torsion, a.candidates);
  if (!a.contact.empty() || !a.fem.empty() || a.compliance > 0.0)
    notes.push_back("--update-model: the baseline is the model of " + c.path + " run now (not --fem, --compliance "
                    "or --contact), so that it and its re-runs are one model");
  const reconcile::Baseline base = model_baseline(c, src);
  e = reconcile::make_experiment(rec, base);
  reconcile::ModelUpdate u = reconcile::update_model(e, base, candidates, a.options);
  if (u.refit) reconciled = reconciled_case_text(c, *u.refit);
  return u.result;
}

void run_reconcile(const ReconcileArgs& a) {
  const Case c = load_case(a.case_path);
  progress(case_headline(c));
  const reconcile::Recording rec = reconcile::load_recording(a.recording_path);
  BaselineSources src;
  src.case_file = c;
  src.torsion = parse_torsion_baseline(a.baseline);
  if (!a.contact.empty() && src.torsion != TorsionBaseline::Contact)
    throw InputError("--contact " + a.contact + ": the torque-twist curve is read only with --baseline contact");
  src.fem_result = a.fem;
  src.contact_result = a.contact.empty() ? (default_out_dir(c) / "contact.json").string() : a.contact;
  if (a.compliance > 0.0) src.compliance = a.compliance;
  src.recording = &rec;
  std::vector<std::string> notes;
  if (src.torsion == TorsionBaseline::Contact && rec.kind != reconcile::Kind::Torsion)
    notes.push_back("--baseline contact applies to torsion recordings; this one is " + reconcile::kind_name(rec.kind) +
                    " and keeps its own baseline");
  const bool update = a.update_model || !a.candidates.empty();
  reconcile::Experiment e;
  std::string reconciled;
  reconcile::Result r;
  if (update) {
    r = update_model(a, c, rec, src, notes, e, reconciled);
  } else {
    e = reconcile::make_experiment(rec, make_baseline(rec.kind, src, notes));
    r = reconcile::reconcile(e, a.options);
  }
  for (const auto& n : notes) progress("reconcile: " + n);
  OutputSet outputs(a.out.empty() ? default_out_dir(c) : std::filesystem::path(a.out),
                    {"reconcile.json", "reconcile.html", "reconciled.toml"});
  write_resolved_case(c, outputs);
  write_file_atomic(outputs.staging() / "reconcile.json", reconcile_json(reconcile::report_of(r), provenance_of(c)));
  write_file_atomic(outputs.staging() / "reconcile.html", reconcile::report_html(e, rec, r, notes));
  if (!reconciled.empty()) write_file_atomic(outputs.staging() / "reconciled.toml", reconciled);
  outputs.commit();
  std::fputs(reconcile::report_summary(r).c_str(), stdout);
  for (const auto& n : notes)
    if (n.find("disagree") != std::string::npos || n.find("but the recording") != std::string::npos)
      std::printf("  note: %s\n", n.c_str());
  std::printf("  %.2f s; wrote %s/reconcile.{json,html}%s\n", r.seconds, outputs.dir().string().c_str(),
              reconciled.empty() ? "" : " and reconciled.toml");
}

}  // namespace

void add_reconcile_command(CLI::App& app) {
  auto a = std::make_shared<ReconcileArgs>();
  auto* cmd = app.add_subcommand("reconcile",
                                 "compare a recording with the simulation: locate the mismatch, name and fit the "
                                 "missing physics, check it on held-out data (writes reconcile.json, reconcile.html)");
  cmd->add_option("case", a->case_path, "case file (TOML)")->required()->check(CLI::ExistingFile);
  cmd->add_option("recording", a->recording_path, "recording (CSV with '# key: value' metadata; see SPEC.md)")
      ->required();
  cmd->add_option("--fem", a->fem, "FEM result.json (torsion: C_tau = compliance_rad_per_Nm)");
  cmd->add_option("--compliance", a->compliance, "torsion: C_tau in rad/(N*m), overrides --fem")->check(CLI::PositiveNumber);
  cmd->add_option("--baseline", a->baseline,
                  "torsion: what the recording is held against: fem (C_tau T of the flexspline body) or contact (the "
                  "drive's torque-twist curve of `strainwave contact`)")
      ->capture_default_str()->check(CLI::IsMember({"fem", "contact"}));
  cmd->add_option("--contact", a->contact, "contact.json for --baseline contact (default out/<case stem>/contact.json)");
  cmd->add_option("--out", a->out, "output directory (default out/<case stem>/)");
  cmd->add_flag("--update-model", a->update_model,
                "torsion: weigh the case's physical keys (rim, wall, diaphragm, generator, circular spline support, "
                "tip rounding, friction) beside the catalog effects, re-running the model for them, refit the "
                "accepted ones and write reconciled.toml");
  cmd->add_option("--candidate", a->candidates,
                  "KEY[=LO:HI]: one more numeric case key to update the model on, with its plausible range (implies "
                  "--update-model; repeat for more)");
  cmd->add_option("--bootstrap", a->options.bootstrap, "parametric bootstrap replicates for breakpoint/transition effects")
      ->capture_default_str()->check(CLI::Range(19, 100000));
  cmd->add_option("--seed", a->options.seed, "bootstrap seed")->capture_default_str();
  cmd->add_option("--alpha", a->options.alpha_family, "family-wise level of the mismatch tests")
      ->capture_default_str()->check(CLI::Range(1e-6, 0.5));
  cmd->add_option("--heldout", a->options.heldout_fraction, "fraction of rows held out at the end")
      ->capture_default_str()->check(CLI::Range(0.05, 0.5));
  cmd->callback([a] { run_reconcile(*a); });
}

}  // namespace sw::app
