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

/// The passive set S and its block of the compliance in Cholesky form, L·Lᵀ = A_SS (A is positive definite, so is
/// every principal block). A contact that joins appends a row (one triangular solve, O(k²)); one that leaves deletes
/// its row and restores the trailing block by a rank-one update (O(k²)), where factorising afresh at every step of the
/// active-set method costs O(k³) a step (Golub & Van Loan, Matrix Computations, 4th ed., 2013, §6.5: updating
/// Cholesky factors; the same updates Lawson & Hanson, Solving Least Squares Problems, 1974, ch. 24, make on their QR
/// form). Written here: Eigen's LLT updates a whole factor by a rank-one term but neither inserts nor deletes a row.
class PassiveFactor {
 public:
  explicit PassiveFactor(const ContactProblem& p) : p_(p), L_(p.q.size(), p.q.size()), at_(p.q.size(), -1) {}

  const std::vector<Eigen::Index>& set() const { return S_; }
  Eigen::Index size() const { return static_cast<Eigen::Index>(S_.size()); }
  bool contains(Eigen::Index i) const { return at_[i] >= 0; }
  /// Position of contact i in set() (−1 when it is not passive).
  Eigen::Index position(Eigen::Index i) const { return at_[i]; }

  /// S becomes `S`, factorised at once (blocked: a warm start's set).
  void reset(const std::vector<Eigen::Index>& S) {
    for (Eigen::Index i : S_) at_[i] = -1;
    S_ = S;
    const Eigen::Index k = size();
    Eigen::MatrixXd A(k, k);
    for (Eigen::Index r = 0; r < k; ++r) {
      at_[S_[r]] = r;
      for (Eigen::Index c = 0; c < k; ++c) A(r, c) = p_.A(S_[r], S_[c]);
    }
    const Eigen::LLT<Eigen::MatrixXd> llt(A);
    L_.topLeftCorner(k, k) = llt.matrixL();
    ok_ = llt.info() == Eigen::Success;
  }

  /// Contact i joins S as its last row. False, S unchanged, when its pattern is (to round-off) a combination of those
  /// already in S: it adds no stiffness the set has not got.
  bool add(Eigen::Index i) {
    const Eigen::Index k = size();
    Eigen::VectorXd a(k);
    for (Eigen::Index r = 0; r < k; ++r) a[r] = p_.A(S_[r], i);
    L_.topLeftCorner(k, k).triangularView<Eigen::Lower>().solveInPlace(a);
    const double d2 = p_.A(i, i) - a.squaredNorm();
    if (!(d2 > 1e-14 * p_.A(i, i))) return false;
    L_.row(k).head(k) = a.transpose();
    L_(k, k) = std::sqrt(d2);
    at_[i] = k;
    S_.push_back(i);
    return true;
  }

  /// Contact i leaves S: its row and column go, the rows below move up and the trailing block takes the rank-one
  /// update by the column it lost (L₂₂·L₂₂ᵀ + v·vᵀ, LINPACK's dchud: plane rotations, stable).
  void remove(Eigen::Index i) {
    const Eigen::Index r = at_[i], k = size(), m = k - 1 - r;
    Eigen::VectorXd v = L_.col(r).segment(r + 1, m);
    if (r > 0) L_.block(r, 0, m, r) = L_.block(r + 1, 0, m, r).eval();
    L_.block(r, r, m, m).triangularView<Eigen::Lower>() = L_.block(r + 1, r + 1, m, m).eval();
    for (Eigen::Index j = 0; j < m; ++j) {
      const Eigen::Index J = r + j;
      const double Ljj = L_(J, J), rho = std::hypot(Ljj, v[j]), c = rho / Ljj, s = v[j] / Ljj;
      L_(J, J) = rho;
      for (Eigen::Index t = j + 1; t < m; ++t) {
        double& Ltj = L_(r + t, J);
        Ltj = (Ltj + s * v[t]) / c;
        v[t] = c * v[t] - s * Ltj;
      }
    }
    at_[i] = -1;
    S_.erase(S_.begin() + r);
    for (Eigen::Index t = r; t < k - 1; ++t) at_[S_[t]] = t;
  }

  /// A_SS⁻¹·b (b in set() order).
  Eigen::VectorXd solve(Eigen::VectorXd b) const {
    const Eigen::Index k = size();
    const auto L = L_.topLeftCorner(k, k);
    L.triangularView<Eigen::Lower>().solveInPlace(b);
    L.transpose().triangularView<Eigen::Upper>().solveInPlace(b);
    return b;
  }

  bool factorised() const { return ok_; }

 private:
  const ContactProblem& p_;
  Eigen::MatrixXd L_;  // its top-left size() × size() lower triangle is the factor
  std::vector<Eigen::Index> S_;
  std::vector<Eigen::Index> at_;
  bool ok_ = true;
};

