#include "contact/frictional_contact.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include "common/error.hpp"
#include "common/format.hpp"

namespace sw {
namespace {

// ---- The bounded problem: min ½xᵀHx + cᵀx subject to aᵀx = t, lo ≤ x ≤ hi ------------------------------------

/// The symmetric matrix H = [[A, Bᵀ], [B, D]] (n × n blocks) read in place: the blocks stay the caller's, a step
/// touches the entries of its contacts only.
struct BlockMatrix {
  const Eigen::MatrixXd *A, *B, *D;
  Eigen::Index size() const { return 2 * A->rows(); }
  double operator()(Eigen::Index i, Eigen::Index j) const {
    const Eigen::Index n = A->rows();
    if (i < n) return j < n ? (*A)(i, j) : (*B)(j - n, i);
    return j < n ? (*B)(i - n, j) : (*D)(i - n, j - n);
  }
  double max_diagonal() const { return std::max(A->diagonal().maxCoeff(), D->diagonal().maxCoeff()); }
  /// H·x for an x with few nonzeros (the closed contacts' forces, the bounds held away from zero): the columns of the
  /// nonzeros only.
  Eigen::VectorXd times(const Eigen::VectorXd& x) const {
    const Eigen::Index n = A->rows();
    Eigen::VectorXd y = Eigen::VectorXd::Zero(2 * n);
    for (Eigen::Index j = 0; j < n; ++j)
      if (x[j] != 0) y.head(n) += x[j] * A->col(j), y.tail(n) += x[j] * B->col(j);
    for (Eigen::Index j = 0; j < n; ++j)
      if (x[n + j] != 0) y.head(n) += x[n + j] * B->row(j).transpose(), y.tail(n) += x[n + j] * D->col(j);
    return y;
  }
};

/// Where a variable stands: free, or held at its lower or upper bound (lo = hi: fixed, held at its lower).
enum class Bound : signed char { Free, Lower, Upper };

/// H symmetric positive definite; lo_j ≤ hi_j (±∞ allowed).
struct BoundedQp {
  BlockMatrix H;
  Eigen::VectorXd c, a, lo, hi;
  double t = 0;
  double gradient_tol = 0;  ///< a held variable whose gradient points into the box by more than this is freed
};

/// A feasible iterate (within the bounds, aᵀx = t), where each variable stands, and the multiplier ψ of its solve.
struct QpIterate {
  Eigen::VectorXd x;
  std::vector<Bound> where;
  double psi = 0;
  /// The free variables, ascending.
  std::vector<Eigen::Index> free() const {
    std::vector<Eigen::Index> F;
    for (std::size_t j = 0; j < where.size(); ++j)
      if (where[j] == Bound::Free) F.push_back(static_cast<Eigen::Index>(j));
    return F;
  }
};

struct FreeOptimum {
  Eigen::VectorXd z;
  double psi = 0;
};

/// The optimum over the free variables F with the others held at x: H_FF·z − ψ·a_F = −(c_F + H_FB·x_B),
/// a_Fᵀz = t − a_Bᵀx_B, by the Schur complement on ψ (solve_contact's algebra: with x_B = 0 its
/// numbers to round-off).
/// Not finite when no free variable carries the equality.
FreeOptimum optimum_on(const BoundedQp& qp, const std::vector<Eigen::Index>& F, const Eigen::VectorXd& x) {
  Eigen::VectorXd held = x;
  for (Eigen::Index j : F) held[j] = 0;
  const Eigen::VectorXd pull = qp.H.times(held);
  const auto n = static_cast<Eigen::Index>(F.size());
  Eigen::MatrixXd M(n, n);
  Eigen::VectorXd r(n), l(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    r[i] = qp.c[F[i]] + pull[F[i]];
    l[i] = qp.a[F[i]];
    for (Eigen::Index k = 0; k < n; ++k) M(i, k) = qp.H(F[i], F[k]);
  }
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(M);
  const Eigen::VectorXd Ar = ldlt.solve(r), Al = ldlt.solve(l);
  FreeOptimum o;
  o.psi = (qp.t - qp.a.dot(held) + l.dot(Ar)) / l.dot(Al);
  o.z = o.psi * Al - Ar;
  return o;
}

/// Moves the free variables toward their optimum, holding each one the move would carry past a bound at that bound,
/// until the optimum lies within the bounds (Lawson–Hanson's inner loop, two-sided). False when the variable `freed`
/// last (from bound `left`) cannot leave it after all (round-off): it is held again and the iterate, unchanged, stands.
bool settle_free_set(const BoundedQp& qp, QpIterate& s, Eigen::Index freed, Bound left) {
  for (bool first = true;; first = false) {
    const std::vector<Eigen::Index> F = s.free();
    const FreeOptimum o = optimum_on(qp, F, s.x);
    if (!(o.z.allFinite() && std::isfinite(o.psi)))
      throw std::runtime_error("frictional contact: no free variable carries the torque (degenerate active set)");
    if (first && freed >= 0) {
      const double z = o.z[std::find(F.begin(), F.end(), freed) - F.begin()];
      if (left == Bound::Lower ? z <= qp.lo[freed] : z >= qp.hi[freed]) {
        s.where[freed] = left;
        return false;
      }
    }
    s.psi = o.psi;
    double alpha = 1.0;
    std::size_t blocking = F.size();
    for (std::size_t r = 0; r < F.size(); ++r) {
      const Eigen::Index j = F[r];
      const double target = o.z[r] < qp.lo[j] ? qp.lo[j] : o.z[r] > qp.hi[j] ? qp.hi[j] : o.z[r];
      if (target == o.z[r]) continue;
      const double step = std::clamp((target - s.x[j]) / (o.z[r] - s.x[j]), 0.0, 1.0);
      if (step < alpha) alpha = step, blocking = r;
    }
    for (std::size_t r = 0; r < F.size(); ++r) s.x[F[r]] += alpha * (o.z[r] - s.x[F[r]]);
    if (blocking == F.size()) return true;
    // The blocking variable is held exactly at its bound; any other the move left past one (round-off) too.
    for (std::size_t r = 0; r < F.size(); ++r) {
      const Eigen::Index j = F[r];
      if (r == blocking ? o.z[r] < qp.lo[j] : s.x[j] <= qp.lo[j]) s.x[j] = qp.lo[j], s.where[j] = Bound::Lower;
      else if (r == blocking || s.x[j] >= qp.hi[j]) s.x[j] = qp.hi[j], s.where[j] = Bound::Upper;
    }
  }
}

/// The held variable whose gradient g points into its box by the most (beyond the tolerance), −1 when none.
Eigen::Index most_violating(const BoundedQp& qp, const std::vector<Bound>& where, const Eigen::VectorXd& g) {
  Eigen::Index worst = -1;
  double worst_v = qp.gradient_tol;
  for (Eigen::Index j = 0; j < g.size(); ++j) {
    const double v = where[j] == Bound::Lower && qp.lo[j] < qp.hi[j] ? -g[j] : where[j] == Bound::Upper ? g[j] : 0.0;
    if (v > worst_v) worst_v = v, worst = j;
  }
  return worst;
}

/// Solves the bounded problem from the feasible iterate `s` (primal active set: Lawson–Hanson's outer loop frees the
/// most violating held variable, two-sided as BVLS).
QpIterate solve_bounded_qp(const BoundedQp& qp, QpIterate s) {
  Eigen::Index freed = -1;
  Bound left = Bound::Lower;
  for (Eigen::Index outer = 0; outer < 6 * qp.c.size() + 20; ++outer) {
    const bool stalled = !settle_free_set(qp, s, freed, left);
    const Eigen::VectorXd g = qp.H.times(s.x) + qp.c - s.psi * qp.a;
    freed = stalled ? -1 : most_violating(qp, s.where, g);
    if (freed < 0) return s;
    left = s.where[freed];
    s.where[freed] = Bound::Free;
  }
  throw std::runtime_error("frictional contact: the active-set iteration did not converge");
}

/// How many times a warm start may hold the free variables that leave their bounds and solve again.
constexpr int kWarmRepairs = 8;

/// A feasible start near `where` (a nearby problem's sets): holds the variables where it says and solves for the free
/// ones; a free variable whose optimum leaves its bounds is held at the bound it crosses and the free ones are solved
/// again (at most kWarmRepairs times). Nothing when no such start is found.
std::optional<QpIterate> start_from(const BoundedQp& qp, std::vector<Bound> where) {
  QpIterate s{Eigen::VectorXd::Zero(qp.c.size()), std::move(where)};
  for (int repair = 0; repair <= kWarmRepairs; ++repair) {
    for (Eigen::Index j = 0; j < s.x.size(); ++j) {
      if (qp.lo[j] == qp.hi[j]) s.where[j] = Bound::Lower;
      s.x[j] = s.where[j] == Bound::Lower ? qp.lo[j] : s.where[j] == Bound::Upper ? qp.hi[j] : 0.0;
    }
    const std::vector<Eigen::Index> F = s.free();
    if (F.empty()) return std::nullopt;
    const FreeOptimum o = optimum_on(qp, F, s.x);
    if (!(o.z.allFinite() && std::isfinite(o.psi))) return std::nullopt;
    bool inside = true;
    for (std::size_t r = 0; r < F.size(); ++r) {
      if (o.z[r] <= qp.lo[F[r]]) s.where[F[r]] = Bound::Lower, inside = false;
      if (o.z[r] >= qp.hi[F[r]]) s.where[F[r]] = Bound::Upper, inside = false;
    }
    if (inside) {
      for (std::size_t r = 0; r < F.size(); ++r) s.x[F[r]] = o.z[r];
      s.psi = o.psi;
      return s;
    }
  }
  return std::nullopt;
}

// ---- The frictional step: x = [p; q] --------------------------------------------------------------------------

constexpr int kMaxPasses = 200;
/// The fixed point b = μ∘p is reached when a pass moves the slip bound by less than this fraction of its largest.
constexpr double kFixedPointTol = 1e-13;
/// Round-off of the conditions, relative to the step's scales of displacement and force.
constexpr double kRoundOff = 1e-12;

void check_problem(const FrictionalContactProblem& p) {
  const Eigen::Index n = p.q.size();
  if (p.A.rows() != n || p.A.cols() != n || p.lambda.size() != n || p.A_tn.rows() != n || p.A_tn.cols() != n ||
      p.A_tt.rows() != n || p.A_tt.cols() != n || p.lambda_t.size() != n || p.friction_coefficient.size() != n)
    throw std::invalid_argument("frictional contact: the blocks, gaps, arms and friction coefficients differ in size");
  for (Eigen::Index i = 0; i < n; ++i)
    if (!(p.friction_coefficient[i] >= 0 && std::isfinite(p.friction_coefficient[i])))
      throw InputError("contact: friction_coefficient = " + six_digits(p.friction_coefficient[i]) + " at contact " +
                       std::to_string(i) + "; must be a finite number >= 0");
}

/// The step's bounded problem: H the block compliance, c = [q0; −s_prev] (the gradient is then [g; Δs]),
/// a = [λ; λt], t = T; p ≥ 0, the slip bound set per pass.
BoundedQp step_problem(const FrictionalContactProblem& p, double T, const Eigen::VectorXd& slip_prev) {
  const Eigen::Index n = p.q.size();
  BoundedQp qp;
  qp.H = {&p.A, &p.A_tn, &p.A_tt};
  qp.c.resize(2 * n);
  qp.c << p.q, -slip_prev;
  qp.a.resize(2 * n);
  qp.a << p.lambda, p.lambda_t;
  qp.t = T;
  qp.lo = Eigen::VectorXd::Zero(2 * n);
  qp.hi = Eigen::VectorXd::Constant(2 * n, std::numeric_limits<double>::infinity());
  const double displacement = std::max(qp.c.cwiseAbs().maxCoeff(),
                                       std::abs(T) * qp.H.max_diagonal() / qp.a.cwiseAbs().maxCoeff());
  qp.gradient_tol = kRoundOff * std::max(displacement, 1e-300);
  return qp;
}

void set_slip_bound(BoundedQp& qp, const Eigen::VectorXd& b) {
  const Eigen::Index n = b.size();
  qp.lo.tail(n) = -b;
  qp.hi.tail(n) = b;
}

/// Where the variables start from the previous step's states: closed contacts free, sticking ones' q free, slipping
/// ones' q held at the bound of its sign.
std::vector<Bound> bounds_of(const FrictionalStep& s) {
  const auto n = static_cast<std::size_t>(s.state.size());
  std::vector<Bound> where(2 * n, Bound::Lower);
  for (std::size_t i = 0; i < n; ++i) {
    if (s.state[i] == ContactState::Open) continue;
    where[i] = Bound::Free;
    where[n + i] = s.state[i] == ContactState::Stick  ? Bound::Free
                   : s.tangential_force_N[i] > 0      ? Bound::Upper
                                                      : Bound::Lower;
  }
  return where;
}

/// Cold start: the whole torque on the contact that closes first in T's direction, no tangential force.
QpIterate cold_start(const FrictionalContactProblem& p, const BoundedQp& qp) {
  const Eigen::Index n = p.q.size();
  Eigen::Index first = -1;
  double first_turn = std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < n; ++i) {
    const double turn = p.q[i] / std::abs(p.lambda[i]);
    if (p.lambda[i] * qp.t > 0 && turn < first_turn) first_turn = turn, first = i;
  }
  if (first < 0)
    throw InputError("contact: no tooth flank can carry a torque of " + six_digits(qp.t) +
                     " N·m (no flank pair closes in that direction)");
  QpIterate s{Eigen::VectorXd::Zero(2 * n), std::vector<Bound>(2 * n, Bound::Lower)};
  for (Eigen::Index i = 0; i < n; ++i)
    if (qp.lo[n + i] < qp.hi[n + i]) s.where[n + i] = Bound::Free;
  s.x[first] = qp.t / p.lambda[first];
  s.where[first] = Bound::Free;
  return s;
}

/// Contact sets: the state of each contact and, on slipping ones, the sign of q = sense·μ·p (0 where μ = 0).
struct ContactSets {
  std::vector<ContactState> state;
  Eigen::VectorXd sense;
};

/// The sets of a Tresca solution. A contact that closed under a zero slip bound (open at the pass's start) slips
/// against its slip increment, or sticks where that is zero.
ContactSets sets_of(const FrictionalContactProblem& p, const BoundedQp& qp, const QpIterate& it) {
  const Eigen::Index n = p.q.size();
  const Eigen::VectorXd slip_increment = (qp.H.times(it.x) + qp.c - it.psi * qp.a).tail(n);
  ContactSets sets{std::vector<ContactState>(n, ContactState::Open), Eigen::VectorXd::Zero(n)};
  for (Eigen::Index i = 0; i < n; ++i) {
    if (it.where[i] != Bound::Free) continue;
    const Bound w = it.where[n + i];
    const bool fixed = qp.lo[n + i] == qp.hi[n + i], frictionless = p.friction_coefficient[i] == 0;
    const double ds = slip_increment[i];
    sets.state[i] = ContactState::Slip;
    if (w == Bound::Free || (fixed && !frictionless && ds == 0))
      sets.state[i] = ContactState::Stick;
    else if (!fixed)
      sets.sense[i] = w == Bound::Upper ? 1.0 : -1.0;
    else if (!frictionless)
      sets.sense[i] = -std::copysign(1.0, ds);
  }
  return sets;
}

struct Candidate {
  Eigen::VectorXd x;
  double psi = 0;
};

/// Coulomb's conditions as equations on the sets: closed gaps zero, sticking slip increments zero, equilibrium.
/// Unknowns: the closed contacts' p (a slipping one's q = sense·μ·p rides on it), the sticking ones' q, and ψ.
Candidate coulomb_on_sets(const FrictionalContactProblem& p, const BoundedQp& qp, const ContactSets& sets) {
  const Eigen::Index n = p.q.size();
  std::vector<Eigen::Index> var;  // the unknowns' variables in x = [p; q]
  std::vector<double> rider;      // q/p of the unknown's contact where q rides on p
  for (Eigen::Index i = 0; i < n; ++i)
    if (sets.state[i] != ContactState::Open) {
      var.push_back(i);
      rider.push_back(sets.sense[i] * p.friction_coefficient[i]);
    }
  for (Eigen::Index i = 0; i < n; ++i)
    if (sets.state[i] == ContactState::Stick) {
      var.push_back(n + i);
      rider.push_back(0.0);
    }
  const auto m = static_cast<Eigen::Index>(var.size());
  // A row's entries (at(j): its j-th) per unit of unknown k.
  const auto per_unit = [&](const auto& at, Eigen::Index k) {
    return at(var[k]) + (rider[k] != 0 ? rider[k] * at(n + var[k]) : 0.0);
  };
  Eigen::MatrixXd M(m + 1, m + 1);
  Eigen::VectorXd rhs(m + 1);
  for (Eigen::Index r = 0; r < m; ++r) {
    const auto row = [&](Eigen::Index j) { return qp.H(var[r], j); };
    for (Eigen::Index k = 0; k < m; ++k) M(r, k) = per_unit(row, k);
    M(r, m) = -qp.a[var[r]];
    rhs[r] = -qp.c[var[r]];
  }
  const auto arm = [&](Eigen::Index j) { return qp.a[j]; };
  for (Eigen::Index k = 0; k < m; ++k) M(m, k) = per_unit(arm, k);
  M(m, m) = 0;
  rhs[m] = qp.t;
  const Eigen::VectorXd y = M.partialPivLu().solve(rhs);
  Candidate c{Eigen::VectorXd::Zero(2 * n), y[m]};
  for (Eigen::Index k = 0; k < m; ++k) c.x[var[k]] = y[k];
  for (Eigen::Index k = 0; k < m; ++k)
    if (rider[k] != 0) c.x[n + var[k]] = rider[k] * y[k];
  return c;
}

/// Whether a candidate meets every condition of Coulomb's problem on its sets, to round-off.
bool satisfies_coulomb(const FrictionalContactProblem& p, const BoundedQp& qp, const ContactSets& sets,
                       const Candidate& c) {
  if (!(c.x.allFinite() && std::isfinite(c.psi))) return false;
  const Eigen::Index n = p.q.size();
  const Eigen::VectorXd g = qp.H.times(c.x) + qp.c - c.psi * qp.a;  // [gap; slip increment]
  const double force_tol =
      kRoundOff * std::max(c.x.cwiseAbs().maxCoeff(), std::abs(qp.t) / qp.a.cwiseAbs().maxCoeff());
  for (Eigen::Index i = 0; i < n; ++i) {
    const double pn = c.x[i], qt = c.x[n + i], mu = p.friction_coefficient[i];
    const bool ok = sets.state[i] == ContactState::Open  ? g[i] >= -qp.gradient_tol
                    : sets.state[i] == ContactState::Stick ? pn >= 0 && std::abs(qt) <= mu * pn + force_tol
                                                           : pn >= 0 && sets.sense[i] * g[n + i] <= qp.gradient_tol;
    if (!ok) return false;
  }
  return true;
}

/// The step's state from the solution x = [p; q], ψ on its sets; round-off cleaned where the conditions are
/// equalities (closed gaps zero, sticking slips unchanged).
FrictionalStep step_state(const FrictionalContactProblem& p, const BoundedQp& qp, const FrictionalStep& prev,
                          const Candidate& c, const ContactSets& sets) {
  const Eigen::Index n = p.q.size();
  const Eigen::VectorXd g = qp.H.times(c.x) + qp.c - c.psi * qp.a;
  FrictionalStep s;
  s.torque_Nm = qp.t;
  s.twist_rad = c.psi;
  s.normal_force_N = c.x.head(n);
  s.tangential_force_N = c.x.tail(n);
  s.gap_m = g.head(n);
  s.slip_m = prev.slip_m + g.tail(n);
  s.state = sets.state;
  for (Eigen::Index i = 0; i < n; ++i) {
    if (s.state[i] != ContactState::Open) s.gap_m[i] = 0;
    if (s.state[i] == ContactState::Stick) s.slip_m[i] = prev.slip_m[i];
    s.friction_work_J += std::abs(s.tangential_force_N[i]) * std::abs(s.slip_m[i] - prev.slip_m[i]);
  }
  return s;
}

/// How far the state at a cycle's top moved from the one before's: the slips (what a step starts from: its solution
/// depends on the previous state's slips and the torque alone) over the largest, and the twist.
double top_state_change(const FrictionalStep& before, const FrictionalStep& after) {
  const double slips = (after.slip_m - before.slip_m).cwiseAbs().maxCoeff() /
                       std::max(after.slip_m.cwiseAbs().maxCoeff(), std::numeric_limits<double>::min());
  return std::max(slips, std::abs(after.twist_rad - before.twist_rad) / std::abs(after.twist_rad));
}

}  // namespace

