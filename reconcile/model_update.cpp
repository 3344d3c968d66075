#include "reconcile/model_update.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "common/error.hpp"
#include "common/format.hpp"
#include "common/progress.hpp"
#include "reconcile/fit.hpp"
#include "reconcile/rerun.hpp"
#include "reconcile/stats.hpp"

namespace sw::reconcile {

using Vec = Eigen::VectorXd;
using Mat = Eigen::MatrixXd;

namespace {


/// Below this fraction of the baseline's size, the change a candidate makes over its whole plausible range is taken
/// as no response (the model does not read the key for this recording).
constexpr double kNoResponse = 1e-6;

/// Levenberg-Marquardt: the most iterations, and the step (in units of each key's sensitivity step) below which the
/// values have converged: 1e-3 of a step moves the prediction by ~1e-3 of the column's effect over a step, far below
/// any interval.
constexpr int kMaxIterations = 12;
constexpr double kConvergedStep = 1e-3;


/// The response of a re-run with `values` set.
Vec response_at(const Experiment& e, const Baseline& base, const ModelKeyValues& values) {
  return predicted_response(e, base.model_run(values));
}

/// d response / d key at `value` (per unit of the key): central differences of +-step, one-sided (forward from the
/// value) where value - step falls below the candidate's range (a friction coefficient or a tip rounding of 0).
Vec sensitivity_at(const Experiment& e, const Baseline& base, const ModelCandidate& c, const ModelKeyValues& at,
                   double value) {
  const double h = sensitivity_step(c);
  auto with = [&](double v) {
    ModelKeyValues kv = at;
    auto it = std::find_if(kv.begin(), kv.end(), [&](const auto& p) { return p.first == c.key; });
    if (it == kv.end()) kv.emplace_back(c.key, v);
    else it->second = v;
    return kv;
  };
  if (value - h < c.lo) return (response_at(e, base, with(value + h)) - response_at(e, base, with(value))) / h;
  if (value + h > c.hi) return (response_at(e, base, with(value)) - response_at(e, base, with(value - h))) / h;
  return (response_at(e, base, with(value + h)) - response_at(e, base, with(value - h))) / (2.0 * h);
}

/// The value of a candidate's key at a point of linearisation: the point's, else the case's.
double value_at(const ModelCandidate& c, const ModelKeyValues& at) {
  for (const auto& [key, v] : at)
    if (key == c.key) return v;
  return c.case_value;
}

/// The physical effect of a candidate: its column (per unit change of the key) and its headline, the value it
/// implies and the case's.
EffectSpec model_spec(const Experiment& e, const ModelCandidate& c, double at, const Vec& column) {
  EffectSpec s;
  s.name = model_effect_name(c.key);
  s.kind = e.kind();
  s.label = s.name;
  s.physics = c.physics;
  s.n_linear = 1;
  s.bounds = [](const Experiment&) { return std::make_pair(Vec(0), Vec(0)); };
  s.columns = [column](const Experiment&, const Vec&) { return Mat(column); };
  s.headline = [at, cv = c.case_value](const Experiment&, const FitResult& f, int t) {
    return NamedValues{{"value", at + f.terms[t].beta[0]}, {"case_value", cv}};
  };
  s.implausible = [at, c](const Experiment&, const FitResult& f, int t) {
    const double v = at + f.terms[t].beta[0];
    if (v >= c.lo && v <= c.hi) return std::string();
    return "the recording asks for " + c.key + " = " + formatted("%.4g", v) + ", outside its plausible range [" +
           formatted("%g", c.lo) + ", " + formatted("%g", c.hi) + "] (case " + formatted("%g", c.case_value) +
           "): this part alone does not explain it";
  };
  s.held = [](const Experiment&, const FitResult&, int, const std::string& parameter) {
    return parameter == "case_value" ? std::string("the case") : std::string();
  };
  return s;
}

/// Whitened columns with the nuisance columns projected out (what the data can tell apart).
Vec projected(const Experiment& e, const ArModel& ar, const Vec& column) {
  const Mat N = whiten(ar, nuisance_columns(e));
  const Vec c = whiten(ar, column);
  return N.cols() ? least_squares(N, c).residual : c;
}

/// Adds to each accepted physical effect the candidates the recording cannot tell from it (|r| above
/// kIndistinguishableCorrelation): the equivalent change of that key, "or:KEY", with its interval scaled alike.
void add_indistinguishable(const Experiment& e, const ModelEffects& fx, Result& r) {
  for (AcceptedEffect& a : r.effects)
    for (std::size_t i = 0; i < fx.specs.size(); ++i) {
      if (a.name != fx.specs[i].name) continue;
      const Vec own = projected(e, r.noise, fx.specs[i].columns(e, Vec(0)).col(0));
      const Headline v = a.params.front();  // "value"
      const double cv = fx.candidates[i].case_value;
      for (std::size_t j = 0; j < fx.specs.size(); ++j) {
        if (j == i) continue;
        const Vec other = projected(e, r.noise, fx.specs[j].columns(e, Vec(0)).col(0));
        const double corr = own.dot(other) / std::max(own.norm() * other.norm(), 1e-300);
        if (!(std::abs(corr) > kIndistinguishableCorrelation)) continue;
        const double scale = own.dot(other) / other.squaredNorm();  // change of key j per unit change of key i
        const double cj = fx.candidates[j].case_value;
        const double lo = cj + scale * (v.lo - cv), hi = cj + scale * (v.hi - cv);
        a.params.push_back({"or:" + fx.candidates[j].key, cj + scale * (v.value - cv), std::min(lo, hi),
                            std::max(lo, hi)});
        a.physics += "; the recording cannot tell it from " + fx.specs[j].name + " (columns correlate at " +
                     formatted("%.3f", corr) + "): " + fx.candidates[j].physics;
      }
    }
}

// ---- the refit ----------------------------------------------------------------------------------------------------

/// The refit's problem for the accepted terms of a result: the physical keys with their starts (case value + the
/// selection's linear estimate) and the other terms' columns at their theta.
struct KeyRefit {
  std::vector<ModelCandidate> keys;
  Mat linear;
  Vec start;

