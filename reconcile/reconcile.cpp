#include "reconcile/reconcile.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>

#include "common/error.hpp"
#include "common/format.hpp"
#include "common/progress.hpp"
#include "reconcile/effects.hpp"
#include "reconcile/rerun.hpp"

namespace sw::reconcile {

using Vec = Eigen::VectorXd;
using Mat = Eigen::MatrixXd;

namespace {


/// Resolvable values per nonlinear parameter in the Bonferroni bound that lets a decisive F statistic stand in for
/// the bootstrap (see Analysis::effect_test).
constexpr double kSearchValuesPerParameter = 100.0;

const EffectSpec* effect_by_id(Kind kind, const std::string& id) {
  for (const auto& s : effect_catalog(kind))
    if (s.id() == id) return &s;
  return nullptr;
}

/// Complexity for parsimony between rivals: nonlinear parameters first, then linear ones.
std::pair<int, int> complexity(const EffectSpec& s) { return {s.n_nonlinear(), s.n_linear}; }

bool has(const std::vector<Term>& terms, const std::string& id) {
  for (const auto& t : terms)
    if (t.spec->id() == id) return true;
  return false;
}

/// The terms with `spec` added last (theta to be searched); an exclusive variant of it already present is replaced.
std::vector<Term> with(std::vector<Term> terms, const EffectSpec* spec) {
  terms.erase(std::remove_if(terms.begin(), terms.end(), [&](const Term& t) { return spec->conflicts(*t.spec); }),
              terms.end());
  terms.push_back(Term{spec, Vec(0), Vec(0)});
  return terms;
}

std::vector<Term> without(std::vector<Term> terms, std::size_t i) {
  terms.erase(terms.begin() + i);
  return terms;
}

std::string ids(const std::vector<Term>& terms) {
  std::vector<std::string> v;
  for (const auto& t : terms) v.push_back(t.spec->id());
  std::sort(v.begin(), v.end());
  std::string s;
  for (const auto& x : v) s += x + ",";
  return s;
}

struct SigTest {
  double p_adj = 1.0;
  Vec contribution;  // fitted basis contribution (n)
};

/// The state of one analysis, passed from step to step.
struct Analysis {
  const Experiment& e;
  const Options& opt;
  Vec y;                                  // recording - baseline
  int train = 0;                          // rows fitted for the held-out score
  const std::vector<SignatureSpec>& sigs;
  int m = 0;                              // signatures (Bonferroni factor)
  ArModel ar;
  SpectralCalibration cal;
  std::vector<bool> located;
  std::set<std::string> candidates;       // effect ids the located signatures point to
  FitResult cur;                          // the current model
  std::map<std::string, std::string> rejected;        // id -> reason
  std::map<std::string, AcceptedEffect> accepted;     // id -> test record
  std::map<std::string, std::pair<double, std::string>> test_cache;  // "id|base ids" -> (p, test)
  std::uint64_t salt = 0;
  const std::vector<EffectSpec>* physical = nullptr;  // model:KEY candidates (model_update.hpp), or none
  std::vector<const EffectSpec*> held;                // in the model from the start, never pruned

  Analysis(const Experiment& ex, const Options& o, const std::vector<EffectSpec>* model_effects,
           std::vector<const EffectSpec*> held_in)
      : e(ex), opt(o), y(ex.residual()), sigs(signature_catalog(ex.kind())), m(static_cast<int>(sigs.size())),
        physical(model_effects), held(std::move(held_in)) {
    const int hold = std::max(1, static_cast<int>(std::lround(e.n * opt.heldout_fraction)));
    train = e.n - hold;
  }

  /// The catalog effect or physical candidate of an id; nullptr when neither has it.
  const EffectSpec* spec_of(const std::string& id) const {
    if (const EffectSpec* s = effect_by_id(e.kind(), id)) return s;
    if (physical)
      for (const auto& s : *physical)
        if (s.id() == id) return &s;
    return nullptr;
  }

  FitResult fit(const std::vector<Term>& terms, bool multistart = true, int starts = FitOptions{}.starts) const {
    FitOptions o;
    o.multistart_last = multistart;
    o.starts = starts;
    return fit_model(e, y, terms, ar, o);
  }

  /// RMS over the held-out rows of y - model fitted on the training rows (thetas start at the given terms').
  double heldout(const std::vector<Term>& terms) const {
    FitOptions o;
    o.rows = train;
    o.multistart_last = false;
    const FitResult f = fit_model(e, y, terms, ar, o);
    return rms(Vec((y - f.contribution).tail(e.n - train)));
  }

  SigTest signature(int i, const std::vector<Term>& terms) const {
    const SignatureSpec& s = sigs[i];
    const Mat base = hcat(design_matrix(e, terms), s.condition(e));
    const Mat B = s.basis(e);
    const Vec yw = whiten(ar, y);
    const FTest t = calibrated_f_test(cal, whiten(ar, base), whiten(ar, B), yw);
    SigTest out;
    out.p_adj = std::min(1.0, t.p_value * m);
    const LsResult ls = least_squares(whiten(ar, hcat(base, B)), yw);
    out.contribution = B * ls.beta.tail(B.cols());
    return out;
  }
  bool significant(int i, const std::vector<Term>& terms) const {
    return signature(i, terms).p_adj < opt.alpha_family;
  }

  /// Parametric bootstrap of the likelihood-ratio statistic of `full` (its last term searched) against `reduced`
  /// (noise: the AR model), with an early stop once the p-value cannot reach alpha_effect.
  double bootstrap_p(const FitResult& reduced, const FitResult& full) {
    const double observed = reduced.n_w * std::log(reduced.rss_w / full.rss_w);
    std::mt19937_64 rng(opt.seed * 0x9E3779B97F4A7C15ULL + ++salt);
    std::vector<Term> full_terms = full.terms;
    full_terms.back().theta = Vec(0);
    int exceed = 0;
    const int B = opt.bootstrap;
    for (int b = 0; b < B; ++b) {
      const Vec ystar = reduced.contribution + simulate_ar(ar, e.n, rng);
      FitOptions o0;
      o0.multistart_last = false;
      const FitResult f0 = fit_model(e, ystar, reduced.terms, ar, o0);
      FitOptions o1;
      o1.starts = 1;  // the grid's best start only: each replicate refits the whole model
      const FitResult f1 = fit_model(e, ystar, full_terms, ar, o1);
      if (f0.n_w * std::log(f0.rss_w / f1.rss_w) >= observed) ++exceed;
      if ((1.0 + exceed) / (B + 1.0) > opt.alpha_effect) return (1.0 + exceed) / (b + 2.0);
    }
    return (1.0 + exceed) / (B + 1.0);
  }