int FrictionalStep::count(ContactState s) const { return static_cast<int>(std::count(state.begin(), state.end(), s)); }

FrictionalStep unloaded_state(const FrictionalContactProblem& p) {
  const Eigen::Index n = p.q.size();
  FrictionalStep s;
  s.normal_force_N = s.tangential_force_N = s.slip_m = Eigen::VectorXd::Zero(n);
  s.gap_m = p.q;
  s.state.assign(n, ContactState::Open);
  return s;
}

FrictionalStep solve_frictional_step(const FrictionalContactProblem& p, double T, const FrictionalStep& previous,
                                     const FrictionalStep* near) {
  check_problem(p);
  const Eigen::Index n = p.q.size();
  if (previous.normal_force_N.size() != n || previous.tangential_force_N.size() != n || previous.slip_m.size() != n ||
      static_cast<Eigen::Index>(previous.state.size()) != n)
    throw std::invalid_argument("solve_frictional_step: the previous state has other contacts");
  BoundedQp qp = step_problem(p, T, previous.slip_m);
  const FrictionalStep& from = near ? *near : previous;
  Eigen::VectorXd bound = p.friction_coefficient.cwiseProduct(from.normal_force_N);
  std::vector<Bound> warm = bounds_of(from);
  for (int pass = 1; pass <= kMaxPasses; ++pass) {
    set_slip_bound(qp, bound);
    const std::optional<QpIterate> start = start_from(qp, warm);
    const QpIterate it = solve_bounded_qp(qp, start ? *start : cold_start(p, qp));
    const ContactSets sets = sets_of(p, qp, it);
    const Eigen::VectorXd next = p.friction_coefficient.cwiseProduct(it.x.head(n));
    std::optional<Candidate> solution;
    if ((next - bound).cwiseAbs().maxCoeff() <= kFixedPointTol * next.cwiseAbs().maxCoeff())
      solution = Candidate{it.x, it.psi};  // the Tresca solution is Coulomb's (always so without friction)
    else if (Candidate c = coulomb_on_sets(p, qp, sets); satisfies_coulomb(p, qp, sets, c))
      solution = c;
    if (solution) {
      FrictionalStep s = step_state(p, qp, previous, *solution, sets);
      s.passes = pass;
      return s;
    }
    bound = next;
    warm = it.where;
  }
  throw InputError("contact: the load step to " + six_digits(T) + " N·m found no Coulomb solution in " +
                   std::to_string(kMaxPasses) + " fixed-point passes; friction_coefficient up to " +
                   six_digits(p.friction_coefficient.maxCoeff()) + " is too large for a unique load increment");
}