/// KKT system on the passive set S: A_SS·z − ψ·λ_S = −q_S, λ_Sᵀz = T (Schur complement on ψ); z in set() order.
struct Kkt {
  Eigen::VectorXd z;
  double psi = 0;
};
Kkt solve_on(const ContactProblem& p, const PassiveFactor& f, double T) {
  const std::vector<Eigen::Index>& S = f.set();
  const auto n = static_cast<Eigen::Index>(S.size());
  Eigen::VectorXd q(n), l(n);
  for (Eigen::Index r = 0; r < n; ++r) {
    q[r] = p.q[S[r]];
    l[r] = p.lambda[S[r]];
  }
  const Eigen::VectorXd Aq = f.solve(q), Al = f.solve(l);
  Kkt k;
  k.psi = (T + l.dot(Aq)) / l.dot(Al);
  k.z = k.psi * Al - Aq;
  return k;
}

/// The iterate of the active-set method: the forces x (feasible: x ≥ 0, λᵀx = T), the passive set (contacts free to
/// carry force, with their factor) and the last multiplier ψ.
struct ActiveSet {
  Eigen::VectorXd x;
  PassiveFactor passive;
  double psi = 0;
};

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
  ActiveSet s{Eigen::VectorXd::Zero(n), PassiveFactor(p)};
  if (warm && warm->size() == n) {
    std::vector<Eigen::Index> S;
    for (Eigen::Index i = 0; i < n; ++i)
      if ((*warm)[i] > 0) S.push_back(i);
    if (!S.empty()) {
      s.passive.reset(S);
      if (s.passive.factorised()) {
        const Kkt k = solve_on(p, s.passive, T);
        if ((k.z.array() > 0).all() && k.z.allFinite()) {
          for (std::size_t r = 0; r < S.size(); ++r) s.x[S[r]] = k.z[r];
          return s;
        }
      }
    }
  }
  s.passive.reset({first});
  s.x[first] = T / p.lambda[first];
  return s;
}

/// Solves on the passive set, stepping back while a force would go negative (Lawson–Hanson inner loop); updates x,
/// the passive set and ψ. False when the contact `added` last cannot carry force after all (round-off): it leaves the
/// passive set and the previous iterate, left as it was, is optimal.
bool solve_on_passive_set(const ContactProblem& p, double T, ActiveSet& s, Eigen::Index added) {
  for (bool first_pass = true;; first_pass = false) {
    const Kkt k = solve_on(p, s.passive, T);
    const std::vector<Eigen::Index> S = s.passive.set();
    if (first_pass && added >= 0 && k.z[s.passive.position(added)] <= 0) {
      s.passive.remove(added);
      return false;
    }
    s.psi = k.psi;
    if ((k.z.array() > 0).all()) {
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
        s.passive.remove(i);
      }
  }
}

/// The gaps g = A·x + q − ψ·λ, from the passive set's columns only (x is zero elsewhere): O(n·k).
Eigen::VectorXd gaps(const ContactProblem& p, const ActiveSet& s) {
  Eigen::VectorXd g = p.q - s.psi * p.lambda;
  for (Eigen::Index j : s.passive.set()) g.noalias() += p.A.col(j) * s.x[j];
  return g;
}

/// The gap below which a contact counts as penetrating: round-off of the problem's largest gap, or of the gap the
/// torque opens through the largest compliance.
double penetration_tolerance(const ContactProblem& p, double T) {
  const double scale = std::max(p.q.cwiseAbs().maxCoeff(),
                                std::abs(T) * p.A.diagonal().maxCoeff() / p.lambda.cwiseAbs().maxCoeff());
  return 1e-12 * std::max(scale, 1e-300);
}

/// The most penetrating contact outside the passive set (gap below −tol), −1 when none.
Eigen::Index most_penetrating(const Eigen::VectorXd& gap, const PassiveFactor& passive, double tol) {
  Eigen::Index add = -1;
  double worst = -tol;
  for (Eigen::Index i = 0; i < gap.size(); ++i)
    if (!passive.contains(i) && gap[i] < worst) worst = gap[add = i];
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
    const Eigen::VectorXd gap = gaps(p, s);
    Eigen::Index add = stalled ? -1 : most_penetrating(gap, s.passive, tol);
    if (add >= 0 && !s.passive.add(add)) add = -1;  // it adds nothing the set has not got: optimal to round-off
    if (add < 0) {
      ContactSolution out;
      out.force_N = s.x;
      out.gap_m = gap;
      for (Eigen::Index i : s.passive.set()) out.gap_m[i] = 0;  // equal to zero to round-off by construction
      out.twist_rad = s.psi;
      out.iterations = outer + 1;
      return out;
    }
    added = add;
  }
  throw std::runtime_error("solve_contact: the active-set iteration did not converge");
}

}  // namespace sw
