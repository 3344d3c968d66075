#include "reconcile/fit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include <unsupported/Eigen/LevenbergMarquardt>
#include <unsupported/Eigen/NumericalDiff>

namespace sw::reconcile {

using Vec = Eigen::VectorXd;
using Mat = Eigen::MatrixXd;

std::vector<double> start_grid(double lo, double hi, int count) {
  std::vector<double> g(count);
  const bool log_spaced = lo > 0.0 && hi / lo > 20.0;
  for (int i = 0; i < count; ++i) {
    const double f = (i + 0.5) / count;
    g[i] = log_spaced ? lo * std::pow(hi / lo, f) : lo + (hi - lo) * f;
  }
  return g;
}

namespace {

/// Design matrix (all rows) for given thetas.
Mat design(const Experiment& e, const std::vector<Term>& terms, const std::vector<Vec>& thetas) {
  Mat X = nuisance_columns(e);
  for (std::size_t i = 0; i < terms.size(); ++i) X = hcat(X, terms[i].spec->columns(e, thetas[i]));
  return X;
}

struct Problem {
  const Experiment& e;
  const std::vector<Term>& terms;
  const ArModel& ar;
  int rows;
  Vec yw;                              // whitened y over the rows
  std::vector<std::pair<int, int>> slot;  // (term, theta index) per free nonlinear parameter
  Vec lo, hi;