LoadStep frictional_step_of(const FrictionalContactProblem& p) {
  return [p](double T, const FrictionalStep& previous) { return solve_frictional_step(p, T, previous); };
}

std::vector<FrictionalStep> run_torque_history(const LoadStep& step, const FrictionalStep& start,
                                               const std::vector<double>& torques_Nm) {
  std::vector<FrictionalStep> out;
  out.reserve(torques_Nm.size());
  for (std::size_t k = 0; k < torques_Nm.size(); ++k) {
    try {
      out.push_back(step(torques_Nm[k], k ? out.back() : start));
    } catch (const InputError& e) {
      throw InputError("torque history step " + std::to_string(k) + " (" + six_digits(torques_Nm[k]) + " N·m): " + e.what());
    }
  }
  return out;
}

std::vector<FrictionalStep> solve_torque_history(const FrictionalContactProblem& p,
                                                 const std::vector<double>& torques_Nm) {
  return run_torque_history(frictional_step_of(p), unloaded_state(p), torques_Nm);
}

std::vector<double> cycle_torque_history(double T_R, int N, int cycles) {
  if (!(T_R > 0 && N >= 1 && cycles >= 1))
    throw std::invalid_argument("cycle_torque_history: need T_R > 0, steps >= 1, cycles >= 1");
  const double eps = kZeroTorqueLimit * T_R;
  std::vector<double> T{eps};
  const auto run = [&](int from, int to) {  // the steps T_R·s/N strictly after `from` up to `to`, with the limits at 0
    for (int s = from + (to > from ? 1 : -1);; s += to > from ? 1 : -1) {
      if (s == 0) {
        T.push_back(from > 0 ? eps : -eps);
        T.push_back(from > 0 ? -eps : eps);
      } else {
        T.push_back(T_R * s / N);
      }
      if (s == to) break;
    }
  };
  run(0, N);
  for (int c = 0; c < cycles; ++c) {
    run(N, -N);
    run(-N, N);
  }
  return T;
}