  /// Is the last term of `full` (its nonlinear parameters `nl_extra` more than `reduced` has) significant against
  /// the noise? Linear: the calibrated F-test times the harmonic multiplicity. Nonlinear: the same F statistic at the
  /// fitted breakpoints/transitions, Bonferroni-corrected for searching them (kSearchValuesPerParameter values
  /// each); when that bound is not decisive, the parametric bootstrap of the likelihood ratio.
  std::pair<double, std::string> effect_test(const FitResult& reduced, const FitResult& full, int nl_extra) {
    const std::string key = full.terms.back().spec->id() + "|" + ids(reduced.terms);
    if (const auto it = test_cache.find(key); it != test_cache.end()) return it->second;
    const EffectSpec& spec = *full.terms.back().spec;
    const FTest ft = calibrated_f_test(cal, whiten(ar, design_matrix(e, reduced.terms)),
                                       whiten(ar, design_matrix(e, full.terms)), whiten(ar, y));
    std::pair<double, std::string> out;
    if (nl_extra <= 0) {
      out = {std::min(1.0, ft.p_value * spec.multiplicity), "F"};
    } else {
      const double bound = std::min(1.0, ft.p_value * std::pow(kSearchValuesPerParameter, nl_extra));
      out = bound <= opt.alpha_effect ? std::make_pair(bound, std::string("F, search-corrected"))
                                      : std::make_pair(bootstrap_p(reduced, full), std::string("bootstrap"));
      if (out.second == "bootstrap")
        progress("reconcile: bootstrap of " + spec.id() + " against " + ids(reduced.terms) + ": p " + formatted("%.3g", out.first));
    }
    return test_cache[key] = out;
  }

  /// Searches each term's nonlinear parameters again with the others in (grid starts, then all polished together):
  /// a term fitted before the others entered may sit in a local minimum they created.
  FitResult refine(FitResult f) const {
    for (std::size_t i = 0; i < f.terms.size(); ++i) {
      if (f.terms[i].spec->n_nonlinear() == 0) continue;
      std::vector<Term> order = without(f.terms, i);
      order.push_back(f.terms[i]);
      const FitResult g = fit(order, true, 1);
      if (g.rss_w < f.rss_w) f = g;
    }
    return f;
  }