  std::vector<Vec> thetas_from(const Vec& theta_free) const {
    std::vector<Vec> th;
    for (const auto& t : terms) th.push_back(t.theta);
    for (std::size_t s = 0; s < slot.size(); ++s) th[slot[s].first][slot[s].second] = theta_free[s];
    return th;
  }
  LsResult solve(const Vec& theta_free) const {
    const Mat X = design(e, terms, thetas_from(theta_free)).topRows(rows);
    return least_squares(whiten(ar, X), yw);
  }
  Vec theta_of(const Vec& u) const {
    Vec th(u.size());
    for (int i = 0; i < u.size(); ++i) th[i] = lo[i] + (hi[i] - lo[i]) / (1.0 + std::exp(-u[i]));
    return th;
  }
  Vec u_of(const Vec& th) const {
    Vec u(th.size());
    for (int i = 0; i < th.size(); ++i) {
      const double f = std::clamp((th[i] - lo[i]) / (hi[i] - lo[i]), 1e-6, 1.0 - 1e-6);
      u[i] = std::log(f / (1.0 - f));
    }
    return u;
  }
};

struct LmFunctor : Eigen::DenseFunctor<double> {
  const Problem* p;
  LmFunctor(const Problem* problem, int inputs, int values) : DenseFunctor<double>(inputs, values), p(problem) {}
  int operator()(const InputType& u, ValueType& f) const {
    f = p->solve(p->theta_of(u)).residual;
    return 0;
  }
};

}  // namespace

Mat design_matrix(const Experiment& e, const std::vector<Term>& terms) {
  std::vector<Vec> th;
  for (const auto& t : terms) th.push_back(t.theta);
  return design(e, terms, th);
}

Vec model_contribution(const Experiment& e, const FitResult& m) {
  std::vector<Vec> th;
  Vec beta = m.nuisance_beta;
  for (const auto& t : m.terms) {
    th.push_back(t.theta);
    Vec b(beta.size() + t.beta.size());
    b << beta, t.beta;
    beta = b;
  }
  const Mat X = design(e, m.terms, th);
  return X.cols() ? Vec(X * beta) : Vec(Vec::Zero(e.n));
}

namespace {

/// The problem of fitting `terms` to the first `rows` rows of y: each term's theta at its start (the middle of its
/// bounds when it has none yet) and the bounds of every free nonlinear parameter.
Problem make_problem(const Experiment& e, const Vec& y, std::vector<Term>& terms, const ArModel& ar, int rows) {
  Problem prob{e, terms, ar, rows, whiten(ar, Vec(y.head(rows))), {}, {}, {}};
  std::vector<double> lo, hi;
  for (std::size_t i = 0; i < terms.size(); ++i) {
    auto& t = terms[i];
    if (t.theta.size() != t.spec->n_nonlinear()) {
      const auto [l, h] = t.spec->bounds(e);
      t.theta = 0.5 * (l + h);
    }
    if (t.spec->n_nonlinear() == 0) continue;
    const auto [l, h] = t.spec->bounds(e);
    for (int j = 0; j < t.spec->n_nonlinear(); ++j) {
      prob.slot.emplace_back(static_cast<int>(i), j);
      lo.push_back(l[j]);
      hi.push_back(h[j]);
    }
  }
  prob.lo = Eigen::Map<Vec>(lo.data(), lo.size());
  prob.hi = Eigen::Map<Vec>(hi.data(), hi.size());
  return prob;
}

/// Starts of the search: the given thetas, or (multistart_last) the best points of a grid over the last term's
/// nonlinear parameters (16 points; for two, 20 x 20, or its upper triangle when they share one range and enter
/// symmetrically): breakpoint pairs have several local minima at high signal-to-noise. The best `starts` (+2 for two)
/// are polished by LM.
std::vector<Vec> search_starts(const Problem& prob, const Vec& theta_free, const FitOptions& opt) {
  const Term& last = prob.terms.back();
  const int nl = last.spec->n_nonlinear();
  if (!opt.multistart_last || (nl != 1 && nl != 2)) return {theta_free};
  const int nfree = static_cast<int>(theta_free.size());
  const auto [l, h] = last.spec->bounds(prob.e);
  std::vector<std::pair<double, Vec>> scored;
  const std::vector<double> g0 = start_grid(l[0], h[0], nl == 1 ? 16 : 20);
  const std::vector<double> g1 = nl == 2 ? start_grid(l[1], h[1], 20) : std::vector<double>{0.0};
  const bool symmetric = nl == 2 && l[0] == l[1] && h[0] == h[1];
  for (std::size_t i = 0; i < g0.size(); ++i)
    for (std::size_t j = symmetric ? i + 1 : 0; j < g1.size(); ++j) {
      Vec th = theta_free;
      th[nfree - nl] = g0[i];
      if (nl == 2) th[nfree - 1] = g1[j];
      scored.emplace_back(prob.solve(th).rss, th);
    }
  std::sort(scored.begin(), scored.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<Vec> starts;
  const int keep = opt.starts + (nl == 2 && opt.starts > 1 ? 2 : 0);
  for (int s = 0; s < std::min<int>(keep, scored.size()); ++s) starts.push_back(scored[s].second);
  return starts;
}

/// The best free thetas reached by Levenberg-Marquardt from each start (or the start itself, when LM made it worse).
Vec polish(const Problem& prob, const std::vector<Vec>& starts, Vec best_theta) {
  const int nfree = static_cast<int>(prob.slot.size());
  double best_rss = std::numeric_limits<double>::infinity();
  for (const Vec& s : starts) {
    LmFunctor functor(&prob, nfree, static_cast<int>(prob.yw.size()));
    // Central differences with a step of 1e-4 in the logistic variable: the variable projection re-solves a nearly
    // collinear least-squares problem at each point, and the default step (1e-8) drowns in its round-off.
    Eigen::NumericalDiff<LmFunctor, Eigen::Central> nd(functor, 1e-8);
    Eigen::LevenbergMarquardt<Eigen::NumericalDiff<LmFunctor, Eigen::Central>> lm(nd);
    lm.setMaxfev(60 * (nfree + 1));
    Vec u = prob.u_of(s);
    lm.minimize(u);
    const Vec th = prob.theta_of(u);
    const double rss = prob.solve(th).rss;
    const double rss_start = prob.solve(s).rss;
    if (rss < best_rss) { best_rss = rss; best_theta = th; }
    if (rss_start < best_rss) { best_rss = rss_start; best_theta = s; }
  }
  return best_theta;
}

/// The fitted model at the free thetas: every term's theta and beta, the whitened RSS and the parameter count.
FitResult fitted_model(const Problem& prob, std::vector<Term> terms, const Vec& theta) {
  const auto thetas = prob.thetas_from(theta);
  for (std::size_t i = 0; i < terms.size(); ++i) terms[i].theta = thetas[i];
  const LsResult ls = prob.solve(theta);
  FitResult out;
  const int nn = static_cast<int>(nuisance_columns(prob.e).cols());
  out.nuisance_beta = ls.beta.head(nn);
  int c = nn;
  for (auto& t : terms) {
    t.beta = ls.beta.segment(c, t.spec->n_linear);
    c += t.spec->n_linear;
  }
  out.terms = terms;
  out.rss_w = ls.rss;
  out.n_w = static_cast<int>(prob.yw.size());
  out.k = ls.rank + static_cast<int>(theta.size());
  out.contribution = model_contribution(prob.e, out);
  return out;
}

/// The central-difference step of parameter j of params(): relative to its value, for a theta to its bound width.
double covariance_step(const Experiment& e, const FitResult& f, const Vec& p0, int j) {
  double h = 1e-6 * std::max(std::abs(p0[j]), 1e-12);
  int idx = static_cast<int>(f.nuisance_beta.size());
  for (std::size_t ti = 0; ti < f.terms.size(); ++ti) {
    idx += f.terms[ti].spec->n_linear;
    for (int q = 0; q < f.terms[ti].spec->n_nonlinear(); ++q, ++idx)
      if (idx == j) {
        const auto [l, hh] = f.terms[ti].spec->bounds(e);
        h = 1e-4 * (hh[q] - l[q]);
      }
  }
  return h;
}

/// Covariance of params() (whitened Gauss-Newton, s^2 (J^T J)^+) from the Jacobian of the whitened prediction of the
/// first `rows` rows (central differences).
Mat parameter_covariance(const Experiment& e, FitResult& out, const ArModel& ar, int rows) {
  const Vec p0 = out.params();
  Mat J(out.n_w, p0.size());
  for (int j = 0; j < p0.size(); ++j) {
    FitResult a = out, b = out;
    Vec pa = p0, pb = p0;
    const double h = covariance_step(e, out, p0, j);
    pa[j] += h;
    pb[j] -= h;
    a.set_params(pa);
    b.set_params(pb);
    J.col(j) = whiten(ar, Vec((model_contribution(e, a) - model_contribution(e, b)).head(rows))) / (2.0 * h);
  }
  out.jac_w = J;
  const double s2 = out.rss_w / std::max(1, out.n_w - out.k);
  const Mat JtJ = J.transpose() * J;
  // Scale for conditioning, then pseudo-inverse.
  Vec d = JtJ.diagonal().cwiseMax(1e-300).cwiseSqrt();
  const Mat S = d.cwiseInverse().asDiagonal() * JtJ * d.cwiseInverse().asDiagonal();
  Eigen::CompleteOrthogonalDecomposition<Mat> cod(S);
  cod.setThreshold(1e-12);
  return s2 * d.cwiseInverse().asDiagonal() * Mat(cod.pseudoInverse()) * d.cwiseInverse().asDiagonal();
}

}  // namespace

FitResult fit_model(const Experiment& e, const Vec& y, std::vector<Term> terms, const ArModel& ar,
                    const FitOptions& opt) {
  const int rows = opt.rows < 0 ? e.n : opt.rows;
  const Problem prob = make_problem(e, y, terms, ar, rows);
  const int nfree = static_cast<int>(prob.slot.size());
  Vec theta_free(nfree);
  for (int s = 0; s < nfree; ++s) theta_free[s] = terms[prob.slot[s].first].theta[prob.slot[s].second];
  const Vec best_theta = nfree > 0 ? polish(prob, search_starts(prob, theta_free, opt), theta_free) : theta_free;
  FitResult out = fitted_model(prob, terms, best_theta);
  if (opt.covariance && out.params().size() > 0) out.cov = parameter_covariance(e, out, ar, rows);
  return out;
}

namespace {

/// Whitened RSS of the model with term `term`'s nonlinear parameter q fixed at `value` and every other free nonlinear
/// parameter re-fitted from its fitted value (the profile), over all rows.
double profile_rss(const Experiment& e, const IntervalNoise& noise, const FitResult& model, int term, int q,
                   double value) {
  std::vector<Term> terms = model.terms;
  terms[term].theta[q] = value;
  Problem prob = make_problem(e, *noise.y, terms, *noise.ar, e.n);
  Vec start(static_cast<int>(prob.slot.size()) - 1), lo(start.size()), hi(start.size());
  std::vector<std::pair<int, int>> slots;
  for (std::size_t k = 0; k < prob.slot.size(); ++k) {
    if (prob.slot[k] == std::pair{term, q}) continue;
    lo[slots.size()] = prob.lo[k];
    hi[slots.size()] = prob.hi[k];
    start[slots.size()] = terms[prob.slot[k].first].theta[prob.slot[k].second];
    slots.push_back(prob.slot[k]);
  }
  prob.slot = slots;
  prob.lo = lo;
  prob.hi = hi;
  const Vec best = start.size() > 0 ? polish(prob, {start}, start) : start;
  return prob.solve(best).rss;
}

/// The profile interval of nonlinear parameter q of term `term`: the values whose profile RSS exceeds the fitted one
/// by at most `delta_rss` (stepping out from the fit, then bisecting), within the parameter's bounds.
std::pair<double, double> profile_interval(const Experiment& e, const IntervalNoise& noise, const FitResult& model,
                                           int term, int q, double delta_rss, double first_step) {
  const double at = model.terms[term].theta[q];
  const auto [lo, hi] = model.terms[term].spec->bounds(e);
  const double bound[2] = {lo[q], hi[q]};
  double ends[2];
  for (int side = 0; side < 2; ++side) {
    double inside = at, step = std::max(first_step, 1e-6 * (hi[q] - lo[q])), outside = NAN;
    while (std::isnan(outside)) {
      const double v = side == 0 ? std::max(bound[0], inside - step) : std::min(bound[1], inside + step);
      if (profile_rss(e, noise, model, term, q, v) - model.rss_w > delta_rss) outside = v;
      else if (v == bound[side]) break;
      else inside = v, step *= 2.0;
    }
    if (std::isnan(outside)) {
      ends[side] = bound[side];
      continue;
    }
    for (int it = 0; it < 30; ++it) {
      const double mid = 0.5 * (inside + outside);
      (profile_rss(e, noise, model, term, q, mid) - model.rss_w > delta_rss ? outside : inside) = mid;
    }
    ends[side] = 0.5 * (inside + outside);
  }
  return {ends[0], ends[1]};
}

}  // namespace

std::vector<Headline> headline_with_ci(const Experiment& e, const FitResult& model, int term,
                                       const IntervalNoise& noise) {
  const NamedValues base = model.terms[term].spec->headline(e, model, term);
  std::vector<Headline> out;
  const EffectSpec& spec = *model.terms[term].spec;
  for (const auto& [name, v] : base) out.push_back({name, v, v, v, spec.held ? spec.held(e, model, term, name) : ""});
  if (model.cov.size() == 0) return out;
  const double s2 = model.rss_w / std::max(1, model.n_w - model.k);
  const Vec p0 = model.params();
  Mat G(base.size(), p0.size());
  for (int j = 0; j < p0.size(); ++j) {
    const double h = 1e-6 * std::max(std::abs(p0[j]), 1e-12);
    FitResult a = model, b = model;
    Vec pa = p0, pb = p0;
    pa[j] += h;
    pb[j] -= h;
    a.set_params(pa);
    b.set_params(pb);
    const NamedValues va = a.terms[term].spec->headline(e, a, term);
    const NamedValues vb = b.terms[term].spec->headline(e, b, term);
    for (std::size_t i = 0; i < base.size(); ++i) G(i, j) = (va[i].second - vb[i].second) / (2.0 * h);
  }
  for (std::size_t i = 0; i < base.size(); ++i) {
    if (base[i].first == "order" || out[i].fixed()) continue;
    const double wald = G.row(i) * model.cov * G.row(i).transpose();
    // The headline is g^T p = v^T r_w + const with v = J (J^T J)^+ g (the fit's influence on it): its variance at the
    // noise level the calibration measured where v's energy lies, with Student's t at that level's degrees of freedom.
    // A slow headline (an offset, a level per torque) is where the AR model's level is low and the Wald interval
    // (s^2 g^T (J^T J)^+ g) too narrow.
    const bool calibrated = noise.cal && noise.cal->valid() && model.jac_w.rows() == noise.cal->n && s2 > 0.0;
    const double half =
        calibrated ? calibrated_half_width_95(*noise.cal, model.jac_w * (model.cov * G.row(i).transpose() / s2))
                   : 1.959964 * std::sqrt(std::max(wald, 0.0));
    out[i].lo = base[i].second - half;
    out[i].hi = base[i].second + half;
    // A headline that is a nonlinear parameter itself (a breakpoint, a transition torque) is where the linearisation
    // is poorest (a breakpoint the data barely locate): its interval is also the profile's, at the RSS rise that
    // gives the half-width above for a quadratic profile, s^2 half^2 / (g^T cov g), and the wider of the two stands.
    // Where the linearisation gives no width (a parameter on its bound, two elements that coincide) the profile
    // alone stands, at Wald's RSS rise s^2 1.96^2.
    if (!noise.y || !noise.ar) continue;
    const bool linearised = wald > 0.0 && half > 0.0;
    const double delta_rss = linearised ? s2 * half * half / wald : s2 * 1.959964 * 1.959964;
    for (int q = 0; q < spec.n_nonlinear(); ++q) {
      if (model.terms[term].theta[q] != base[i].second) continue;
      const auto [lo, hi] = spec.bounds(e);
      // On an end of its search range (a dead band sharper than the smallest transition searched) the parameter's
      // linearisation is no interval, whatever width it gives: the profile alone stands (at the RSS rise the
      // calibrated level gives).
      const double at = base[i].second, tol = 1e-9 * (hi[q] - lo[q]);
      const bool at_lo = at <= lo[q] + tol, at_hi = at >= hi[q] - tol, at_bound = at_lo || at_hi;
      const double first_step = linearised && !at_bound ? 0.5 * half : 1e-3 * (hi[q] - lo[q]);
      const auto [plo, phi] = profile_interval(e, noise, model, term, q, delta_rss, first_step);
      out[i].lo = at_bound ? plo : std::min(out[i].lo, plo);
      out[i].hi = at_bound ? phi : std::max(out[i].hi, phi);
      // A parameter searched over non-negative values is a scale that cannot be negative (a breakpoint, a transition
      // torque): its interval stops at zero, as the re-run refit's stop at what a headline can be (rerun.hpp); on the
      // lower end of its search, nothing in the data bounds it from below, and its interval reaches zero; on the
      // upper end, nothing bounds it from above.
      if (lo[q] >= 0.0) out[i].lo = at_lo ? 0.0 : std::max(out[i].lo, 0.0);
      if (at_hi) out[i].hi = INFINITY;
      break;
    }
  }
  return out;
}

}  // namespace sw::reconcile
