#include "contact/hat_patterns.hpp"

#include <cmath>

namespace sw {

double hat_moment(int n, double h) {
  return n == 0 ? h : 2 * (1 - std::cos(n * h)) / (static_cast<double>(n) * n * h);
}

HatAmplitudes amplitudes(const FlankPattern& p, double h, double sum_S, double sum_rS) {
  const double c = p.stations_rad.front();
  const double F_r = p.scale * p.force_dir.dot(Eigen::Vector2d(std::cos(c), std::sin(c)));
  const double F_t = p.scale * p.force_dir.dot(Eigen::Vector2d(-std::sin(c), std::cos(c)));
  HatAmplitudes a;
  a.radial = F_r / (hat_moment(1, h) * sum_S);
  a.tangential = p.contact_radius_m * F_t / (h * sum_rS);
  a.couple = (F_t - a.tangential * hat_moment(1, h) * sum_S) / (2 * hat_moment(1, h / 2) * std::sin(h / 2) * sum_S);
  return a;
}

void add_flank(Moments& m, Eigen::Index row, Eigen::Index col, const FlankPattern& p, const HatAmplitudes& a,
               double h) {
  for (std::size_t n = 0; n < m.sym.size(); ++n) {
    const int k = static_cast<int>(n);
    const double Hh = hat_moment(k, h), Hq = hat_moment(k, h / 2);
    for (const double c : p.stations_rad) {
      const double cs = std::cos(k * c), sn = std::sin(k * c);
      const double cp = std::cos(k * (c + h / 2)), cm = std::cos(k * (c - h / 2));
      const double sp = std::sin(k * (c + h / 2)), sm = std::sin(k * (c - h / 2));
      m.sym[n](row, col) += a.radial * Hh * cs + a.couple * Hq * (cp - cm);
      m.anti[n](row, col) += a.radial * Hh * sn + a.couple * Hq * (sp - sm);
      m.sym[n](row, col + 1) += a.tangential * Hh * sn;
      m.anti[n](row, col + 1) -= a.tangential * Hh * cs;
    }
  }
}

FlankHats add_flanks(Moments& m, const std::vector<FlankPattern>& patterns, int slices,
                     const std::vector<const BandResponse*>& r, const Eigen::VectorXd& radius, double h) {
  FlankHats hats;
  for (std::size_t j = 0; j < patterns.size(); ++j) {
    const FlankPattern& p = patterns[j];
    const Eigen::Index b = p.slice >= 0 && slices > 1 ? 1 + p.slice : 0;
    const Eigen::VectorXd& S = r[static_cast<std::size_t>(b)]->S;
    hats.amplitude.push_back(amplitudes(p, h, S.sum(), radius.dot(S)));
    hats.band.push_back(b);
    add_flank(m, static_cast<Eigen::Index>(j), 2 * b, p, hats.amplitude.back(), h);
  }
  return hats;
}

Eigen::MatrixXd gram(const std::vector<const BandResponse*>& r, std::size_t n) {
  const Eigen::Index B = static_cast<Eigen::Index>(r.size());
  if (r.front()->Ur[n].size() == 0) return {};
  Eigen::MatrixXd G(2 * B, 2 * B);
  for (Eigen::Index a = 0; a < B; ++a)
    for (Eigen::Index b = 0; b < B; ++b)
      for (int l = 0; l < 2; ++l) {
        const Eigen::MatrixXd& U = l == 0 ? r[b]->Ur[n] : r[b]->Ut[n];
        for (int k = 0; k < 2; ++k) G(2 * a + k, 2 * b + l) = r[a]->S.dot(U.col(k));
      }
  return G;
}

Eigen::MatrixXd influence_of(const Moments& m, const std::vector<const BandResponse*>& r) {
  const Eigen::Index rows = m.sym.front().rows();
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(rows, rows);
  for (std::size_t n = 0; n < m.sym.size(); ++n) {
    const Eigen::MatrixXd G = gram(r, n);
    if (G.size() == 0) continue;
    A.noalias() += m.sym[n] * G * m.sym[n].transpose() + m.anti[n] * G * m.anti[n].transpose();
  }
  return 0.5 * (A + A.transpose()).eval();
}

HarmonicField field_of(const Moments& m, const std::vector<const BandResponse*>& r, const Eigen::VectorXd& x) {
  HarmonicField u;
  u.sym.assign(m.sym.size(), {});
  u.anti.assign(m.sym.size(), {});
  for (std::size_t n = 0; n < m.sym.size(); ++n) {
    if (r.front()->Ur[n].size() == 0) continue;
    const Eigen::VectorXd ws = m.sym[n].transpose() * x, wa = m.anti[n].transpose() * x;
    u.sym[n] = Eigen::MatrixXd::Zero(r.front()->Ur[n].rows(), 3);
    u.anti[n] = u.sym[n];
    for (std::size_t b = 0; b < r.size(); ++b) {
      const Eigen::Index i = 2 * static_cast<Eigen::Index>(b);
      u.sym[n] += ws[i] * r[b]->Ur[n] + ws[i + 1] * r[b]->Ut[n];
      u.anti[n] += wa[i] * r[b]->Ur[n] + wa[i + 1] * r[b]->Ut[n];
    }
  }
  return u;
}

Eigen::MatrixXd anti0_loads(const Moments& m, const std::vector<const BandResponse*>& r, const Eigen::VectorXd& x) {
  Eigen::MatrixXd anti0 = Eigen::MatrixXd::Zero(r.front()->S.size(), 3);
  const Eigen::VectorXd w0 = m.anti[0].transpose() * x;
  for (std::size_t b = 0; b < r.size(); ++b) {
    anti0.col(0) += w0[2 * static_cast<Eigen::Index>(b)] * r[b]->S;
    anti0.col(1) += w0[2 * static_cast<Eigen::Index>(b) + 1] * r[b]->S;
  }
  return anti0;
}

}  // namespace sw
