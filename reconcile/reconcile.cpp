#include "reconcile/reconcile.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>

#include "common/progress.hpp"
#include "reconcile/catalog.hpp"

namespace sw::reconcile {

using Vec = Eigen::VectorXd;
using Mat = Eigen::MatrixXd;

namespace {

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

double rms(const Vec& v) { return v.size() ? std::sqrt(v.squaredNorm() / v.size()) : 0.0; }

struct SigTest {
  double p_adj = 1.0;
  Vec contribution;  // fitted basis contribution (n)
};

SigTest test_signature(const Experiment& e, const SignatureSpec& s, const Vec& y, const std::vector<Term>& terms,
                       const ArModel& ar, const SpectralCalibration& cal, int m) {
  const Mat base = hcat(design_matrix(e, terms), s.condition(e));
  const Mat B = s.basis(e);
  const Vec yw = whiten(ar, y);
  const FTest t = calibrated_f_test(cal, whiten(ar, base), whiten(ar, B), yw);
  SigTest out;
  out.p_adj = std::min(1.0, t.p_value * m);
  const Mat full = hcat(base, B);
  const LsResult ls = least_squares(whiten(ar, full), yw);
  out.contribution = B * ls.beta.tail(B.cols());
  return out;
}

Location make_location(const Experiment& e, const SignatureSpec& s, const SigTest& t) {
  Location loc;
  loc.signature = s.name;
  loc.domain = s.domain;
  loc.p_value = t.p_adj;
  const Vec& c = t.contribution;
  const double amp = c.cwiseAbs().maxCoeff();
  std::string d = s.what;
  if (s.periodic) {
    d += "; amplitude " + fmt("%.3g", amp) + " " + e.response_unit;
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
    d += "; strongest for " + s.domain + " in [" + fmt("%.4g", lo) + ", " + fmt("%.4g", hi) + "] " + s.where_unit +
         ", up to " + fmt("%.3g", amp) + " " + e.response_unit;
  }
  loc.description = d;
  return loc;
}

const EffectSpec* effect_by_id(Kind kind, const std::string& id) {
  for (const auto& s : effect_catalog(kind))
    if (s.id() == id) return &s;
  return nullptr;
}

std::vector<Term> with(std::vector<Term> terms, const EffectSpec* spec) {
  terms.push_back(Term{spec, Vec(0), Vec(0)});
  return terms;
}

/// RMS over the held-out rows of y - model fitted on the training rows (thetas start at the given terms').
double heldout_rms(const Experiment& e, const Vec& y, const std::vector<Term>& terms, const ArModel& ar, int train,
                   bool multistart) {
  FitOptions o;
  o.rows = train;
  o.multistart_last = multistart;
  const FitResult f = fit_model(e, y, terms, ar, o);
  return rms(Vec((y - f.contribution).tail(e.n - train)));
}

/// Parametric bootstrap of the likelihood-ratio statistic for adding `spec` to `cur` (noise: the AR model).
double bootstrap_p(const Experiment& e, const FitResult& cur, const FitResult& alt, const ArModel& ar,
                   const Options& opt, std::uint64_t salt) {
  const double observed = cur.n_w * std::log(cur.rss_w / alt.rss_w);
  std::mt19937_64 rng(opt.seed * 0x9E3779B97F4A7C15ULL + salt);
  int exceed = 0;
  const int B = opt.bootstrap;
  for (int b = 0; b < B; ++b) {
    const Vec ystar = cur.contribution + simulate_ar(ar, e.n, rng);
    FitOptions o0;
    o0.multistart_last = false;
    const FitResult f0 = fit_model(e, ystar, cur.terms, ar, o0);
    const FitResult f1 = fit_model(e, ystar, with(cur.terms, alt.terms.back().spec), ar);
    const double stat = f0.n_w * std::log(f0.rss_w / f1.rss_w);
    if (stat >= observed) ++exceed;
    // Early stop: once the p-value cannot reach alpha any more.
    if ((1.0 + exceed) / (B + 1.0) > opt.alpha_effect) return (1.0 + exceed) / (b + 2.0);
  }
  return (1.0 + exceed) / (B + 1.0);
}

/// Complexity for parsimony between rivals: nonlinear parameters first, then linear ones.
std::pair<int, int> complexity(const EffectSpec& s) { return {s.n_nonlinear(), s.n_linear}; }

/// Do both effects appear among the triggers of one located signature?
bool share_signature(const std::vector<SignatureSpec>& sigs, const std::vector<bool>& located, const EffectSpec& a,
                     const EffectSpec& b) {
  for (std::size_t i = 0; i < sigs.size(); ++i) {
    if (!located[i]) continue;
    const auto& t = sigs[i].triggers;
    if (std::find(t.begin(), t.end(), a.id()) != t.end() && std::find(t.begin(), t.end(), b.id()) != t.end())
      return true;
  }
  return false;
}

std::string effect_label(const EffectSpec& s) {
  return s.order ? s.name + " (order " + std::to_string(s.order) + ")" : s.name;
}

}  // namespace

int signature_count(Kind kind) { return static_cast<int>(signature_catalog(kind).size()); }

Result reconcile(const Experiment& e, const Options& opt) {
  Stopwatch clock;
  Result r;
  r.kind = e.kind;
  r.samples = e.n;
  const Vec y = e.residual();
  const int hold = std::max(1, static_cast<int>(std::lround(e.n * opt.heldout_fraction)));
  const int train = e.n - hold;
  r.heldout_rows = hold;
  const auto& sigs = signature_catalog(e.kind);
  const int m = static_cast<int>(sigs.size());

  // Noise model: AR fitted to the residual of a rich model (nuisance + every signature basis), so that structure the
  // signatures can explain does not inflate the noise estimate.
  {
    Mat rich = nuisance_columns(e);
    for (const auto& s : sigs) rich = hcat(hcat(rich, s.basis(e)), s.condition(e));
    r.noise = fit_ar(least_squares(rich, y).residual, opt.ar_max_order);
    if (opt.spectral_half_width > 0) {
      const Mat rich_w = whiten(r.noise, rich);
      r.calibration = spectral_calibration(rich_w, least_squares(rich_w, whiten(r.noise, y)).residual,
                                           opt.spectral_half_width);
    }
  }
  const ArModel& ar = r.noise;
  const SpectralCalibration& cal = r.calibration;
  progress("reconcile: " + kind_name(e.kind) + ", " + std::to_string(e.n) + " samples, noise AR(" +
           std::to_string(ar.order()) + ") sd " + fmt("%.3g", ar.process_sd));

  FitResult cur = fit_model(e, y, {}, ar);
  r.residual_before = y - cur.contribution;
  r.baseline_prediction = e.baseline + cur.contribution;
  r.baseline_rms = rms(r.residual_before);
  r.baseline_heldout_rms = heldout_rms(e, y, {}, ar, train, false);

  // Locate.
  std::set<std::string> candidates;
  std::vector<bool> located(m, false);
  for (int i = 0; i < m; ++i) {
    const SigTest t = test_signature(e, sigs[i], y, cur.terms, ar, cal, m);
    if (t.p_adj < opt.alpha_family) {
      located[i] = true;
      r.locations.push_back(make_location(e, sigs[i], t));
      for (const auto& id : sigs[i].triggers) candidates.insert(id);
    }
  }
  r.significant = !r.locations.empty();
  progress("reconcile: located " + std::to_string(r.locations.size()) + " significant signatures, " +
           std::to_string(candidates.size()) + " candidate effects");

  // Forward selection with backward pruning.
  std::map<std::string, std::string> rejected;  // id -> reason
  std::map<std::string, AcceptedEffect> accepted_info;
  std::uint64_t salt = 0;
  while (static_cast<int>(cur.terms.size()) < opt.max_effects) {
    struct Eval {
      const EffectSpec* spec;
      FitResult alt;
      double dbic;
    };
    std::vector<Eval> evals;
    for (const auto& id : candidates) {
      if (cur.find(id.substr(0, id.find('#'))) >= 0) {
        bool same = false;
        for (const auto& t : cur.terms) same = same || t.spec->id() == id;
        if (same) continue;
      }
      const EffectSpec* spec = effect_by_id(e.kind, id);
      if (!spec) continue;
      FitResult alt = fit_model(e, y, with(cur.terms, spec), ar);
      evals.push_back({spec, alt, alt.bic() - cur.bic()});
    }
    std::sort(evals.begin(), evals.end(), [](const Eval& a, const Eval& b) { return a.dbic < b.dbic; });
    bool added = false;
    for (auto& ev : evals) {
      const std::string id = ev.spec->id();
      const std::string label = effect_label(*ev.spec);
      if (!(ev.dbic < -opt.min_delta_bic)) {
        rejected[id] = label + ": BIC changes by " + fmt("%.1f", ev.dbic) + " (needs < -" +
                       fmt("%.0f", opt.min_delta_bic) + ")";
        continue;
      }
      const double h_cur = heldout_rms(e, y, cur.terms, ar, train, false);
      const double h_alt = heldout_rms(e, y, ev.alt.terms, ar, train, false);
      // Parsimony between rivals of one signature: a more complex effect (e.g. the soft start's breakpoint) that
      // would pass on its own must also beat each simpler rival that passes the BIC bar (e.g. plain series
      // compliance) clearly, by BIC and on the held-out block; otherwise the simpler one is named.
      std::string simpler;
      for (const auto& rv : evals) {
        if (&rv == &ev || !(rv.dbic < -opt.min_delta_bic)) continue;
        if (complexity(*rv.spec) >= complexity(*ev.spec) || !share_signature(sigs, located, *rv.spec, *ev.spec))
          continue;
        const double dbic_rv = ev.alt.bic() - rv.alt.bic();
        const double h_rv = heldout_rms(e, y, rv.alt.terms, ar, train, false);
        // ... unless the complex one removes a located signature that only it (not the simpler one) explains.
        bool needed = false;
        for (int i = 0; i < m && !needed; ++i) {
          const auto& t = sigs[i].triggers;
          if (!located[i] || std::find(t.begin(), t.end(), id) == t.end() ||
              std::find(t.begin(), t.end(), rv.spec->id()) != t.end())
            continue;
          needed = test_signature(e, sigs[i], y, rv.alt.terms, ar, cal, m).p_adj < opt.alpha_family &&
                   test_signature(e, sigs[i], y, ev.alt.terms, ar, cal, m).p_adj >= opt.alpha_family;
        }
        if (!needed && (!(dbic_rv < -opt.min_delta_bic) || !(h_alt < h_rv))) {
          simpler = effect_label(*rv.spec) + " explains as much (BIC " + fmt("%.1f", dbic_rv) + " vs it, held-out " +
                    fmt("%.4g", h_rv) + " -> " + fmt("%.4g", h_alt) + ")";
          break;
        }
      }
      if (!simpler.empty()) {
        rejected[id] = label + ": the simpler rival " + simpler;
        continue;
      }
      if (!(h_alt < h_cur)) {
        rejected[id] = label + ": held-out RMS not improved (" + fmt("%.4g", h_cur) + " -> " + fmt("%.4g", h_alt) + ")";
        continue;
      }
      // It must remove a signature that pointed to it and is still significant under the current model.
      bool removes = false;
      std::string left;
      for (int i = 0; i < m; ++i) {
        if (!located[i]) continue;
        if (std::find(sigs[i].triggers.begin(), sigs[i].triggers.end(), id) == sigs[i].triggers.end()) continue;
        const double before = test_signature(e, sigs[i], y, cur.terms, ar, cal, m).p_adj;
        if (!(before < opt.alpha_family)) continue;
        const double after = test_signature(e, sigs[i], y, ev.alt.terms, ar, cal, m).p_adj;
        if (after >= opt.alpha_family) removes = true;
        else left = sigs[i].name + " (p " + fmt("%.2g", after) + ")";
      }
      if (!removes) {
        rejected[id] = label + ": " + (left.empty() ? "its signatures are already explained by other effects"
                                                    : "leaves its signature " + left);
        continue;
      }
      double p = 1.0;
      std::string test;
      if (ev.spec->n_nonlinear() == 0) {
        const Mat X0 = design_matrix(e, cur.terms);
        const FTest ft =
            calibrated_f_test(cal, whiten(ar, X0), whiten(ar, Mat(ev.spec->columns(e, Vec(0)))), whiten(ar, y));
        p = std::min(1.0, ft.p_value * ev.spec->multiplicity);
        test = "F";
      } else {
        p = bootstrap_p(e, cur, ev.alt, ar, opt, ++salt);
        test = "bootstrap";
      }
      if (!(p <= opt.alpha_effect)) {
        rejected[id] = label + ": not significant against the estimated noise (" + test + " p = " + fmt("%.3g", p) + ")";
        continue;
      }
      AcceptedEffect a;
      a.name = ev.spec->name;
      a.physics = ev.spec->physics;
      a.delta_bic = ev.dbic;
      a.p_value = p;
      a.test = test;
      accepted_info[id] = a;
      rejected.erase(id);
      cur = ev.alt;
      added = true;
      progress("reconcile: accepted " + label + " (dBIC " + fmt("%.1f", ev.dbic) + ", " + test + " p " +
               fmt("%.3g", p) + ")");
      break;
    }
    if (!added) break;
    // Backward: drop any earlier term the others have made redundant.
    for (bool pruned = true; pruned && cur.terms.size() > 1;) {
      pruned = false;
      for (std::size_t i = 0; i + 1 < cur.terms.size(); ++i) {
        std::vector<Term> reduced = cur.terms;
        reduced.erase(reduced.begin() + i);
        FitOptions o;
        o.multistart_last = false;
        const FitResult red = fit_model(e, y, reduced, ar, o);
        const double dbic = cur.bic() - red.bic();
        if (!(dbic < -opt.min_delta_bic)) {
          const std::string id = cur.terms[i].spec->id();
          rejected[id] = effect_label(*cur.terms[i].spec) + ": pruned, redundant once " +
                         effect_label(*cur.terms.back().spec) + " is in the model (BIC " + fmt("%.1f", dbic) + ")";
          accepted_info.erase(id);
          cur = red;
          pruned = true;
          progress("reconcile: pruned " + id);
          break;
        }
      }
    }
  }

  // Parsimony again once the model is complete: a complex term that entered because it also mimicked another
  // effect's signature (the soft start bending like unmodelled hysteresis) is replaced by its simpler rival when,
  // with the other effects in, it no longer beats it clearly (BIC > min_delta_bic and held-out) and no located
  // signature that only it explains needs it.
  for (std::size_t i = 0; i < cur.terms.size(); ++i) {
    const EffectSpec& cx = *cur.terms[i].spec;
    for (const auto& rv : effect_catalog(e.kind)) {
      if (complexity(rv) >= complexity(cx) || !share_signature(sigs, located, rv, cx)) continue;
      bool present = false;
      for (const auto& t : cur.terms) present = present || t.spec->id() == rv.id();
      if (present) continue;
      std::vector<Term> swapped = cur.terms;
      swapped[i] = Term{&rv, Vec(0), Vec(0)};
      FitOptions o;
      o.multistart_last = false;
      const FitResult sw = fit_model(e, y, swapped, ar, o);
      const double dbic = cur.bic() - sw.bic();
      const double h_cx = heldout_rms(e, y, cur.terms, ar, train, false);
      const double h_rv = heldout_rms(e, y, sw.terms, ar, train, false);
      if (dbic < -opt.min_delta_bic && h_cx < h_rv) continue;  // the complex one is clearly better
      bool needed = false;
      for (int k = 0; k < m && !needed; ++k) {
        const auto& t = sigs[k].triggers;
        if (!located[k] || std::find(t.begin(), t.end(), cx.id()) == t.end() ||
            std::find(t.begin(), t.end(), rv.id()) != t.end())
          continue;
        needed = test_signature(e, sigs[k], y, sw.terms, ar, cal, m).p_adj < opt.alpha_family;
      }
      if (needed) continue;
      // The simpler one must stand on its own: significant against the model without it.
      std::vector<Term> without = sw.terms;
      without.erase(without.begin() + i);
      const FitResult wo = fit_model(e, y, without, ar, o);
      double p = 1.0;
      if (rv.n_nonlinear() == 0) {
        const FTest ft = calibrated_f_test(cal, whiten(ar, design_matrix(e, without)),
                                           whiten(ar, Mat(rv.columns(e, Vec(0)))), whiten(ar, y));
        p = std::min(1.0, ft.p_value * rv.multiplicity);
      }
      if (!(p <= opt.alpha_effect) || !(sw.bic() - wo.bic() < -opt.min_delta_bic)) continue;
      const std::string cx_id = cx.id();
      rejected[cx_id] = effect_label(cx) + ": with the other effects in, the simpler rival " + effect_label(rv) +
                        " explains as much (BIC " + fmt("%.1f", dbic) + " vs it, held-out " + fmt("%.4g", h_rv) +
                        " -> " + fmt("%.4g", h_cx) + ")";
      accepted_info.erase(cx_id);
      AcceptedEffect a;
      a.name = rv.name;
      a.physics = rv.physics;
      a.delta_bic = sw.bic() - wo.bic();
      a.p_value = p;
      a.test = "F";
      accepted_info[rv.id()] = a;
      rejected.erase(rv.id());
      progress("reconcile: replaced " + cx_id + " by its simpler rival " + rv.id());
      cur = sw;
      break;
    }
  }

  // Final fit with covariance, headlines with intervals.
  {
    FitOptions o;
    o.multistart_last = false;
    o.covariance = true;
    cur = fit_model(e, y, cur.terms, ar, o);
  }
  for (std::size_t i = 0; i < cur.terms.size(); ++i) {
    AcceptedEffect a = accepted_info[cur.terms[i].spec->id()];
    a.params = headline_with_ci(e, cur, static_cast<int>(i));
    r.effects.push_back(a);
  }
  for (const auto& [id, reason] : rejected) r.rejected.push_back({id.substr(0, id.find('#')), reason});
  r.final_model = cur;
  r.residual_after = y - cur.contribution;
  r.final_prediction = e.baseline + cur.contribution;
  r.final_rms = rms(r.residual_after);
  r.final_heldout_rms = heldout_rms(e, y, cur.terms, ar, train, false);

  for (int i = 0; i < m; ++i) {
    const SigTest t = test_signature(e, sigs[i], y, cur.terms, ar, cal, m);
    if (t.p_adj < opt.alpha_family) r.unexplained.push_back(make_location(e, sigs[i], t));
  }
  if (r.effects.empty() && !r.significant && r.unexplained.empty()) r.verdict = "no_significant_mismatch";
  else if (!r.effects.empty() && r.unexplained.empty()) r.verdict = "explained";
  else r.verdict = "partly_explained";
  r.significant = r.significant || !r.effects.empty() || !r.unexplained.empty();
  r.seconds = clock.lap();
  return r;
}

}  // namespace sw::reconcile
