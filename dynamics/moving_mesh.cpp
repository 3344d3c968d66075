#include "dynamics/moving_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include <Eigen/Cholesky>

#include "common/error.hpp"

namespace sw {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// φ wrapped to (−π, π], or to (−π/2, π/2] when one unknown stands for a tooth and its half-turn partner.
double wrap_phi(double phi, int teeth_per_unknown) {
  const double period = 2 * kPi / teeth_per_unknown;
  return phi - period * std::ceil(phi / period - 0.5);
}

struct TableValue {
  double q, dq_dphi, lambda, dlambda_dphi, compliance, dcompliance_dphi;
};

/// Slope of a tabulated function at grid point j, monotone (Fritsch–Butland, as PCHIP): the harmonic mean of the two
/// neighbouring secants where they agree in sign, zero at a local extremum, the one-sided secant at a validity edge.
/// A monotone slope never overshoots the data (Catmull–Rom's central difference did at the kinks of q, where the
/// contact moves from the circular spline's flank to its tip corner, and put a line at 8·f_m into the spectrum).
double node_slope(const std::vector<double>& y, int j, double h) {
  const bool lo = j > 0 && !std::isnan(y[j - 1]);
  const bool hi = j + 1 < static_cast<int>(y.size()) && !std::isnan(y[j + 1]);
  if (lo && hi) {
    const double d0 = (y[j] - y[j - 1]) / h, d1 = (y[j + 1] - y[j]) / h;
    return d0 * d1 > 0 ? 2 * d0 * d1 / (d0 + d1) : 0.0;
  }
  if (hi) return (y[j + 1] - y[j]) / h;
  if (lo) return (y[j] - y[j - 1]) / h;
  return 0.0;
}

/// Cubic Hermite interpolation on [j, j + 1] at fraction a with the node slopes above: value and
/// derivative in φ, continuous across grid points. A linear interpolation kinks every flank at every grid point, all
/// teeth at once (they sit one pitch apart on a grid of pitch/n), and each kink cut the integrator's step.
void hermite(const std::vector<double>& y, int j, double a, double h, double& value, double& slope) {
  const double m0 = node_slope(y, j, h) * h, m1 = node_slope(y, j + 1, h) * h;
  const double a2 = a * a, a3 = a2 * a;
  value = (2 * a3 - 3 * a2 + 1) * y[j] + (a3 - 2 * a2 + a) * m0 + (-2 * a3 + 3 * a2) * y[j + 1] + (a3 - a2) * m1;
  slope = ((6 * a2 - 6 * a) * y[j] + (3 * a2 - 4 * a + 1) * m0 + (-6 * a2 + 6 * a) * y[j + 1] + (3 * a2 - 2 * a) * m1) / h;
}

/// The table at φ; false where the flank cannot close on either grid angle.
bool lookup(const FlankTable& t, int side, double phi, TableValue& v) {
  const double u = (phi - t.phi_start_rad) / t.step_rad;
  const int j = static_cast<int>(std::floor(u));
  if (j < 0 || j + 1 >= t.size()) return false;
  const double a = u - j;
  if (std::isnan(t.q_m[side][j]) || std::isnan(t.q_m[side][j + 1])) return false;
  hermite(t.q_m[side], j, a, t.step_rad, v.q, v.dq_dphi);
  hermite(t.lambda_m[side], j, a, t.step_rad, v.lambda, v.dlambda_dphi);
  hermite(t.compliance_m_per_N[side], j, a, t.step_rad, v.compliance, v.dcompliance_dphi);
  return true;
}

}  // namespace

