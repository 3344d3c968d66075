#include "dynamics/moving_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <string>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "common/constants.hpp"
#include "common/error.hpp"

namespace sw {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// φ wrapped to (−π, π], or to (−π/2, π/2] when one unknown stands for a tooth and its half-turn partner.
double wrap_phi(double phi, int teeth_per_unknown) {
  const double period = 2 * kPi / teeth_per_unknown;
  return phi - period * std::ceil(phi / period - 0.5);
}

struct TableValue {
  double q, dq_dphi, lambda, dlambda_dphi, compliance, dcompliance_dphi, sliding, tangent_arm;
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

/// The node slopes of a whole column of the table.
std::vector<double> node_slopes(const std::vector<double>& y, double h) {
  std::vector<double> out(y.size(), 0.0);
  for (std::size_t j = 0; j < y.size(); ++j)
    if (!std::isnan(y[j])) out[j] = node_slope(y, static_cast<int>(j), h);
  return out;
}

/// A cubic Hermite segment over a ∈ [0, 1] (a step h long) with end values y0, y1 and end slopes m0, m1 per unit a:
/// its value and its derivative per unit of the step's variable.
struct HermitePoint {
  double value, slope;
};

HermitePoint hermite_segment(double y0, double m0, double y1, double m1, double a, double h) {
  const double a2 = a * a, a3 = a2 * a;
  return {(2 * a3 - 3 * a2 + 1) * y0 + (a3 - 2 * a2 + a) * m0 + (-2 * a3 + 3 * a2) * y1 + (a3 - a2) * m1,
          ((6 * a2 - 6 * a) * y0 + (3 * a2 - 4 * a + 1) * m0 + (-6 * a2 + 6 * a) * y1 + (3 * a2 - 2 * a) * m1) / h};
}

/// Cubic Hermite interpolation on [j, j + 1] at fraction a with the node slopes above: value and
/// derivative in φ, continuous across grid points. A linear interpolation kinks every flank at every grid point, all
/// teeth at once (they sit one pitch apart on a grid of pitch/n), and each kink cut the integrator's step.
HermitePoint hermite(const std::vector<double>& y, const std::vector<double>& dy, int j, double a, double h) {
  return hermite_segment(y[j], dy[j] * h, y[j + 1], dy[j + 1] * h, a, h);
}

/// The table at φ, the sliding and the tangent arm only when asked for (0 otherwise); false where the flank cannot close
/// on either grid angle.
bool lookup(const FlankTable& t, int side, double phi, bool with_sliding, TableValue& v) {
  const double u = (phi - t.phi_start_rad) / t.step_rad;
  const int j = static_cast<int>(std::floor(u));
  if (j < 0 || j + 1 >= t.size()) return false;
  const double a = u - j;
  if (std::isnan(t.q_m[side][j]) || std::isnan(t.q_m[side][j + 1])) return false;
  const HermitePoint q = hermite(t.q_m[side], t.q_slope[side], j, a, t.step_rad);
  const HermitePoint lambda = hermite(t.lambda_m[side], t.lambda_slope[side], j, a, t.step_rad);
  const HermitePoint c = hermite(t.compliance_m_per_N[side], t.compliance_slope[side], j, a, t.step_rad);
  v = {q.value, q.slope, lambda.value, lambda.slope, c.value, c.slope, 0.0, 0.0};
  if (with_sliding) {
    v.sliding = hermite(t.sliding_m_per_rad[side], t.sliding_slope[side], j, a, t.step_rad).value;
    v.tangent_arm = hermite(t.tangent_arm_m[side], t.tangent_arm_slope[side], j, a, t.step_rad).value;
  }
  return true;
}

}  // namespace

FlankTable make_flank_table(double phi_start, double phi_end, double step, int teeth_per_unknown,
                            const std::function<bool(double, int, FlankSample&)>& flank,
                            const std::function<double(double, double)>& tooth_compliance) {
  FlankTable t;
  t.phi_start_rad = phi_start;
  t.step_rad = step;
  const int n = static_cast<int>(std::ceil((phi_end - phi_start) / step)) + 1;
  for (int side = 0; side < 2; ++side)
    for (auto* column : {&t.q_m[side], &t.lambda_m[side], &t.compliance_m_per_N[side], &t.sliding_m_per_rad[side],
                         &t.tangent_arm_m[side]})
      column->assign(n, kNaN);
  const double per = teeth_per_unknown;
  for (int j = 0; j < n; ++j)
    for (int side = 0; side < 2; ++side) {
      FlankSample f;
      if (!flank(phi_start + j * step, side, f)) continue;
      t.q_m[side][j] = per * f.q_m;
      t.lambda_m[side][j] = per * f.lever_m;
      t.compliance_m_per_N[side][j] =
          tooth_compliance ? per * tooth_compliance(f.contact_radius_f_m, f.contact_radius_c_m) : 0.0;
      t.sliding_m_per_rad[side][j] = per * f.sliding_m_per_rad;
      t.tangent_arm_m[side][j] = per * f.tangent_arm_m;
    }
  for (int side = 0; side < 2; ++side) {
    t.q_slope[side] = node_slopes(t.q_m[side], step);
    t.lambda_slope[side] = node_slopes(t.lambda_m[side], step);
    t.compliance_slope[side] = node_slopes(t.compliance_m_per_N[side], step);
    t.sliding_slope[side] = node_slopes(t.sliding_m_per_rad[side], step);
    t.tangent_arm_slope[side] = node_slopes(t.tangent_arm_m[side], step);
  }
  return t;
}

namespace {

/// Where σ falls: the whole pitches turned (teeth renamed by them), the rest r in [0, pitch), and on a coupled rim the
/// compliance phase whose interval holds r and the fraction a of that interval.
struct MeshPlace {
  int shift = 0;
  double r = 0;
  int phase = 0, next_phase = 0;
  double a = 0;
};

MeshPlace place_of(const MovingMesh& m, double sigma) {
  const int period = m.key_period();
  const double p = m.pitch_rad;
  const double turns = std::floor(sigma / p);
  MeshPlace at;
  at.r = sigma - turns * p;
  at.shift = static_cast<int>(std::fmod(turns, period) + period) % period;
  if (m.coupled()) {
    const int S = static_cast<int>(m.phases.size());
    const double h = p / S;
    at.phase = std::min(static_cast<int>(std::floor(at.r / h)), S - 1);
    at.next_phase = (at.phase + 1) % S;
    at.a = (at.r - m.phases[at.phase].shift_rad) / h;
  }
  return at;
}

/// The flanks that can close at σ with their table values (tooth and side into `out`): both flanks of every tooth
/// on a rigid rim; the phase's continuing flanks on a coupled rim, with their places among those in `kept`.
std::vector<TableValue> flanks_at(const MovingMesh& m, double sigma, const MeshPlace& at, bool with_sliding,
                                  MeshInstant& out, std::vector<int>& kept) {
  out.tooth.clear();
  out.side.clear();
  std::vector<TableValue> values;
  auto add = [&](int tooth, int side, double phi) {
    TableValue v;
    if (!lookup(m.table, side, wrap_phi(phi, m.teeth_per_unknown), with_sliding, v)) return false;
    out.tooth.push_back(tooth);
    out.side.push_back(side);
    values.push_back(v);
    return true;
  };
  const int period = m.key_period();
  if (!m.coupled()) {
    for (int k = 0; k < period; ++k)
      for (int side = 0; side < 2; ++side) add(k, side, 2 * kPi * k / m.teeth_flexspline - sigma);
    return values;
  }
  const MeshPhase& ph = m.phases[at.phase];
  for (std::size_t c = 0; c < ph.continuing.size(); ++c) {
    const int i = ph.continuing[c];
    if (add((ph.key[i] + at.shift) % period, ph.side[i], ph.phi_rad[i] - (at.r - ph.shift_rad)))
      kept.push_back(static_cast<int>(c));
  }
  return values;
}

/// The flanks' gaps, arms and compliances with their σ-derivatives (φ = 2πk/z_f − σ), their sliding and tangent arms
/// when asked for (else left empty).
void set_flank_values(const std::vector<TableValue>& values, bool with_sliding, MeshInstant& out) {
  const int nf = static_cast<int>(values.size());
  out.q.resize(nf);
  out.dq.resize(nf);
  out.lambda.resize(nf);
  out.dlambda.resize(nf);
  out.compliance.resize(nf);
  out.dcompliance.resize(nf);
  out.sliding.resize(with_sliding ? nf : 0);
  out.tangent_arm.resize(with_sliding ? nf : 0);
  for (int i = 0; i < nf; ++i) {
    const TableValue& v = values[i];
    out.q[i] = v.q;
    out.dq[i] = -v.dq_dphi;
    out.lambda[i] = v.lambda;
    out.dlambda[i] = -v.dlambda_dphi;
    out.compliance[i] = v.compliance;
    out.dcompliance[i] = -v.dcompliance_dphi;
  }
  for (Eigen::Index i = 0; i < out.sliding.size(); ++i) {
    out.sliding[i] = values[i].sliding;
    out.tangent_arm[i] = values[i].tangent_arm;
  }
}

/// Coupled rim: the phase's body-compliance cubic over the kept flanks and the stations (columns formed on demand),
/// and each flank's gap correction (the generator's own state) added to its gap and rate.
void set_body(const MovingMesh& m, const MeshPlace& at, const std::vector<int>& kept, MeshInstant& out) {
  const MeshPhase& P0 = m.phases[at.phase];
  const MeshPhase& P1 = m.phases[at.next_phase];
  const double h = m.pitch_rad / m.phases.size();
  const int nf = out.flanks();
  const auto nc = static_cast<int>(P0.continuing.size());
  out.cubic = P0.A_cubic;
  out.a = at.a;
  out.h = h;
  out.rows.clear();
  if (nf != nc) {  // a continuing flank is off the table here: a subset of the gathered block
    out.rows = kept;
    for (int j = 0; j < static_cast<int>(m.station_q.size()); ++j) out.rows.push_back(nc + j);
  }
  out.stations = static_cast<int>(m.station_q.size());
  const int n = nf + out.stations;
  if (out.A.rows() < n) out.A.resize(n, n);  // kept between instants: only the first n rows of a column are used
  out.formed.assign(n, 0);
  out.series.setZero(n);
  for (int k = 0; k < nf; ++k) {
    const int c = kept[k], i = P0.continuing[c];
    const HermitePoint g = hermite_segment(P0.q_correction[i], P0.q_slope_start[c] * h,
                                           P1.q_correction[P0.next[i]], P0.q_slope_end[c] * h, at.a, h);
    out.q[k] += g.value;
    out.dq[k] += g.slope;
  }
}

/// Interval s (phase s to the next) as a cubic in a over the flanks continuing into the next phase and the stations,
/// with the phases' slopes of A and the gap correction's slopes.
void set_interval(MovingMesh& m, int s, const Eigen::MatrixXd& tangent0, const Eigen::MatrixXd& tangent1,
                  const std::vector<std::vector<double>>& q_tangent) {
  const int S = static_cast<int>(m.phases.size());
  const int nb = static_cast<int>(m.station_q.size());
  const double h = m.pitch_rad / S;
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
  // The Hermite segment over a ∈ [0, 1] as a cubic: A0 + a·hT0 + a²·(3ΔA − 2hT0 − hT1) + a³·(hT0 + hT1 − 2ΔA).
  const Eigen::MatrixXd A0 = P0.A_body(i0, i0);
  const Eigen::MatrixXd dA = P1.A_body(i1, i1) - A0;
  const Eigen::MatrixXd T0 = h * tangent0(i0, i0), T1 = h * tangent1(i1, i1);
  P0.A_cubic[0] = A0;
  P0.A_cubic[1] = T0;
  P0.A_cubic[2] = 3 * dA - 2 * T0 - T1;
  P0.A_cubic[3] = T0 + T1 - 2 * dA;
  P0.q_slope_start.clear();
  P0.q_slope_end.clear();
  for (int i : P0.continuing) {
    P0.q_slope_start.push_back(q_tangent[s][i]);
    P0.q_slope_end.push_back(q_tangent[(s + 1) % S][P0.next[i]]);
  }
}

/// The contact problem's matrix on the interval, its cubic with `series_m_per_N` on the continuing flanks' diagonal
/// (their tooth pairs' least compliance there), at a = k/16, k = 1..15: the eigenvector of its least eigenvalue at the
/// first point where that is not positive, else nothing.
std::optional<Eigen::VectorXd> negative_direction(const MeshPhase& P, const Eigen::VectorXd& series_m_per_N) {
  for (int k = 1; k < 16; ++k) {
    const double a = k / 16.0;
    Eigen::MatrixXd A = P.A_cubic[0] + a * (P.A_cubic[1] + a * (P.A_cubic[2] + a * P.A_cubic[3]));
    A.diagonal().head(series_m_per_N.size()) += series_m_per_N;
    if (A.llt().info() == Eigen::Success) continue;
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(A);
    return eig.eigenvectors().col(0);  // eigenvalues ascending
  }
  return std::nullopt;
}

}  // namespace

void mesh_instant(const MovingMesh& m, double sigma, MeshInstant& out, bool with_sliding) {
  const MeshPlace at = place_of(m, sigma);
  std::vector<int> kept;  // coupled: the flanks' places among the phase's continuing flanks
  set_flank_values(flanks_at(m, sigma, at, with_sliding, out, kept), with_sliding, out);
  if (!m.coupled()) {
    out.cubic = nullptr;
    out.stations = 0;
    return;
  }
  set_body(m, at, kept, out);
}

const double* MeshInstant::column(int j) {
  double* out = A.col(j).data();
  if (formed[j]) return out;
  const Eigen::MatrixXd* C = cubic;
  const double a2 = a * a, a3 = a2 * a;
  const Eigen::Index n = unknowns();
  if (rows.empty()) {
    const double *c0 = C[0].col(j).data(), *c1 = C[1].col(j).data(), *c2 = C[2].col(j).data(), *c3 = C[3].col(j).data();
    for (Eigen::Index i = 0; i < n; ++i) out[i] = c0[i] + a * c1[i] + a2 * c2[i] + a3 * c3[i];
  } else {
    const Eigen::Index jj = rows[j];
    const double *c0 = C[0].col(jj).data(), *c1 = C[1].col(jj).data(), *c2 = C[2].col(jj).data(), *c3 = C[3].col(jj).data();
    for (Eigen::Index i = 0; i < n; ++i) {
      const Eigen::Index r = rows[i];
      out[i] = c0[r] + a * c1[r] + a2 * c2[r] + a3 * c3[r];
    }
  }
  out[j] += series[j];
  formed[j] = 1;
  return out;
}

double body_travel_torque_Nm(const MeshInstant& in, const Eigen::VectorXd& x) {
  if (!in.cubic) return 0.0;
  const Eigen::MatrixXd* C = in.cubic;
  const double b2 = 2 * in.a, b3 = 3 * in.a * in.a;
  std::vector<int> loaded;
  for (Eigen::Index i = 0; i < x.size(); ++i)
    if (x[i] != 0.0) loaded.push_back(static_cast<int>(i));
  double sum = 0.0;
  for (int c : loaded) {
    const Eigen::Index j = in.rows.empty() ? c : in.rows[c];
    double col = 0.0;
    for (int r : loaded) {
      const Eigen::Index i = in.rows.empty() ? r : in.rows[r];
      col += x[r] * (C[1](i, j) + b2 * C[2](i, j) + b3 * C[3](i, j));
    }
    sum += x[c] * col;
  }
  return 0.5 * sum / in.h;
}

void prepare_intervals(MovingMesh& m) {
  const int S = static_cast<int>(m.phases.size());
  const int nb = static_cast<int>(m.station_q.size());
  const double h = m.pitch_rad / S;
  // Each phase's neighbours: a flank's (or station's) index in the previous and in the next phase, −1 where absent.
  std::vector<std::vector<int>> before(S), after(S);
  for (int s = 0; s < S; ++s) {
    const MeshPhase& P = m.phases[s];
    const MeshPhase& prev = m.phases[(s + S - 1) % S];
    const MeshPhase& next = m.phases[(s + 1) % S];
    after[s] = P.next;
    before[s].assign(P.key.size(), -1);
    for (std::size_t i = 0; i < prev.next.size(); ++i)
      if (prev.next[i] >= 0) before[s][prev.next[i]] = static_cast<int>(i);
    for (int j = 0; j < nb; ++j) {
      after[s].push_back(static_cast<int>(next.key.size()) + j);
      before[s].push_back(static_cast<int>(prev.key.size()) + j);
    }
  }
  // The slope in σ at a phase of a value known at the phases: the central difference where the entry is in both
  // neighbouring phases, one-sided where it is in one, zero where it is in neither. It belongs to the phase, so the two
  // segments that meet there share it.
  auto slope = [h](bool lo, bool hi, double down, double here, double up) {
    return hi && lo ? (up - down) / (2 * h) : hi ? (up - here) / h : lo ? (here - down) / h : 0.0;
  };
  std::vector<Eigen::MatrixXd> tangent(S);
  std::vector<std::vector<double>> q_tangent(S);
  for (int s = 0; s < S; ++s) {
    const MeshPhase& P = m.phases[s];
    const MeshPhase& prev = m.phases[(s + S - 1) % S];
    const MeshPhase& next = m.phases[(s + 1) % S];
    const auto n = P.A_body.rows();
    tangent[s].resize(n, n);
    for (Eigen::Index c = 0; c < n; ++c)
      for (Eigen::Index r = 0; r < n; ++r) {
        const int rl = before[s][r], cl = before[s][c], rh = after[s][r], ch = after[s][c];
        const bool lo = rl >= 0 && cl >= 0, hi = rh >= 0 && ch >= 0;
        tangent[s](r, c) = slope(lo, hi, lo ? prev.A_body(rl, cl) : 0.0, P.A_body(r, c), hi ? next.A_body(rh, ch) : 0.0);
      }
    q_tangent[s].resize(P.key.size());
    for (std::size_t i = 0; i < P.key.size(); ++i) {
      const int lo = before[s][i], hi = after[s][i];
      q_tangent[s][i] = slope(lo >= 0, hi >= 0, lo >= 0 ? prev.q_correction[lo] : 0.0, P.q_correction[i],
                              hi >= 0 ? next.q_correction[hi] : 0.0);
    }
  }
  // An interval's Hermite family need not stay positive definite: central slopes overshoot where an entry changes fast
  // between phases (a flank's own compliance as it enters or leaves the zone), and a flank present in one neighbouring
  // phase only has a one-sided slope beside the central ones. Seen on the designed size 17 (−6.6e-7 m/N against the
  // tooth pairs' 2e-8 in series): the contact problem then has no unique solution. Where an interval fails, the slopes
  // of A at its two phases are halved in the rows and columns that carry the failure (the entries of the most negative
  // eigenvector's within a quarter of its largest; once those are zero, every row of the interval), until it passes;
  // after six halvings a row's slopes are zero, and once every row's is, the segment is the convex blend
  // A0 + (3a² − 2a³)(A1 − A0) of two positive definite matrices, positive definite at every a. A phase's slopes stay shared with the neighbouring interval (C¹ kept), which is
  // checked again. The check: the matrix the contact problem solves at its least (each flank's tooth pair at its least
  // compliance over the interval; 0 for rigid teeth) at 15 points inside the interval (a = k/16), by Cholesky.
  // Each continuing flank's least tooth-pair compliance over the interval: the table's at the grid angles its
  // material angle passes (φ falls by h; the table's interpolant is monotone between them); 0 off the table.
  auto least_series = [&](int s) {
    const MeshPhase& P = m.phases[s];
    const FlankTable& t = m.table;
    Eigen::VectorXd out = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(P.continuing.size()));
    if (t.step_rad <= 0) return out;
    for (std::size_t c = 0; c < P.continuing.size(); ++c) {
      const int i = P.continuing[c], side = P.side[i];
      const double phi = wrap_phi(P.phi_rad[i], m.teeth_per_unknown);
      const auto lo = static_cast<int>(std::floor((phi - h - t.phi_start_rad) / t.step_rad - 1e-9));
      const auto hi = static_cast<int>(std::ceil((phi - t.phi_start_rad) / t.step_rad + 1e-9));
      if (lo < 0 || hi >= t.size()) continue;
      double least = std::numeric_limits<double>::infinity();
      for (int j = lo; j <= hi; ++j) least = std::min(least, t.compliance_m_per_N[side][j]);
      if (std::isfinite(least)) out[static_cast<Eigen::Index>(c)] = least;  // NaN anywhere: min is NaN, not finite
    }
    return out;
  };
  std::vector<Eigen::VectorXd> row_scale(S);  // per phase, per unknown: the factor on its row's and column's slopes
  for (int s = 0; s < S; ++s) row_scale[s] = Eigen::VectorXd::Ones(m.phases[s].A_body.rows());
  auto scaled = [&](int s) { return Eigen::MatrixXd(row_scale[s].asDiagonal() * tangent[s] * row_scale[s].asDiagonal()); };
  auto halve = [](double& x) {
    if (x <= 0) return false;
    x = x > 1.0 / 64 ? x / 2 : 0.0;
    return true;
  };
  std::vector<char> reduced(S, 0);
  for (;;) {
    bool changed = false, failed = false;
    for (int s = 0; s < S; ++s) {
      set_interval(m, s, scaled(s), scaled((s + 1) % S), q_tangent);
      const std::optional<Eigen::VectorXd> v = negative_direction(m.phases[s], least_series(s));
      if (!v) continue;
      failed = true;
      // v's entries: the interval's continuing flanks then the stations, in both end phases' numbering.
      const MeshPhase& P0 = m.phases[s];
      const int e = (s + 1) % S;
      const auto nc = static_cast<Eigen::Index>(P0.continuing.size());
      // The rows that carry the failure first; once their slopes are zero, every row of the interval.
      bool here = false;
      for (const double cut : {0.25 * v->cwiseAbs().maxCoeff(), 0.0}) {
        for (Eigen::Index k = 0; k < v->size(); ++k) {
          if (std::abs((*v)[k]) < cut) continue;
          const Eigen::Index i0 = k < nc ? P0.continuing[k] : P0.key.size() + (k - nc);
          const Eigen::Index i1 = k < nc ? P0.next[P0.continuing[k]] : m.phases[e].key.size() + (k - nc);
          if (halve(row_scale[s][i0])) here = reduced[s] = 1;
          if (halve(row_scale[e][i1])) here = reduced[e] = 1;
        }
        if (here) break;
      }
      changed = changed || here;
    }
    if (!failed) break;
    if (!changed)  // every slope of a failing interval is zero already: a phase's own matrix is not positive definite
      throw InputError("dynamics: the rim's compliance at a generator phase is not positive definite");
  }
  m.reduced_phases = static_cast<int>(std::count(reduced.begin(), reduced.end(), 1));
}

int solve_lcp(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, Eigen::VectorXd& x, std::vector<char>& active) {
  return solve_lcp([&A](int j) { return A.col(j).data(); }, b, x, active);
}

int solve_lcp(const std::function<const double*(int)>& column, const Eigen::VectorXd& b, Eigen::VectorXd& x,
              std::vector<char>& active) {
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
        const double* col = column(F[c]);
        for (int r = 0; r < nF; ++r) AF(r, c) = col[F[r]];
      }
      const Eigen::VectorXd xF = AF.llt().solve(bF);
      for (int c = 0; c < nF; ++c) x[F[c]] = xF[c];
    }
    w = b;
    for (int j : F) w += x[j] * Eigen::Map<const Eigen::VectorXd>(column(j), n);
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