  void accept(const EffectSpec& spec, double dbic, double p, const std::string& test) {
    AcceptedEffect a;
    a.name = spec.name;
    a.physics = spec.physics;
    a.delta_bic = dbic;
    a.p_value = p;
    a.test = test;
    accepted[spec.id()] = a;
    rejected.erase(spec.id());
  }
};

Location make_location(const Experiment& e, const SignatureSpec& s, const SigTest& t) {
  Location loc;
  loc.signature = s.name;
  loc.domain = s.domain;
  loc.p_value = t.p_adj;
  const Vec& c = t.contribution;
  const double amp = c.cwiseAbs().maxCoeff();
  std::string d = s.what;
  if (s.periodic) {
    d += "; amplitude " + formatted("%.3g", amp) + " " + e.response_unit;
  } else {
    const Vec w = s.where(e);
    double lo = INFINITY, hi = -INFINITY;
    for (int i = 0; i < e.n; ++i)
      if (std::abs(c[i]) >= 0.5 * amp) {
        lo = std::min(lo, w[i]);
        hi = std::max(hi, w[i]);
      }
    loc.has_range = std::isfinite(lo);
    loc.lo = lo;
    loc.hi = hi;
    d += "; strongest for " + s.domain + " in [" + formatted("%.4g", lo) + ", " + formatted("%.4g", hi) + "] " + s.where_unit +
         ", up to " + formatted("%.3g", amp) + " " + e.response_unit;
  }
  loc.description = d;
  return loc;
}

/// Do both effects appear among the triggers of one located signature?
bool share_signature(const Analysis& a, const EffectSpec& x, const EffectSpec& z) {
  for (int i = 0; i < a.m; ++i) {
    if (!a.located[i]) continue;
    const auto& t = a.sigs[i].triggers;
    if (std::find(t.begin(), t.end(), x.id()) != t.end() && std::find(t.begin(), t.end(), z.id()) != t.end())
      return true;
  }
  return false;
}

bool triggers(const SignatureSpec& s, const std::string& id) {
  return std::find(s.triggers.begin(), s.triggers.end(), id) != s.triggers.end();
}

// ---- The steps -------------------------------------------------------------------------------------------------

/// Noise model: AR fitted to the residual of a rich model (nuisance + every signature basis), so that structure the
/// signatures can explain does not inflate the noise estimate; its level checked per frequency (calibration).
void fit_noise(Analysis& a, Result& r) {
  Mat rich = nuisance_columns(a.e);
  for (const auto& s : a.sigs) rich = hcat(hcat(rich, s.basis(a.e)), s.condition(a.e));
  a.ar = fit_ar(least_squares(rich, a.y).residual, a.opt.ar_max_order);
  if (a.opt.spectral_half_width > 0) {
    const Mat rich_w = whiten(a.ar, rich);
    a.cal = spectral_calibration(rich_w, least_squares(rich_w, whiten(a.ar, a.y)).residual, a.opt.spectral_half_width);
  }
  r.noise = a.ar;
  r.calibration = a.cal;
  progress("reconcile: " + kind_name(a.e.kind()) + ", " + std::to_string(a.e.n) + " samples, noise AR(" +
           std::to_string(a.ar.order()) + ") sd " + formatted("%.3g", a.ar.process_sd));
}

/// The baseline with its nuisance columns only (offsets, scale): the starting model.
void fit_baseline(Analysis& a, Result& r) {
  std::vector<Term> held;  // physical effects a model update holds in from the start
  for (const EffectSpec* h : a.held) {
    held.push_back(Term{h, Vec(0), Vec(0)});
    a.accept(*h, 0.0, 1.0, "held");
  }
  a.cur = a.fit(held);
  r.residual_before = a.y - a.cur.contribution;
  r.baseline_prediction = a.e.baseline + a.cur.contribution;
  r.baseline_rms = rms(r.residual_before);
  r.baseline_heldout_rms = a.heldout({});
}

/// Which signatures differ from noise, and the effects they point to.
void locate(Analysis& a, Result& r) {
  a.located.assign(a.m, false);
  for (int i = 0; i < a.m; ++i) {
    const SigTest t = a.signature(i, a.cur.terms);
    if (t.p_adj < a.opt.alpha_family) {
      a.located[i] = true;
      r.locations.push_back(make_location(a.e, a.sigs[i], t));
      for (const auto& id : a.sigs[i].triggers) a.candidates.insert(id);
    }
  }
  r.significant = !r.locations.empty();
  if (r.significant && a.physical)
    for (const auto& s : *a.physical) a.candidates.insert(s.id());
  progress("reconcile: located " + std::to_string(r.locations.size()) + " significant signatures, " +
           std::to_string(a.candidates.size()) + " candidate effects");
}

/// A complex effect that passes on its own must also beat each simpler rival of the same signature clearly (BIC and
/// held-out), unless it removes a located signature the rival leaves. Returns the reason it loses, or "".
std::string simpler_rival(Analysis& a, const EffectSpec& spec, const FitResult& alt, double h_alt,
                          const std::vector<std::pair<const EffectSpec*, FitResult>>& passing) {
  for (const auto& [rv, rv_fit] : passing) {
    if (rv == &spec || complexity(*rv) >= complexity(spec) || !share_signature(a, *rv, spec)) continue;
    const double dbic_rv = alt.bic() - rv_fit.bic();
    const double h_rv = a.heldout(rv_fit.terms);
    bool needed = false;
    for (int i = 0; i < a.m && !needed; ++i) {
      if (!a.located[i] || !triggers(a.sigs[i], spec.id()) || triggers(a.sigs[i], rv->id())) continue;
      needed = a.significant(i, rv_fit.terms) && !a.significant(i, alt.terms);
    }
    if (!needed && (!(dbic_rv < -a.opt.min_delta_bic) || !(h_alt < h_rv)))
      return rv->label + " explains as much (BIC " + formatted("%.1f", dbic_rv) + " vs it, held-out " +
             formatted("%.4g", h_rv) + " -> " + formatted("%.4g", h_alt) + ")";
  }
  return "";
}

/// Physical candidates (case keys) whose BIC lies within `bar` of the best candidate's move ahead of the
/// phenomenological ones, in their BIC order: when both explain the mismatch as well, the model's own parameter is
/// the explanation (it says what differs in the part).
void prefer_physical(std::vector<std::pair<const EffectSpec*, FitResult>>& evals, double bar) {
  if (evals.empty()) return;
  const double best = evals.front().second.bic();
  std::stable_partition(evals.begin(), evals.end(), [&](const auto& ev) {
    return is_model_effect(*ev.first) && ev.second.bic() <= best + bar;
  });
}

/// Forward selection: one effect at a time, the best by BIC that passes every test (BIC, simpler rivals, held-out,
/// removes a signature that points to it, significant against the noise).
/// EffectSpec::implausible of the spec's term in a fitted model ("" when it has none).
std::string implausible(const Analysis& a, const EffectSpec& spec, const FitResult& f) {
  for (std::size_t k = 0; k < f.terms.size(); ++k)
    if (f.terms[k].spec == &spec && spec.implausible) return spec.implausible(a.e, f, static_cast<int>(k));
  return "";
}

void admit_one_at_a_time(Analysis& a) {
  const double bar = a.opt.min_delta_bic;
  // A physical key's first "the recording asks for KEY = v" stands: the value it would need with the fewest other
  // effects in the model (alone against the model, in the first round), which later rounds would replace by its
  // answer to what those effects left.
  const auto reject = [&a](const EffectSpec& spec, const std::string& reason) {
    std::string& old = a.rejected[spec.id()];
    if (is_model_effect(spec) && old.find(" asks for ") != std::string::npos) return;
    old = reason;
  };
  while (static_cast<int>(a.cur.terms.size()) < a.opt.max_effects) {
    std::vector<std::pair<const EffectSpec*, FitResult>> evals;
    for (const auto& id : a.candidates) {
      const EffectSpec* spec = a.spec_of(id);
      if (!spec || has(a.cur.terms, id)) continue;
      bool richer_present = false;
      for (const auto& t : a.cur.terms)
        richer_present = richer_present || (spec->conflicts(*t.spec) && complexity(*t.spec) > complexity(*spec));
      if (richer_present) continue;
      evals.emplace_back(spec, a.fit(with(a.cur.terms, spec)));
    }
    std::sort(evals.begin(), evals.end(), [](const auto& x, const auto& z) { return x.second.bic() < z.second.bic(); });
    prefer_physical(evals, bar);
    std::vector<std::pair<const EffectSpec*, FitResult>> passing;
    for (const auto& ev : evals)
      if (ev.second.bic() - a.cur.bic() < -bar) passing.push_back(ev);
    bool added = false;
    for (const auto& [spec, alt] : evals) {
      const std::string id = spec->id(), label = spec->label;
      const double dbic = alt.bic() - a.cur.bic();
      if (!(dbic < -bar)) {
        reject(*spec, label + ": BIC changes by " + formatted("%.1f", dbic) + " (needs < -" + formatted("%.0f", bar) + ")");
        continue;
      }
      if (const std::string why = implausible(a, *spec, alt); !why.empty()) {
        std::string beside;
        for (const auto& t : a.cur.terms) beside += (beside.empty() ? " (beside " : ", ") + t.spec->label;
        reject(*spec, label + ": " + why + (beside.empty() ? "" : beside + " in the model)"));
        continue;
      }
      const double h_cur = a.heldout(a.cur.terms), h_alt = a.heldout(alt.terms);
      if (const std::string rival = simpler_rival(a, *spec, alt, h_alt, passing); !rival.empty()) {
        reject(*spec, label + ": the simpler rival " + rival);
        continue;
      }
      if (!(h_alt < h_cur)) {
        reject(*spec, label + ": held-out RMS not improved (" + formatted("%.4g", h_cur) + " -> " + formatted("%.4g", h_alt) + ")");
        continue;
      }
      bool removes = false;
      std::string left;
      for (int i = 0; i < a.m; ++i) {
        // A physical candidate answers to every located signature with an effect (its column is the model's own).
        const bool points = triggers(a.sigs[i], id) || (is_model_effect(*spec) && !a.sigs[i].triggers.empty());
        if (!a.located[i] || !points || !a.significant(i, a.cur.terms)) continue;
        const double after = a.signature(i, alt.terms).p_adj;
        if (after >= a.opt.alpha_family) removes = true;
        else left = a.sigs[i].name + " (p " + formatted("%.2g", after) + ")";
      }
      if (!removes) {
        reject(*spec, label + ": " + (left.empty() ? "its signatures are already explained by other effects"
                                                   : "alone it leaves its signature " + left));
        continue;
      }
      // Against the current model (for a richer variant of a law: against the poorer one it replaces).
      int nl_extra = spec->n_nonlinear();
      for (const auto& t : a.cur.terms)
        if (spec->conflicts(*t.spec)) nl_extra -= t.spec->n_nonlinear();
      const auto [p, test] = a.effect_test(a.cur, alt, nl_extra);
      if (!(p <= a.opt.alpha_effect)) {
        reject(*spec, label + ": not significant against the estimated noise (" + test + " p = " + formatted("%.3g", p) + ")");
        continue;
      }
      a.accept(*spec, dbic, p, test);
      for (const auto& t : a.cur.terms)
        if (spec->conflicts(*t.spec)) a.accepted.erase(t.spec->id());
      a.cur = alt;
      added = true;
      progress("reconcile: accepted " + label + " (dBIC " + formatted("%.1f", dbic) + ", " + test + " p " + formatted("%.3g", p) + ")");
      break;
    }
    if (!added) break;
  }
}

/// Effects whose signatures overlap (a soft start, friction and play all bend the loop near zero torque; a law's
/// last slope and series compliance share the straight part) may each leave the others' signatures when added alone.
/// If located signatures remain after one-at-a-time selection, every effect the located signatures point to enters
/// at once (the richest variant of a law), fitted term by term from the current model and then each term's
/// nonlinear parameters searched again with the others in; the joint model is kept when it lowers BIC and the
/// held-out RMS at all (an effect may pay off only once prune() drops one it replaces). prune() then keeps only the
/// effects whose removal costs significantly.
void admit_jointly(Analysis& a) {
  std::vector<bool> open(a.m, false);
  bool any_open = false;
  for (int i = 0; i < a.m; ++i) any_open = (open[i] = a.located[i] && a.significant(i, a.cur.terms)) || any_open;
  if (!any_open) return;
  // Two joint sets: the effects the still-open signatures point to (the poorer variant of a law kept), and every
  // effect any located signature points to (the richest variant). The one with the lower BIC that passes is kept.
  auto joint_set = [&](const std::vector<bool>& from, bool richest) {
    std::vector<const EffectSpec*> add;
    for (const auto& spec : effect_catalog(a.e.kind())) {
      bool pointed = false;
      for (int i = 0; i < a.m; ++i) pointed = pointed || (from[i] && triggers(a.sigs[i], spec.id()));
      if (!pointed || has(a.cur.terms, spec.id())) continue;
      // A variant of this law in the model: the poorer set keeps it; the richest set upgrades a poorer one.
      bool skip = false;
      for (const auto& t : a.cur.terms)
        skip = skip || (spec.conflicts(*t.spec) && (!richest || complexity(*t.spec) >= complexity(spec)));
      if (skip) continue;
      // Variants in the list (the catalog lists the poorer first): keep the first, or replace it by the richer.
      const auto listed = std::find_if(add.begin(), add.end(), [&](const EffectSpec* x) { return spec.conflicts(*x); });
      if (listed == add.end()) add.push_back(&spec);
      else if (richest) *listed = &spec;
    }
    return add;
  };
  const double h_cur = a.heldout(a.cur.terms);
  FitResult best = a.cur;
  std::vector<const EffectSpec*> best_add;
  std::string best_names, failed;
  std::vector<std::vector<const EffectSpec*>> sets{joint_set(open, false), joint_set(a.located, true)};
  if (sets[1] == sets[0]) sets.pop_back();
  for (const auto& add : sets) {
    if (add.empty()) continue;
    FitResult joint = a.cur;
    std::string names;
    for (const EffectSpec* s : add) {
      joint = a.fit(with(joint.terms, s));
      names += (names.empty() ? "" : ", ") + s->label;
    }
    joint = a.refine(joint);
    const double dbic = joint.bic() - a.cur.bic();
    const double h_joint = a.heldout(joint.terms);
    // Any improvement admits the set: prune() then holds every effect of it to the full bar.
    if (!(dbic < 0.0) || !(h_joint < h_cur)) {
      failed = names + " (BIC " + formatted("%.1f", dbic) + ", held-out " + formatted("%.4g", h_cur) + " -> " + formatted("%.4g", h_joint) + ")";
      continue;
    }
    if (joint.bic() < best.bic()) {
      best = joint;
      best_add = add;
      best_names = names;
    }
  }
  if (best_add.empty()) {
    for (const auto& add : sets)
      for (const EffectSpec* s : add)
        if (!a.rejected.count(s->id()))
          a.rejected[s->id()] = s->label + ": admitted jointly, the model does not improve: " + failed;
    return;
  }
  progress("reconcile: admitted jointly " + best_names + " (dBIC " + formatted("%.1f", best.bic() - a.cur.bic()) + ")");
  for (const EffectSpec* s : best_add) a.accept(*s, best.bic() - a.cur.bic(), 1.0, "joint");
  a.cur = best;
}

/// Backward pruning: an effect stays only if removing it (or, for a law with variants, falling back to the poorer
/// variant) costs significantly: BIC up by more than min_delta_bic, a worse held-out RMS, and significant against
/// the noise. The cheapest removal that fails one of these goes first; repeat until every effect is needed.
void prune(Analysis& a) {
  const double bar = a.opt.min_delta_bic;
  for (bool changed = true; changed && !a.cur.terms.empty();) {
    changed = false;
    struct Removal {
      std::size_t term;
      FitResult reduced;
      double cost;
      std::string why;
    };
    std::vector<Removal> removable;
    const double h_cur = a.heldout(a.cur.terms);
    for (std::size_t i = 0; i < a.cur.terms.size(); ++i) {
      const EffectSpec& spec = *a.cur.terms[i].spec;
      if (std::find(a.held.begin(), a.held.end(), &spec) != a.held.end()) continue;  // held in: not weighed
      // Reductions: drop it; or replace it by a poorer exclusive variant.
      std::vector<std::pair<FitResult, int>> reductions{{a.fit(without(a.cur.terms, i), false), spec.n_nonlinear()}};
      for (const auto& v : effect_catalog(a.e.kind()))
        if (spec.conflicts(v) && complexity(v) < complexity(spec))
          reductions.emplace_back(a.fit(with(without(a.cur.terms, i), &v)), spec.n_nonlinear() - v.n_nonlinear());
      // A term whose fit cannot stand (friction elements that cancel) goes first, to its best reduction.
      if (const std::string bad = implausible(a, spec, a.cur); !bad.empty()) {
        const auto best = std::min_element(reductions.begin(), reductions.end(), [](const auto& x, const auto& z) {
          return x.first.bic() < z.first.bic();
        });
        removable.push_back({i, best->first, -INFINITY, bad});
        continue;
      }
      for (auto& [red, nl_extra] : reductions) {
        const double cost = red.bic() - a.cur.bic();
        std::string why;
        if (!(cost > bar)) {
          why = "BIC rises by only " + formatted("%.1f", cost);
        } else if (const double h_red = a.heldout(red.terms); !(h_cur < h_red)) {
          why = "held-out RMS " + formatted("%.4g", h_red) + " without it, " + formatted("%.4g", h_cur) + " with it";
        } else {
          // Test the term as the last one of the full model against the reduction.
          std::vector<Term> order = without(a.cur.terms, i);
          order.push_back(a.cur.terms[i]);
          FitResult full = a.cur;
          full.terms = order;
          const auto [p, test] = a.effect_test(red, full, nl_extra);
          if (!(p <= a.opt.alpha_effect)) why = "not significant against the estimated noise (" + test + " p = " + formatted("%.3g", p) + ")";
          else if (red.terms.size() < a.cur.terms.size()) {
            auto& rec = a.accepted[spec.id()];
            rec.name = spec.name;
            rec.physics = spec.physics;
            rec.delta_bic = -cost;
            rec.p_value = p;
            rec.test = test;
          }
        }
        if (!why.empty()) removable.push_back({i, red, cost, why});
      }
    }
    if (removable.empty()) break;
    const auto best = std::min_element(removable.begin(), removable.end(),
                                       [](const Removal& x, const Removal& z) { return x.cost < z.cost; });
    const EffectSpec& gone = *a.cur.terms[best->term].spec;
    const EffectSpec* variant = nullptr;  // the poorer variant that replaces it, if any
    for (const auto& t : best->reduced.terms)
      if (gone.conflicts(*t.spec)) variant = t.spec;
    a.rejected[gone.id()] = gone.label + ": " +
                            (std::isinf(best->cost) ? "as fitted " + best->why + "; " : std::string("pruned, ")) +
                            (variant ? "replacing it by " + variant->label : std::string("removing it")) +
                            (std::isinf(best->cost) ? "" : " costs nothing significant (" + best->why + ")");
    a.accepted.erase(gone.id());
    if (variant) a.accept(*variant, 0.0, 1.0, "pruned to");
    progress("reconcile: pruned " + gone.id() + " (" + best->why + ")");
    a.cur = best->reduced;
    changed = true;
  }
}

/// Parsimony once the model is complete: a complex term that entered because it also mimicked other effects'
/// signatures (a three-segment law bending like play and series compliance together) is replaced by its simpler
/// rivals -- one rival, or all the simpler effects that share a located signature with it -- when, with the other
/// effects in, it no longer beats them clearly (BIC and held-out) and no located signature that only it explains
/// needs it. The rivals then face prune() like every other effect. Returns whether the model changed.
bool prefer_simpler(Analysis& a) {
  for (std::size_t i = 0; i < a.cur.terms.size(); ++i) {
    const EffectSpec& cx = *a.cur.terms[i].spec;
    auto usable = [&](const EffectSpec& rv) {
      if (complexity(rv) >= complexity(cx) || !share_signature(a, rv, cx) || has(a.cur.terms, rv.id())) return false;
      if (rv.conflicts(cx)) return false;  // variants of one law: prune() weighed them
      for (const auto& t : a.cur.terms)
        if (rv.conflicts(*t.spec)) return false;
      return true;
    };
    std::vector<std::vector<const EffectSpec*>> rival_sets;
    std::vector<const EffectSpec*> all;
    std::pair<int, int> total{0, 0};
    for (const auto& rv : effect_catalog(a.e.kind())) {
      if (!usable(rv)) continue;
      rival_sets.push_back({&rv});
      bool clash = false;
      for (const EffectSpec* x : all) clash = clash || rv.conflicts(*x);
      if (clash) continue;
      all.push_back(&rv);
      total.first += rv.n_nonlinear();
      total.second += rv.n_linear;
    }
    if (all.size() > 1 && total < complexity(cx)) rival_sets.push_back(all);
    for (const auto& rivals : rival_sets) {
      FitResult sw = a.fit(without(a.cur.terms, i), false);
      std::string label;
      for (const EffectSpec* rv : rivals) {
        sw = a.fit(with(sw.terms, rv));
        label += (label.empty() ? "" : " + ") + rv->label;
      }
      const double dbic = a.cur.bic() - sw.bic();
      const double h_cx = a.heldout(a.cur.terms), h_rv = a.heldout(sw.terms);
      if (dbic < -a.opt.min_delta_bic && h_cx < h_rv) continue;  // the complex one is clearly better
      bool needed = false;
      for (int k = 0; k < a.m && !needed; ++k) {
        if (!a.located[k] || !triggers(a.sigs[k], cx.id())) continue;
        bool rival_points = false;
        for (const EffectSpec* rv : rivals) rival_points = rival_points || triggers(a.sigs[k], rv->id());
        if (!rival_points) needed = a.significant(k, sw.terms);
      }
      if (needed) continue;
      if (rivals.size() == 1) {
        // A single rival must stand on its own: significant against the model without it.
        const std::size_t last = sw.terms.size() - 1;
        const FitResult wo = a.fit(without(sw.terms, last), false);
        const auto [p, test] = a.effect_test(wo, sw, rivals[0]->n_nonlinear());
        if (!(p <= a.opt.alpha_effect) || !(sw.bic() - wo.bic() < -a.opt.min_delta_bic)) continue;
        a.accept(*rivals[0], sw.bic() - wo.bic(), p, test);
      } else {
        for (const EffectSpec* rv : rivals) a.accept(*rv, 0.0, 1.0, "swap");  // tested by prune()
      }
      a.rejected[cx.id()] = cx.label + ": with the other effects in, the simpler " + label +
                            " explains as much (BIC " + formatted("%.1f", dbic) + " vs it, held-out " + formatted("%.4g", h_rv) +
                            " -> " + formatted("%.4g", h_cx) + ")";
      a.accepted.erase(cx.id());
      progress("reconcile: replaced " + cx.id() + " by the simpler " + label);
      a.cur = a.refine(sw);
      return true;
    }
  }
  return false;
}

/// The model with term `i` moved last (the term a test or a bootstrap searches).
FitResult with_last(FitResult f, std::size_t i) {
  std::vector<Term> order = without(f.terms, i);
  order.push_back(f.terms[i]);
  f.terms = order;
  return f;
}

/// A law left with structure tries its richer variant before the analysis gives up: when a located signature that
/// points to a richer variant of a law in the model is still significant (a three-segment curve fitted with two
/// slopes leaves it bending, and the two-slope breakpoint sits between the true ones), the richer variant replaces
/// the poorer one if it leaves none of those signatures significant, does not worsen the held-out RMS and is
/// significant against the noise (its extra breakpoints tested as in selection). BIC is not held to min_delta_bic
/// here: the signature test has already found the structure the poorer law leaves. Returns whether the model changed.
bool retry_richer_law(Analysis& a) {
  for (std::size_t i = 0; i < a.cur.terms.size(); ++i) {
    const EffectSpec& poor = *a.cur.terms[i].spec;
    for (const auto& rich : effect_catalog(a.e.kind())) {
      if (!rich.conflicts(poor) || complexity(rich) <= complexity(poor)) continue;
      std::vector<int> open;
      for (int k = 0; k < a.m; ++k)
        if (a.located[k] && triggers(a.sigs[k], rich.id()) && a.significant(k, a.cur.terms)) open.push_back(k);
      if (open.empty()) continue;
      const std::vector<Term> tried = with(a.cur.terms, &rich);
      const FitResult alt = a.refine(a.fit(tried));
      std::string left;
      for (int k : open)
        if (a.significant(k, alt.terms)) left += (left.empty() ? "" : ", ") + a.sigs[k].name;
      const double h_cur = a.heldout(a.cur.terms), h_alt = a.heldout(alt.terms);
      std::string why;
      if (!left.empty()) why = "it leaves " + left;
      else if (!(h_alt <= h_cur)) why = "held-out RMS " + formatted("%.4g", h_cur) + " -> " + formatted("%.4g", h_alt);
      else if (const auto [p, test] = a.effect_test(a.cur, with_last(alt, alt.find(rich.name)),
                                                    rich.n_nonlinear() - poor.n_nonlinear());
               !(p <= a.opt.alpha_effect))
        why = "not significant against the estimated noise (" + test + " p = " + formatted("%.3g", p) + ")";
      else a.accept(rich, alt.bic() - a.cur.bic(), p, test);
      if (!why.empty()) {
        a.rejected[rich.id()] = rich.label + ": tried where " + poor.label + " leaves structure; " + why;
        continue;
      }
      a.rejected[poor.id()] = poor.label + ": leaves structure its richer variant " + rich.label + " explains";
      a.accepted.erase(poor.id());
      progress("reconcile: " + poor.id() + " leaves structure; replaced by " + rich.id());
      a.cur = alt;
      return true;
    }
  }
  return false;
}

/// Against a curve baseline (the model's whole drive: body, teeth, bearing, circular spline) series compliance and a
/// stiffness law answer one mismatch, the slope at high torque: the law's K's are of the whole drive, so its last
/// slope holds the series term. The data have decided which stays in prune(): the law only where falling back to
/// series compliance alone (the model's curve, uniformly softer) costs significantly, series compliance only where
/// removing it from the law (K3 the curve's end slope) does. When both stayed, the law is the one effect reported
/// and series compliance is listed as held in its last slope, not as a second effect (the stiffness counted once).
/// Against C_tau T (the flexspline body alone) series compliance is the rest of the drive and stays an effect.
void fold_series_into_law(const Analysis& a, Result& r) {
  const auto* t = std::get_if<TorsionExperiment>(&a.e.data);
  if (!t || !t->model.twist_rad || a.cur.find("stiffness_nonlinearity") < 0) return;
  const auto series = std::find_if(r.effects.begin(), r.effects.end(),
                                   [](const AcceptedEffect& x) { return x.name == "series_compliance"; });
  if (series == r.effects.end()) return;
  r.rejected.push_back({"series_compliance", "series_compliance: held in the last slope of stiffness_nonlinearity "
                                             "(the law replaces the model's torque-twist curve; compliance " +
                                                 formatted("%.4g", added_series_compliance(a.cur)) + " rad/(N*m))"});
  r.effects.erase(series);
}

/// The dynamics effects refitted on re-runs of the model: per term its headlines with intervals (empty for a term that
/// is not a model run), what the refit took, and the model re-run at the values with the other terms refitted.
struct RunRefit {
  std::vector<std::vector<Headline>> params;
  double discrepancy = 0.0;  // |run at the columns' estimate - the columns' prediction| / |run - baseline|
  int runs = 0;
  Vec prediction;            // the re-run + the linear part (n)
  double rms = 0.0, heldout_rms = 0.0;
  std::string failed;        // why the model could not be run at the columns' estimate ("" when it could)
  std::vector<std::string> unbounded;  // per term: its headlines the data do not bound ("a, b"; "" for none)
};

/// Dynamics effects are changes of the model read through columns from runs at the baseline (small steps, a table);
/// where the model answers them far from linearly (flanks that lose and regain contact, the rim coupled through the
/// FEM body) the columns' estimate is biased by the curvature, and no interval around it holds the truth. The terms
/// with a RunLaw are refitted together on re-runs of the model (rerun.hpp: Levenberg-Marquardt with forward
/// differences at each iterate, each step checked by a run), the nuisance and the other terms' columns fitted beside
/// them; their headlines are the refit's values and their intervals the delta method on its final Jacobian under the
/// calibrated noise. The held-out RMS: the same linearisation fitted on the training rows. nullopt: no such term.
std::optional<RunRefit> refit_runs(const Analysis& a) {
  const auto* d = std::get_if<DynamicsExperiment>(&a.e.data);
  if (!d) return std::nullopt;
  const FitResult& f = a.cur;
  std::vector<int> offset(f.terms.size(), -1);
  std::vector<std::size_t> owner;  // the term each stacked parameter belongs to
  std::vector<double> lo, hi, start;
  Mat linear = nuisance_columns(a.e);
  Vec columns_prediction = Vec::Zero(a.e.n);  // the run terms' columns times their coefficients
  for (std::size_t i = 0; i < f.terms.size(); ++i) {
    const Term& t = f.terms[i];
    const Mat cols = t.spec->columns(a.e, t.theta);
    if (!t.spec->run_law) {
      linear = hcat(linear, cols);
      continue;
    }
    const RunLaw& law = *t.spec->run_law;
    offset[i] = static_cast<int>(start.size());
    const Vec p0 = law.start(a.e, f, static_cast<int>(i));
    for (int k = 0; k < p0.size(); ++k) {
      lo.push_back(law.lo[k]);
      hi.push_back(law.hi[k]);
      start.push_back(p0[k]);
      owner.push_back(i);
    }
    columns_prediction += cols * t.beta;
  }
  if (start.empty()) return std::nullopt;
  const auto segment = [&](const Vec& p, std::size_t i) {
    return Vec(p.segment(offset[i], f.terms[i].spec->run_law->lo.size()));
  };
  RerunProblem p{a.e, a.ar};
  p.lo = Eigen::Map<Vec>(lo.data(), lo.size());
  p.hi = Eigen::Map<Vec>(hi.data(), hi.size());
  p.response = [&](const Vec& values) {
    DynamicsVariation v;
    for (std::size_t i = 0; i < f.terms.size(); ++i)
      if (offset[i] >= 0) f.terms[i].spec->run_law->vary(a.e, segment(values, i), v);
    const DynamicsRun run = d->model.dynamics_run(v);
    return resample(run.time_s, run.mesh_force_N, a.e.time);
  };
  p.step = [&](const Vec& values, int k) {
    const std::size_t i = owner[k];
    return f.terms[i].spec->run_law->step(a.e, segment(values, i), k - offset[i]);
  };
  p.linear = linear;
  // Forward differences: a run of the coupled model takes seconds. Converged at 5 % of a difference step (a few
  // tenths of a per cent of the value) or a tenth of the value's standard error, whichever is smaller.
  p.forward = true;
  p.converged = 0.05;
  p.max_iterations = 6;
  p.max_step_in_steps = 10.0;
  RunRefit out;
  out.params.resize(f.terms.size());
  out.unbounded.resize(f.terms.size());
  const auto listed = [](const Vec& values) {
    std::string s;
    for (double v : values) s += (s.empty() ? "" : ", ") + formatted("%.4g", v);
    return "(" + s + ")";
  };
  progress("reconcile: refitting the dynamics effects on re-runs of the model from " +
           listed(Eigen::Map<Vec>(start.data(), start.size())));
  RerunFit fit;
  try {
    fit = refit_on_reruns(p, Eigen::Map<Vec>(start.data(), start.size()));
  } catch (const InputError& err) {
    out.failed = err.what();
    return out;
  }
  const Vec start_change = fit.start_response - a.e.baseline;
  out.discrepancy = start_change.norm() > 0.0 ? (start_change - columns_prediction).norm() / start_change.norm() : 0.0;
  out.runs = fit.runs;
  out.prediction = fit.response + linear * fit.linear_beta;
  out.rms = rms(Vec(a.e.measured - out.prediction));
  {  // held out: the refit's linearisation at the values, fitted on the training rows
    const Mat X = hcat(fit.jacobian, linear);
    const LsResult ls = least_squares(whiten(a.ar, Mat(X.topRows(a.train))),
                                      whiten(a.ar, Vec((a.e.measured - fit.response).head(a.train))));
    out.heldout_rms = rms(Vec((a.e.measured - fit.response - X * ls.beta).tail(a.e.n - a.train)));
  }
  // Headlines and their gradients in the values (the change of the response linearised at the values); the
  // half-widths of all of them from one projection of the Jacobian.
  const Vec change = fit.response - a.e.baseline;
  // The headlines that get an interval with their terms, in the order of the gradients' columns.
  std::vector<std::pair<std::size_t, Headline*>> spread;
  Mat G(fit.values.size(), 0);
  for (std::size_t i = 0; i < f.terms.size(); ++i) {
    if (offset[i] < 0) continue;
    const EffectSpec& spec = *f.terms[i].spec;
    const RunLaw& law = *spec.run_law;
    auto headline_at = [&](const Vec& values) {
      return law.headline(a.e, segment(values, i), Vec(change + fit.jacobian * (values - fit.values)));
    };
    const NamedValues base = headline_at(fit.values);
    std::vector<Headline>& h = out.params[i];
    for (const auto& [name, v] : base)
      h.push_back({name, v, v, v, spec.held ? spec.held(a.e, f, static_cast<int>(i), name) : ""});
    Mat g = Mat::Zero(fit.values.size(), static_cast<Eigen::Index>(base.size()));
    for (int k = offset[i]; k < offset[i] + law.lo.size(); ++k) {
      const double dk = 1e-4 * p.step(fit.values, k);
      Vec up = fit.values, down = fit.values;
      up[k] += dk;
      down[k] -= dk;
      const NamedValues hu = headline_at(up), hd = headline_at(down);
      for (std::size_t q = 0; q < base.size(); ++q) g(k, q) = (hu[q].second - hd[q].second) / (2.0 * dk);
    }
    for (std::size_t q = 0; q < base.size(); ++q) {
      if (h[q].fixed()) continue;
      spread.emplace_back(i, &h[q]);
      G = hcat(G, Mat(g.col(q)));
    }
  }
  // Each interval within what its headline can be over the parameters' bounds (a drag's parts are not negative); a
  // headline along a direction the data do not see is bounded by them alone, and the effect says so.
  const Vec halves = rerun_half_widths(p, fit, G, a.cal);
  for (std::size_t q = 0; q < spread.size(); ++q) {
    Headline& h = *spread[q].second;
    const auto [can_lo, can_hi] = range_within_bounds(p.lo, p.hi, fit.values, h.value, Vec(G.col(q)));
    h.lo = std::max(h.value - halves[q], can_lo);
    h.hi = std::min(h.value + halves[q], can_hi);
    std::string& unbounded = out.unbounded[spread[q].first];
    if (std::isinf(halves[q])) unbounded += (unbounded.empty() ? "" : ", ") + h.name;
  }
  progress("reconcile: dynamics effects refitted on " + std::to_string(fit.runs) + " re-runs of the model (" +
           std::to_string(fit.iterations) + " iterations) to " + listed(fit.values) + ", RMS " + formatted("%.4g", out.rms));
  return out;
}

/// Final fit with covariance, headlines with intervals, the signatures still left, the verdict.
void finalise(Analysis& a, Result& r) {
  FitOptions o;
  o.multistart_last = false;
  o.covariance = true;
  a.cur = fit_model(a.e, a.y, a.cur.terms, a.ar, o);
  const std::optional<RunRefit> rerun = refit_runs(a);
  for (std::size_t i = 0; i < a.cur.terms.size(); ++i) {
    const EffectSpec& spec = *a.cur.terms[i].spec;
    const int term = static_cast<int>(i);
    AcceptedEffect x = a.accepted[spec.id()];
    if (rerun && !rerun->params[i].empty()) {
      x.params = rerun->params[i];
      x.model_discrepancy = rerun->discrepancy;
      x.model_runs = rerun->runs;
    } else {
      x.params = headline_with_ci(a.e, a.cur, term, {&a.cal, &a.y, &a.ar});
    }
    if (spec.meaning) x.meaning = spec.meaning(a.e, a.cur, term);
    if (rerun && !rerun->failed.empty() && spec.run_law)
      x.meaning = "the model could not be re-run at the fitted values (" + rerun->failed +
                  "): the values are read from the columns of the baseline's runs, whose linearisation they may "
                  "outgrow";
    const std::string unbounded = rerun ? rerun->unbounded[i] : "";
    if (!unbounded.empty())
      x.meaning += std::string(x.meaning.empty() ? "" : "; ") + "the recording does not tell " + unbounded +
                   " apart from the other values (the model answers only a combination of them): the interval is "
                   "what the value can be at all";
    r.effects.push_back(x);
  }
  if (rerun && rerun->failed.empty()) {
    r.refitted = true;
    r.refit_rms = rerun->rms;
    r.refit_heldout_rms = rerun->heldout_rms;
    r.refit_prediction = rerun->prediction;
  }
  fold_series_into_law(a, r);
  for (const auto& [id, reason] : a.rejected)
    if (!has(a.cur.terms, id)) r.rejected.push_back({id.substr(0, id.find('#')), reason});
  r.final_model = a.cur;
  r.residual_after = a.y - a.cur.contribution;
  r.final_prediction = a.e.baseline + a.cur.contribution;
  r.final_rms = rms(r.residual_after);
  r.final_heldout_rms = a.heldout(a.cur.terms);
  r.catalog = catalog_figures(a.e, a.cur);
  // A signature left after the complete model (a time drift included) is reported only if it survives that model.
  for (int i = 0; i < a.m; ++i) {
    const SigTest t = a.signature(i, a.cur.terms);
    if (t.p_adj < a.opt.alpha_family) r.unexplained.push_back(make_location(a.e, a.sigs[i], t));
  }
  // A located signature that no effect can explain (a time drift) stands only if the complete model leaves it too.
  r.locations.erase(std::remove_if(r.locations.begin(), r.locations.end(),
                                   [&](const Location& l) {
                                     for (const auto& s : a.sigs)
                                       if (s.name == l.signature && !s.triggers.empty()) return false;
                                     for (const auto& u : r.unexplained)
                                       if (u.signature == l.signature) return false;
                                     return true;
                                   }),
                    r.locations.end());
  r.significant = !r.locations.empty();
  if (r.effects.empty() && !r.significant && r.unexplained.empty()) r.verdict = "no_significant_mismatch";
  else if (!r.effects.empty() && r.unexplained.empty()) r.verdict = "explained";
  else r.verdict = "partly_explained";
  r.significant = r.significant || !r.effects.empty() || !r.unexplained.empty();
}

}  // namespace


Result reconcile(const Experiment& e, const Options& opt, const std::vector<EffectSpec>* physical,
                 const std::vector<const EffectSpec*>& held) {
  Stopwatch clock;
  Result r;
  r.kind = e.kind();
  r.samples = e.n;
  r.baseline_model = e.baseline_model;
  r.baseline_source = e.baseline_source;
  Analysis a(e, opt, physical, held);
  r.heldout_rows = e.n - a.train;
  fit_noise(a, r);
  fit_baseline(a, r);
  locate(a, r);
  admit_one_at_a_time(a);
  a.cur = a.refine(a.cur);
  admit_jointly(a);
  prune(a);
  for (int round = 0; round < 3 && prefer_simpler(a); ++round) prune(a);
  retry_richer_law(a);
  finalise(a, r);
  r.seconds = clock.lap();
  return r;
}

}  // namespace sw::reconcile