FlankTable make_flank_table(double phi_start, double phi_end, double step, int teeth_per_unknown,
                            const std::function<bool(double, int, double&, double&, double&, double&)>& flank,
                            const std::function<double(double, double)>& tooth_compliance) {
  FlankTable t;
  t.phi_start_rad = phi_start;
  t.step_rad = step;
  const int n = static_cast<int>(std::ceil((phi_end - phi_start) / step)) + 1;
  for (int side = 0; side < 2; ++side) {
    t.q_m[side].assign(n, kNaN);
    t.lambda_m[side].assign(n, kNaN);
    t.compliance_m_per_N[side].assign(n, kNaN);
  }
  for (int j = 0; j < n; ++j)
    for (int side = 0; side < 2; ++side) {
      double q = 0, lever = 0, radius = 0, radius_c = 0;
      if (!flank(phi_start + j * step, side, q, lever, radius, radius_c)) continue;
      t.q_m[side][j] = teeth_per_unknown * q;
      t.lambda_m[side][j] = teeth_per_unknown * lever;
      t.compliance_m_per_N[side][j] = tooth_compliance ? teeth_per_unknown * tooth_compliance(radius, radius_c) : 0.0;
    }
  return t;
}

void mesh_instant(const MovingMesh& m, double sigma, MeshInstant& out) {
  out.tooth.clear();
  out.side.clear();
  const int period = m.key_period();
  const double p = m.pitch_rad;
  const double turns = std::floor(sigma / p);
  const double r = sigma - turns * p;
  const int shift = static_cast<int>(std::fmod(turns, period) + period) % period;  // teeth renamed by whole pitches
  std::vector<TableValue> values;
  std::vector<int> kept;  // coupled: the flanks' places among phase s's continuing flanks
  auto add = [&](int tooth, int side, double phi) {
    TableValue v;
    if (!lookup(m.table, side, wrap_phi(phi, m.teeth_per_unknown), v)) return false;
    out.tooth.push_back(tooth);
    out.side.push_back(side);
    values.push_back(v);
    return true;
  };
  int s = 0, s1 = 0;
  double a = 0;
  if (!m.coupled()) {
    for (int k = 0; k < period; ++k)
      for (int side = 0; side < 2; ++side) add(k, side, 2 * kPi * k / m.teeth_flexspline - sigma);
  } else {
    const int S = static_cast<int>(m.phases.size());
    const double h = p / S;
    s = std::min(static_cast<int>(std::floor(r / h)), S - 1);
    s1 = (s + 1) % S;
    a = (r - m.phases[s].shift_rad) / h;
    const MeshPhase& ph = m.phases[s];
    for (std::size_t c = 0; c < ph.continuing.size(); ++c) {
      const int i = ph.continuing[c];
      if (add((ph.key[i] + shift) % period, ph.side[i], ph.phi_rad[i] - (r - ph.shift_rad)))
        kept.push_back(static_cast<int>(c));
    }
  }
  const int nf = static_cast<int>(values.size());
  out.q.resize(nf);
  out.dq.resize(nf);
  out.lambda.resize(nf);
  out.dlambda.resize(nf);
  out.compliance.resize(nf);
  out.dcompliance.resize(nf);
  for (int i = 0; i < nf; ++i) {
    const TableValue& v = values[i];
    out.q[i] = v.q;
    out.dq[i] = -v.dq_dphi;  // φ = 2πk/z_f − σ
    out.lambda[i] = v.lambda;
    out.dlambda[i] = -v.dlambda_dphi;
    out.compliance[i] = v.compliance;
    out.dcompliance[i] = -v.dcompliance_dphi;
  }
  if (!m.coupled()) {
    out.A.resize(0, 0);
    out.dA.resize(0, 0);
    return;
  }
  const MeshPhase& P0 = m.phases[s];
  const MeshPhase& P1 = m.phases[s1];
  const double h = p / m.phases.size();
  const double da = r - P0.shift_rad;
  const auto nc = static_cast<int>(P0.continuing.size());
  if (nf == nc) {  // every continuing flank is on the table here: the whole gathered block
    out.A = P0.A_start + da * P0.A_slope;
    out.dA = P0.A_slope;
  } else {
    const int nb = static_cast<int>(m.station_q.size());
    std::vector<int> idx(kept);
    for (int j = 0; j < nb; ++j) idx.push_back(nc + j);
    out.A = P0.A_start(idx, idx) + da * P0.A_slope(idx, idx);
    out.dA = P0.A_slope(idx, idx);
  }
  for (int k = 0; k < nf; ++k) {
    const int i = P0.continuing[kept[k]];
    const double c0 = P0.q_correction[i], c1 = P1.q_correction[P0.next[i]];
    out.q[k] += (1 - a) * c0 + a * c1;
    out.dq[k] += (c1 - c0) / h;
  }
}

