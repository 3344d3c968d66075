#include "contact/contact_problem.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include <Eigen/Cholesky>

#include "common/error.hpp"

namespace sw {
namespace {

/// KKT system on the passive set S: A_SS·z − ψ·λ_S = −q_S, λ_Sᵀz = T (Schur complement on ψ).
struct Kkt {
  Eigen::VectorXd z;
  double psi = 0;
};
Kkt solve_on(const ContactProblem& p, const std::vector<Eigen::Index>& S, double T) {
  const auto n = static_cast<Eigen::Index>(S.size());
  Eigen::MatrixXd A(n, n);
  Eigen::VectorXd q(n), l(n);
  for (Eigen::Index r = 0; r < n; ++r) {
    q[r] = p.q[S[r]];
    l[r] = p.lambda[S[r]];
    for (Eigen::Index c = 0; c < n; ++c) A(r, c) = p.A(S[r], S[c]);
  }
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(A);
  const Eigen::VectorXd Aq = ldlt.solve(q), Al = ldlt.solve(l);
  Kkt k;
  k.psi = (T + l.dot(Aq)) / l.dot(Al);
  k.z = k.psi * Al - Aq;
  return k;
}

/// The iterate of the active-set method: the forces x (feasible: x ≥ 0, λᵀx = T), the passive set (contacts free to
/// carry force) and the last multiplier ψ.
struct ActiveSet {
  Eigen::VectorXd x;
  std::vector<bool> passive;
  double psi = 0;
};

std::vector<Eigen::Index> passive_indices(const std::vector<bool>& passive) {
  std::vector<Eigen::Index> S;
  for (Eigen::Index i = 0; i < static_cast<Eigen::Index>(passive.size()); ++i)
    if (passive[i]) S.push_back(i);
  return S;
}

/// A feasible start: the whole torque on the contact that closes first in T's direction, or, when `warm` loads a set
/// whose forces on it all come out positive, that set's solution. InputError when no contact closes in T's direction.
ActiveSet feasible_start(const ContactProblem& p, double T, const Eigen::VectorXd* warm) {
  const Eigen::Index n = p.q.size();
  Eigen::Index first = -1;
  double first_turn = std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < n; ++i)
    if (p.lambda[i] * T > 0 && p.q[i] / std::abs(p.lambda[i]) < first_turn) first_turn = p.q[i] / std::abs(p.lambda[first = i]);
  if (first < 0)
    throw InputError("contact: no tooth flank can carry a torque of " + std::to_string(T) +
                     " N·m (no flank pair closes in that direction)");
  ActiveSet s{Eigen::VectorXd::Zero(n), std::vector<bool>(n, false)};
  s.x[first] = T / p.lambda[first];
  s.passive[first] = true;
  if (!warm || warm->size() != n) return s;
  std::vector<Eigen::Index> S;
  for (Eigen::Index i = 0; i < n; ++i)
    if ((*warm)[i] > 0) S.push_back(i);
  if (S.empty()) return s;
  const Kkt k = solve_on(p, S, T);
  if (!((k.z.array() > 0).all() && k.z.allFinite())) return s;
  s.x.setZero();
  std::fill(s.passive.begin(), s.passive.end(), false);
  for (std::size_t r = 0; r < S.size(); ++r) {
    s.x[S[r]] = k.z[r];
    s.passive[S[r]] = true;
  }
  return s;
}

/// Solves on the passive set, stepping back while a force would go negative (Lawson–Hanson inner loop); updates x,
/// the passive set and ψ. False when the contact `added` last cannot carry force after all (round-off): it leaves the
/// passive set and the previous iterate, left as it was, is optimal.
bool solve_on_passive_set(const ContactProblem& p, double T, ActiveSet& s, Eigen::Index added) {
  for (bool first_pass = true;; first_pass = false) {
    const std::vector<Eigen::Index> S = passive_indices(s.passive);
    const Kkt k = solve_on(p, S, T);
    if (first_pass && added >= 0) {
      const auto r = std::find(S.begin(), S.end(), added) - S.begin();
      if (k.z[r] <= 0) {
        s.passive[added] = false;
        return false;
      }
    }
    s.psi = k.psi;
    bool all_positive = true;
    for (double v : k.z) all_positive = all_positive && v > 0;
    if (all_positive) {
      s.x.setZero();
      for (std::size_t r = 0; r < S.size(); ++r) s.x[S[r]] = k.z[r];
      return true;
    }
    double alpha = 1.0;
    for (std::size_t r = 0; r < S.size(); ++r)
      if (k.z[r] <= 0) alpha = std::min(alpha, s.x[S[r]] / (s.x[S[r]] - k.z[r]));
    for (std::size_t r = 0; r < S.size(); ++r) s.x[S[r]] += alpha * (k.z[r] - s.x[S[r]]);
    const double xmax = s.x.cwiseAbs().maxCoeff();
    for (Eigen::Index i : S)
      if (s.x[i] <= 1e-14 * xmax) {
        s.x[i] = 0;
        s.passive[i] = false;
      }
  }
}

/// The gap below which a contact counts as penetrating: round-off of the problem's largest gap, or of the gap the
/// torque opens through the largest compliance.
double penetration_tolerance(const ContactProblem& p, double T) {
  const double scale = std::max(p.q.cwiseAbs().maxCoeff(),
                                std::abs(T) * p.A.diagonal().maxCoeff() / p.lambda.cwiseAbs().maxCoeff());
  return 1e-12 * std::max(scale, 1e-300);
}

/// The most penetrating contact outside the passive set (gap below −tol), −1 when none.
Eigen::Index most_penetrating(const Eigen::VectorXd& gap, const std::vector<bool>& passive, double tol) {
  Eigen::Index add = -1;
  double worst = -tol;
  for (Eigen::Index i = 0; i < gap.size(); ++i)
    if (!passive[i] && gap[i] < worst) worst = gap[add = i];
  return add;
}

}  // namespace

ContactSolution solve_contact(const ContactProblem& p, double T, const Eigen::VectorXd* warm) {
  const Eigen::Index n = p.q.size();
  if (p.A.rows() != n || p.A.cols() != n || p.lambda.size() != n)
    throw std::invalid_argument("solve_contact: A, q and lambda sizes differ");
  ActiveSet s = feasible_start(p, T, warm);
  const double tol = penetration_tolerance(p, T);
  Eigen::Index added = -1;
  for (int outer = 0; outer < 6 * n + 20; ++outer) {
    const bool stalled = !solve_on_passive_set(p, T, s, added);
    // The most penetrating contact outside the passive set joins it; none (or a stalled step): optimal.
    const Eigen::VectorXd gap = p.A * s.x + p.q - s.psi * p.lambda;
    const Eigen::Index add = stalled ? -1 : most_penetrating(gap, s.passive, tol);
    if (add < 0) {
      ContactSolution out;
      out.force_N = s.x;
      out.gap_m = gap;
      for (Eigen::Index i = 0; i < n; ++i)
        if (s.passive[i]) out.gap_m[i] = 0;  // equal to zero to round-off by construction
      out.twist_rad = s.psi;
      out.iterations = outer + 1;
      return out;
    }
    s.passive[add] = true;
    added = add;
  }
  throw std::runtime_error("solve_contact: the active-set iteration did not converge");
}

}  // namespace sw
