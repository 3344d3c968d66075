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

}  // namespace

ContactSolution solve_contact(const ContactProblem& p, double T, const Eigen::VectorXd* warm) {
  const Eigen::Index n = p.q.size();
  if (p.A.rows() != n || p.A.cols() != n || p.lambda.size() != n)
    throw std::invalid_argument("solve_contact: A, q and lambda sizes differ");
  // A feasible start: the whole torque on the contact that closes first in T's direction.
  Eigen::Index first = -1;
  double first_turn = std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < n; ++i)
    if (p.lambda[i] * T > 0 && p.q[i] / std::abs(p.lambda[i]) < first_turn) first_turn = p.q[i] / std::abs(p.lambda[first = i]);
  if (first < 0)
    throw InputError("contact: no tooth flank can carry a torque of " + std::to_string(T) +
                     " N·m (no flank pair closes in that direction)");
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
  x[first] = T / p.lambda[first];
  std::vector<bool> passive(n, false);
  passive[first] = true;
  if (warm && warm->size() == n) {  // the warm set, if it gives a feasible start
    std::vector<Eigen::Index> S;
    for (Eigen::Index i = 0; i < n; ++i)
      if ((*warm)[i] > 0) S.push_back(i);
    if (!S.empty()) {
      const Kkt k = solve_on(p, S, T);
      if ((k.z.array() > 0).all() && k.z.allFinite()) {
        x.setZero();
        std::fill(passive.begin(), passive.end(), false);
        for (std::size_t r = 0; r < S.size(); ++r) {
          x[S[r]] = k.z[r];
          passive[S[r]] = true;
        }
      }
    }
  }
  const double scale = std::max(p.q.cwiseAbs().maxCoeff(), std::abs(T) * p.A.diagonal().maxCoeff() / p.lambda.cwiseAbs().maxCoeff());
  const double tol = 1e-12 * std::max(scale, 1e-300);
  ContactSolution out;
  double psi = 0;
  Eigen::Index added = -1;
  bool stalled = false;
  for (int outer = 0; outer < 6 * n + 20; ++outer) {
    // Solve on the passive set, stepping back while a force would go negative (Lawson–Hanson inner loop).
    for (bool first_pass = true;; first_pass = false) {
      std::vector<Eigen::Index> S;
      for (Eigen::Index i = 0; i < n; ++i)
        if (passive[i]) S.push_back(i);
      const Kkt k = solve_on(p, S, T);
      if (first_pass && added >= 0) {
        const auto r = std::find(S.begin(), S.end(), added) - S.begin();
        if (k.z[r] <= 0) {  // round-off: the contact cannot carry force after all; the previous iterate is optimal
          passive[added] = false;
          stalled = true;
          break;
        }
      }
      psi = k.psi;
      bool all_positive = true;
      for (double v : k.z) all_positive = all_positive && v > 0;
      if (all_positive) {
        x.setZero();
        for (std::size_t r = 0; r < S.size(); ++r) x[S[r]] = k.z[r];
        break;
      }
      double alpha = 1.0;
      for (std::size_t r = 0; r < S.size(); ++r)
        if (k.z[r] <= 0) alpha = std::min(alpha, x[S[r]] / (x[S[r]] - k.z[r]));
      for (std::size_t r = 0; r < S.size(); ++r) x[S[r]] += alpha * (k.z[r] - x[S[r]]);
      const double xmax = x.cwiseAbs().maxCoeff();
      for (Eigen::Index i : S)
        if (x[i] <= 1e-14 * xmax) {
          x[i] = 0;
          passive[i] = false;
        }
    }
    // The most penetrating contact outside the passive set joins it; none: optimal.
    const Eigen::VectorXd gap = p.A * x + p.q - psi * p.lambda;
    Eigen::Index add = -1;
    double worst = -tol;
    for (Eigen::Index i = 0; i < n && !stalled; ++i)
      if (!passive[i] && gap[i] < worst) worst = gap[add = i];
    if (add < 0) {
      out.force_N = x;
      out.gap_m = gap;
      for (Eigen::Index i = 0; i < n; ++i)
        if (passive[i]) out.gap_m[i] = 0;  // equal to zero to round-off by construction
      out.twist_rad = psi;
      out.iterations = outer + 1;
      return out;
    }
    passive[add] = true;
    added = add;
  }
  throw std::runtime_error("solve_contact: the active-set iteration did not converge");
}

}  // namespace sw