void prepare_intervals(MovingMesh& m) {
  const int S = static_cast<int>(m.phases.size());
  const int nb = static_cast<int>(m.station_q.size());
  const double h = m.pitch_rad / S;
  for (int s = 0; s < S; ++s) {
    MeshPhase& P0 = m.phases[s];
    const MeshPhase& P1 = m.phases[(s + 1) % S];
    P0.continuing.clear();
    for (std::size_t i = 0; i < P0.key.size(); ++i)
      if (P0.next[i] >= 0) P0.continuing.push_back(static_cast<int>(i));
    const int n0 = static_cast<int>(P0.key.size()), n1 = static_cast<int>(P1.key.size());
    std::vector<int> i0(P0.continuing), i1;
    for (int i : P0.continuing) i1.push_back(P0.next[i]);
    for (int j = 0; j < nb; ++j) {
      i0.push_back(n0 + j);
      i1.push_back(n1 + j);
    }
    P0.A_start = P0.A_body(i0, i0);
    P0.A_slope = (P1.A_body(i1, i1) - P0.A_start) / h;
  }
}

int solve_lcp(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, Eigen::VectorXd& x, std::vector<char>& active) {
  const int n = static_cast<int>(b.size());
  active.resize(n, 0);
  x = Eigen::VectorXd::Zero(n);
  if (n == 0) return 0;
  const double scale = std::max(b.cwiseAbs().maxCoeff(), 1e-300);
  const double tol_w = 1e-12 * scale;
  int best = n + 1, backups = 3;
  Eigen::VectorXd w(n);
  std::vector<int> F;
  for (int it = 1; it <= 10 * n + 50; ++it) {
    F.clear();
    for (int i = 0; i < n; ++i)
      if (active[i]) F.push_back(i);
    const int nF = static_cast<int>(F.size());
    x.setZero();
    if (nF > 0) {
      Eigen::MatrixXd AF(nF, nF);
      Eigen::VectorXd bF(nF);
      for (int c = 0; c < nF; ++c) {
        bF[c] = -b[F[c]];
        for (int r = 0; r < nF; ++r) AF(r, c) = A(F[r], F[c]);
      }
      const Eigen::VectorXd xF = AF.llt().solve(bF);
      for (int c = 0; c < nF; ++c) x[F[c]] = xF[c];
    }
    w.noalias() = A * x + b;
    std::vector<int> bad;
    for (int i = 0; i < n; ++i)
      if ((active[i] && x[i] < 0) || (!active[i] && w[i] < -tol_w)) bad.push_back(i);
    if (bad.empty()) {
      for (int i = 0; i < n; ++i)
        if (!active[i]) x[i] = 0;
      return it;
    }
    const int ninf = static_cast<int>(bad.size());
    if (ninf < best) {
      best = ninf;
      backups = 3;
      for (int i : bad) active[i] = !active[i];
    } else if (backups > 0) {
      --backups;
      for (int i : bad) active[i] = !active[i];
    } else {
      active[bad.back()] = !active[bad.back()];  // Murty: the largest index, finite for a P-matrix
    }
  }
  throw InputError("dynamics: the tooth contact problem (" + std::to_string(n) +
                   " contacts) did not converge; check the contact stiffness and the clearances");
}

}  // namespace sw