  ModelKeyValues key_values(const Vec& v) const {
    ModelKeyValues kv;
    for (std::size_t i = 0; i < keys.size(); ++i) kv.emplace_back(keys[i].key, v[i]);
    return kv;
  }
  /// The problem on re-runs of the model (rows: the fitted ones).
  RerunProblem problem(const Experiment& e, const Baseline& base, const ArModel& ar, int rows) const {
    RerunProblem p{e, ar};
    p.response = [this, &e, &base](const Vec& v) { return response_at(e, base, key_values(v)); };
    p.lo.resize(keys.size());
    p.hi.resize(keys.size());
    for (std::size_t i = 0; i < keys.size(); ++i) {
      p.lo[i] = keys[i].lo;
      p.hi[i] = keys[i].hi;
    }
    p.step = [this](const Vec&, int i) { return sensitivity_step(keys[i]); };
    p.linear = linear;
    p.rows = rows;
    p.converged = kConvergedStep;
    p.max_iterations = kMaxIterations;
    return p;
  }
};

KeyRefit key_refit(const Experiment& e, const ModelEffects& fx, const Result& r) {
  KeyRefit k{{}, nuisance_columns(e), Vec(0)};
  std::vector<double> v;
  for (const Term& t : r.final_model.terms) {
    if (!is_model_effect(*t.spec)) {
      k.linear = hcat(k.linear, t.spec->columns(e, t.theta));
      continue;
    }
    for (std::size_t j = 0; j < fx.specs.size(); ++j)
      if (&fx.specs[j] == t.spec) {
        k.keys.push_back(fx.candidates[j]);
        v.push_back(t.spec->headline(e, r.final_model, static_cast<int>(&t - r.final_model.terms.data()))[0].second);
      }
  }
  k.start = Eigen::Map<Vec>(v.data(), v.size());
  return k;
}

/// 95 % intervals of the values from the final Jacobian (rerun_half_widths: calibrated where the selection's
/// calibration of the noise is on the same rows).
std::vector<RefitValue> refit_values(const KeyRefit& k, const RerunProblem& p, const RerunFit& f,
                                     const SpectralCalibration& cal) {
  std::vector<RefitValue> out;
  const Vec halves = rerun_half_widths(p, f, Eigen::MatrixXd::Identity(k.keys.size(), k.keys.size()), cal);
  for (std::size_t i = 0; i < k.keys.size(); ++i) {
    const double half = halves[i];
    const ModelCandidate& c = k.keys[i];
    const double v = f.values[i];
    const bool edge = v <= c.lo + 1e-9 * (c.hi - c.lo) || v >= c.hi - 1e-9 * (c.hi - c.lo);
    out.push_back({c.key, v, v - half, v + half, c.case_value, edge, c.lo, c.hi});
  }
  return out;
}

/// Replaces the selection's linear estimate of each refitted physical effect by the refit's value and interval.
void set_refitted_values(const Refit& refit, Result& r) {
  for (AcceptedEffect& a : r.effects)
    for (const RefitValue& v : refit.values)
      if (a.name == model_effect_name(v.key))
        for (Headline& h : a.params)
          if (h.name == "value") {
            h = {"value", v.value, v.lo, v.hi};
            if (v.at_range_edge)
              a.meaning = "the refit stops at the edge of the key's plausible range (" + formatted("%g", v.range_lo) +
                          " to " + formatted("%g", v.range_hi) + "): the recording asks for more than this part can "
                          "plausibly give, so read it as a direction, not a value";
          }
}

/// The experiment with its baseline replaced by the model re-run at `at` (the prediction and the response).
Experiment experiment_at(const Experiment& e, const Baseline& base, const ModelKeyValues& at) {
  Experiment out = e;
  const Prediction p = base.model_run(at);
  out.baseline = predicted_response(e, p);
  if (auto* t = std::get_if<TorsionExperiment>(&out.data)) t->model = std::get<TorsionPrediction>(p);
  if (auto* b = std::get_if<BacklashExperiment>(&out.data)) b->model = std::get<BacklashPrediction>(p);
  return out;
}

/// The figures of the case's own model (before any change) kept from the first pass.
void keep_baseline_figures(const Result& first, Result& r) {
  r.baseline_rms = first.baseline_rms;
  r.baseline_heldout_rms = first.baseline_heldout_rms;
  r.residual_before = first.residual_before;
  r.baseline_prediction = first.baseline_prediction;
  r.locations = first.locations;
}

}  // namespace

double sensitivity_step(const ModelCandidate& c) { return kSensitivityStepFraction * (c.hi - c.lo); }

std::shared_ptr<const ModelEffects> model_effects(const Experiment& e, const Baseline& base,
                                                  const std::vector<ModelCandidate>& candidates,
                                                  const ModelKeyValues& at) {
  if (!base.model_run) throw InputError("physical candidates need a baseline the model can re-run");
  auto fx = std::make_shared<ModelEffects>();
  const double scale = std::max(e.baseline.norm(), 1e-300);
  std::vector<Vec> columns;
  for (const ModelCandidate& c : candidates) {
    const Vec column = sensitivity_at(e, base, c, at, value_at(c, at));
    const double change = column.norm() * (c.hi - c.lo);
    if (!(change > kNoResponse * scale)) {
      fx->rejected.push_back({model_effect_name(c.key), model_effect_name(c.key) + ": over [" + formatted("%g", c.lo) +
                                                            ", " + formatted("%g", c.hi) + "] the model's response changes by " +
                                                            formatted("%.3g", change / scale) + " of the baseline's: not read"});
      continue;
    }
    fx->candidates.push_back(c);
    columns.push_back(column);
  }
  fx->specs.reserve(fx->candidates.size());  // terms point into specs: no reallocation after this
  for (std::size_t i = 0; i < columns.size(); ++i)
    fx->specs.push_back(model_spec(e, fx->candidates[i], value_at(fx->candidates[i], at), columns[i]));
  return fx;
}

Baseline with_remembered_model_runs(Baseline base) {
  if (!base.model_run) return base;
  auto store = std::make_shared<std::map<ModelKeyValues, Prediction>>();
  base.model_run = [run = base.model_run, store](const ModelKeyValues& kv) {
    ModelKeyValues key = kv;
    std::sort(key.begin(), key.end());
    auto it = store->find(key);
    if (it == store->end()) it = store->emplace(key, run(kv)).first;
    return it->second;
  };
  return base;
}

std::optional<Refit> refit_model(const Experiment& e, const Baseline& base, const ModelEffects& fx, const Result& r,
                                 const Options& o) {
  const KeyRefit k = key_refit(e, fx, r);
  if (k.keys.empty()) return std::nullopt;
  Refit out;
  // Held out: the same fit on the training rows, scored on the rows it never saw.
  const int hold = std::max(1, static_cast<int>(std::lround(e.n * o.heldout_fraction)));
  const RerunFit train = refit_on_reruns(k.problem(e, base, r.noise, e.n - hold), k.start);
  const Vec train_prediction = train.response + k.linear * train.linear_beta;
  out.heldout_rms = rms(Vec((e.measured - train_prediction).tail(hold)));
  const RerunProblem all = k.problem(e, base, r.noise, e.n);
  const RerunFit f = refit_on_reruns(all, train.values);
  out.iterations = f.iterations;
  out.values = refit_values(k, all, f, r.calibration);
  out.key_values = k.key_values(f.values);
  out.model_response = f.response;
  out.prediction = f.response + k.linear * f.linear_beta;
  out.rms = rms(Vec(e.measured - out.prediction));
  progress("reconcile: refit of " + std::to_string(k.keys.size()) + " case keys on re-runs of the model: " +
           std::to_string(out.iterations) + " iterations, RMS " + formatted("%.4g", out.rms));
  return out;
}

namespace {

/// The refit of an update's accepted physical effects, its values written into the effects.
void add_refit(const Experiment& e, const Baseline& base, const Options& options, ModelUpdate& u) {
  u.refit = refit_model(e, base, *u.effects, u.result, options);
  if (!u.refit) return;
  set_refitted_values(*u.refit, u.result);
  u.result.refitted = true;
  u.result.refit_rms = u.refit->rms;
  u.result.refit_heldout_rms = u.refit->heldout_rms;
  u.result.refit_prediction = u.refit->prediction;
}

/// Selection over the physical candidates (columns at `at`) and the catalog, the physical effects of `first` (a
/// first pass) held in.
ModelUpdate selected(const Experiment& e, const Baseline& base, const std::vector<ModelCandidate>& candidates,
                     const ModelKeyValues& at, const Options& options, const Result* first = nullptr) {
  ModelUpdate u;
  u.effects = model_effects(e, base, candidates, at);
  std::vector<const EffectSpec*> held;
  for (const AcceptedEffect& a : first ? first->effects : std::vector<AcceptedEffect>{})
    for (const EffectSpec& spec : u.effects->specs)
      if (spec.name == a.name) held.push_back(&spec);
  u.result = reconcile(e, options, &u.effects->specs, held);
  for (const Rejected& x : u.effects->rejected) u.result.rejected.push_back(x);
  return u;
}

/// The first pass's record (its test against the case's model) of each physical effect the second pass held in.
void keep_first_records(const Result& first, Result& r) {
  for (AcceptedEffect& a : r.effects)
    for (const AcceptedEffect& f : first.effects)
      if (a.name == f.name && a.name.rfind(model_effect_name(""), 0) == 0) {
        a.delta_bic = f.delta_bic;
        a.p_value = f.p_value;
        a.test = f.test;
      }
}

}  // namespace

ModelUpdate update_model(const Experiment& e, const Baseline& base, const std::vector<ModelCandidate>& candidates,
                         const Options& options) {
  ModelUpdate first = selected(e, base, candidates, {}, options);
  add_refit(e, base, options, first);
  if (!first.refit) {
    add_indistinguishable(e, *first.effects, first.result);
    return first;
  }
  // Selection read the physical keys through their columns at the case values: the response bends over a change of
  // a few per cent, and that bend would pass for phenomenological effects. Select again against the model re-run at
  // the refitted values (the physical effects held in), then refit everything together; the mismatch located and the
  // baseline's figures stay those of the case's model.
  const ModelKeyValues at = first.refit->key_values;
  const Experiment moved = experiment_at(e, base, at);
  ModelUpdate u = selected(moved, base, candidates, at, options, &first.result);
  keep_first_records(first.result, u.result);
  add_refit(moved, base, options, u);
  keep_baseline_figures(first.result, u.result);
  add_indistinguishable(moved, *u.effects, u.result);
  return u;
}

}  // namespace sw::reconcile