LoopReading read_loop(const std::vector<FrictionalStep>& history, double T_R) {
  std::vector<double> T, psi;
  for (const FrictionalStep& s : history) {
    T.push_back(s.torque_Nm);
    psi.push_back(s.twist_rad);
  }
  const LoadCycle cycle = last_load_cycle(T);
  LoopReading r;
  r.loop = loop_branches(T, psi, cycle, kZeroTorqueSnap * T_R);
  r.hysteresis_loss_rad = hysteresis_loss_rad(r.loop);
  r.rig_hysteresis_loss_rad = rig_hysteresis_loss_rad(r.loop);
  r.widest = widest_loop_width(r.loop);
  r.dissipated_energy_J = loop_area_J(r.loop);
  r.lost_motion_rad = lost_motion_rad(middle_line(r.loop.loading, r.loop.unloading), T_R);
  for (std::size_t k = cycle.top + 1; k <= cycle.end; ++k) r.friction_work_J += history[k].friction_work_J;
  return r;
}

SteadyLoop run_steady_loop(const LoadStep& step, const FrictionalStep& start, double T_R, int N, double rel_tol,
                           int max_cycles) {
  const std::vector<double> once = cycle_torque_history(T_R, N, 1);
  const auto top = once.begin() + N + 1;
  const std::vector<double> loading(once.begin(), top), cycle(top, once.end());  // cycle: +T_R → −T_R → +T_R
  SteadyLoop loop;
  loop.history = run_torque_history(step, start, loading);
  for (loop.cycles = 1;; ++loop.cycles) {
    const FrictionalStep at_top = loop.history.back();
    const std::vector<FrictionalStep> next = run_torque_history(step, at_top, cycle);
    loop.history.insert(loop.history.end(), next.begin(), next.end());
    loop.top_change_rel = top_state_change(at_top, loop.history.back());
    if (loop.top_change_rel <= rel_tol || loop.cycles == max_cycles) break;
  }
  loop.reading = read_loop(loop.history, T_R);
  return loop;
}

std::vector<StepStudyLevel> loop_step_study(const LoadStep& step, const FrictionalStep& start, double T_R,
                                            int first_steps, int levels, double rel_tol, int max_cycles) {
  std::vector<StepStudyLevel> out;
  for (int l = 0; l < levels; ++l) {
    const int N = first_steps << l;
    out.push_back({N, run_steady_loop(step, start, T_R, N, rel_tol, max_cycles)});
  }
  return out;
}

int converged_steps_per_quarter(const std::vector<StepStudyLevel>& study, double rel_tol) {
  if (study.empty()) return 0;
  const double finest = study.back().loop.reading.hysteresis_loss_rad;
  std::size_t k = study.size() - 1;
  while (k > 0 && std::abs(study[k - 1].loop.reading.hysteresis_loss_rad - finest) <= rel_tol * std::abs(finest)) --k;
  return study[k].steps_per_quarter;
}

}  // namespace sw
