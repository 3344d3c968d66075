#include "fem/fourier_element.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include "common/constants.hpp"
#include "common/error.hpp"

namespace sw {
namespace fourier {
namespace {
}  // namespace

Mat6x2 coords(const SectionMesh& s, std::size_t e) {
  Mat6x2 X;
  for (int a = 0; a < 6; ++a) X.row(a) = s.nodes.row(s.triangles[e][a]);
  return X;
}

Mat6 elasticity(const Material& m) {
  const double E = m.youngs_modulus_Pa, nu = m.poisson_ratio;
  const double lambda = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
  Eigen::Matrix<double, 6, 6> D = Eigen::Matrix<double, 6, 6>::Zero();
  D.topLeftCorner<3, 3>().setConstant(lambda);
  D.topLeftCorner<3, 3>().diagonal().array() += 2 * mu;
  D(3, 3) = D(4, 4) = D(5, 5) = mu;
  return D;
}

Mat6 tooth_layer_elasticity(const Material& m, double solidity, double shear_factor) {
  const double E = m.youngs_modulus_Pa, nu = m.poisson_ratio, G = E / (2 * (1 + nu));
  const double plane = solidity * E / (1 - nu * nu);
  Mat6 D = Mat6::Zero();
  D(0, 0) = D(1, 1) = plane;
  D(0, 1) = D(1, 0) = nu * plane;
  D(3, 3) = solidity * G;
  D(2, 2) = kToothLayerResidual * E;
  D(4, 4) = solidity * G;
  D(5, 5) = shear_factor * solidity * G;
  return D;
}

Mat6 elasticity_at(const SectionMesh& s, std::size_t e, const Material& m, double r_m) {
  if (s.region[e] != kToothLayerRegion) return elasticity(m);
  if (!s.tooth_layer) throw std::logic_error("a tooth-layer triangle in a section without the layer's solidity");
  return tooth_layer_elasticity(m, s.tooth_layer->at(r_m), s.tooth_layer->shear_factor);
}

ShapePoint shape_point(const Mat6x2& X, double xi, double eta) {
  ShapePoint p;
  p.N = t6_shape(xi, eta);
  const Eigen::Matrix<double, 2, 6> dN = t6_shape_derivatives(xi, eta);
  const Eigen::Matrix2d J = dN * X;  // rows d/dξ, d/dη; columns r, z
  p.det = J.determinant();
  p.dN = J.inverse() * dN;
  p.r = p.N.dot(X.col(0));
  return p;
}

StrainPoint strain_matrix(const Mat6x2& X, double xi, double eta, int n) {
  const ShapePoint sp = shape_point(X, xi, eta);
  const auto& N = sp.N;
  const auto& G = sp.dN;
  StrainPoint p;
  p.det = sp.det;
  p.r = sp.r;
  const double ir = 1.0 / p.r;
  p.B.setZero();
  for (int i = 0; i < 6; ++i) {
    const double Nr = G(0, i), Nz = G(1, i), Ni = N[i];
    const int a = 3 * i, b = a + 1, c = a + 2;
    p.B(0, a) = Nr;
    p.B(1, c) = Nz;
    p.B(2, a) = Ni * ir;
    p.B(2, b) = n * Ni * ir;
    p.B(3, a) = Nz;
    p.B(3, c) = Nr;
    p.B(4, a) = -n * Ni * ir;
    p.B(4, b) = Nr - Ni * ir;
    p.B(5, b) = Nz;
    p.B(5, c) = -n * Ni * ir;
  }
  return p;
}

double theta_weight(int n) { return n == 0 ? 2 * kPi : kPi; }

HarmonicDofs number_dofs(std::size_t n_nodes, int n, const std::vector<bool>& fixed, const std::vector<bool>& axis) {
  HarmonicDofs d;
  d.eq.assign(3 * n_nodes, -1);
  d.sign.assign(3 * n_nodes, 1.0);
  for (std::size_t i = 0; i < n_nodes; ++i) {
    bool free_dof[3] = {!fixed[3 * i], !fixed[3 * i + 1], !fixed[3 * i + 2]};
    if (axis[i]) {
      if (n == 0) free_dof[0] = free_dof[1] = false;
      else if (n == 1) free_dof[2] = false;  // and b = −a below
      else free_dof[0] = free_dof[1] = free_dof[2] = false;
    }
    for (int k = 0; k < 3; ++k) {
      if (!free_dof[k]) continue;
      if (axis[i] && n == 1 && k == 1) {  // b = −a: single-valued displacement on the axis
        if (d.eq[3 * i] >= 0) {
          d.eq[3 * i + 1] = d.eq[3 * i];
          d.sign[3 * i + 1] = -1.0;
        }
        continue;
      }
      d.eq[3 * i + k] = d.n_eq++;
      d.node_of_eq.push_back(static_cast<std::int64_t>(i));
    }
  }
  return d;
}

std::vector<bool> axis_nodes(const SectionMesh& s) {
  std::vector<bool> axis(s.n_nodes());
  for (std::size_t i = 0; i < s.n_nodes(); ++i) axis[i] = s.nodes(static_cast<Eigen::Index>(i), 0) <= 1e-12;
  return axis;
}

Eigen::VectorXd to_equations(const HarmonicDofs& d, const Eigen::MatrixXd& F) {
  Eigen::VectorXd b = Eigen::VectorXd::Zero(d.n_eq);
  for (Eigen::Index i = 0; i < F.rows(); ++i)
    for (int k = 0; k < 3; ++k)
      if (d.eq[3 * i + k] >= 0) b[d.eq[3 * i + k]] += d.sign[3 * i + k] * F(i, k);
  return b;
}

Eigen::MatrixXd to_nodes(const HarmonicDofs& d, const Eigen::VectorXd& x, Eigen::MatrixXd fixed_values) {
  for (Eigen::Index i = 0; i < fixed_values.rows(); ++i)
    for (int k = 0; k < 3; ++k)
      if (d.eq[3 * i + k] >= 0) fixed_values(i, k) = d.sign[3 * i + k] * x[d.eq[3 * i + k]];
  return fixed_values;
}

ElementPolynomial element_polynomial(const Mat6x2& X, const std::function<Mat6(double r_m)>& D_at) {
  ElementPolynomial p;
  p.k0.setZero();
  p.k1.setZero();
  p.k2.setZero();
  for (int k = 0; k < 7; ++k) {
    const StrainPoint a = strain_matrix(X, kRule.xi[k], kRule.eta[k], 0);
    const StrainPoint b = strain_matrix(X, kRule.xi[k], kRule.eta[k], 1);
    const Mat6x18 B0 = a.B, B1 = b.B - a.B;
    const double w = kRule.w[k] * std::abs(a.det) * a.r;
    const Mat6 D = D_at(a.r);
    const Mat6x18 DB0 = D * B0, DB1 = D * B1;
    p.k0.noalias() += w * (B0.transpose() * DB0);
    const Mat18 cross = B0.transpose() * DB1;
    p.k1.noalias() += w * (cross + cross.transpose());
    p.k2.noalias() += w * (B1.transpose() * DB1);
  }
  return p;
}

std::vector<ElementPolynomial> element_polynomials(const SectionMesh& s, const Material& m) {
  const Mat6 D = elasticity(m);
  std::vector<ElementPolynomial> out(s.triangles.size());
  for (std::size_t e = 0; e < s.triangles.size(); ++e) {
    if (s.region[e] == kToothLayerRegion)
      out[e] = element_polynomial(coords(s, e), [&](double r) { return elasticity_at(s, e, m, r); });
    else
      out[e] = element_polynomial(coords(s, e), [&](double) { return D; });
  }
  return out;
}

GlobalPolynomial assemble_polynomial(const SectionMesh& s, const std::vector<ElementPolynomial>& poly, HarmonicDofs d) {
  GlobalPolynomial g;
  g.k0 = assemble(s, d, [&](std::size_t e) -> const Mat18& { return poly[e].k0; });
  g.v1 = assemble(s, d, [&](std::size_t e) -> const Mat18& { return poly[e].k1; }).value;
  g.v2 = assemble(s, d, [&](std::size_t e) -> const Mat18& { return poly[e].k2; }).value;
  g.dofs = std::move(d);
  return g;
}

Probe probe_at(const SectionMesh& s, const Eigen::Vector2d& rz) {
  const auto [e, q] = locate_in_section(s, rz);
  if (e < 0)
    throw InputError("the point r = " + std::to_string(rz[0] * 1e3) + " mm, z = " + std::to_string(rz[1] * 1e3) +
                     " mm lies outside the flexspline's section");
  Probe p;
  p.node = s.triangles[static_cast<std::size_t>(e)];
  p.weight = t6_shape(q[0], q[1]);
  return p;
}

Probe probe_node(int i) {
  Probe p;
  p.node.fill(i);
  p.weight.setZero();
  p.weight[0] = 1;
  return p;
}

Eigen::Vector3d displacement_at(const HarmonicField& f, const Probe& p, const Trig& trig) {
  Eigen::Vector3d u = Eigen::Vector3d::Zero();
  for (std::size_t n = 0; n < f.sym.size(); ++n) {
    if (f.sym[n].size() == 0) continue;
    Eigen::RowVector3d as = Eigen::RowVector3d::Zero(), aa = Eigen::RowVector3d::Zero();
    for (int j = 0; j < 6; ++j)
      if (p.weight[j] != 0) {
        as += p.weight[j] * f.sym[n].row(p.node[j]);
        aa += p.weight[j] * f.anti[n].row(p.node[j]);
      }
    const double c = trig.c[n], sn = trig.s[n];
    u[0] += as[0] * c + aa[0] * sn;
    u[1] += as[1] * sn - aa[1] * c;
    u[2] += as[2] * c + aa[2] * sn;
  }
  return u;
}

Eigen::Vector3d displacement_at(const HarmonicField& f, const Probe& p, double theta) {
  return displacement_at(f, p, Trig(theta, f.sym.size()));
}

Eigen::Vector3d to_cartesian(const Eigen::Vector3d& cyl, double theta) {
  const double c = std::cos(theta), s = std::sin(theta);
  return {cyl[0] * c - cyl[1] * s, cyl[0] * s + cyl[1] * c, cyl[2]};
}

void nodal_stress(const SectionMesh& s, const Material& m, const HarmonicField& f, std::vector<Eigen::MatrixXd>& sym,
                  std::vector<Eigen::MatrixXd>& anti) {
  const Eigen::Index nn = static_cast<Eigen::Index>(s.n_nodes());
  sym.assign(f.sym.size(), Eigen::MatrixXd());
  anti.assign(f.anti.size(), Eigen::MatrixXd());
  // A node the body and the tooth layer share takes the body's stress only: the rim's outer surface is the body's
  // (the layer's homogenised stress is a tooth's times its solidity, no stress of the surface).
  std::vector<bool> in_body(s.n_nodes(), false);
  for (std::size_t e = 0; e < s.triangles.size(); ++e)
    if (s.region[e] != kToothLayerRegion)
      for (const int i : s.triangles[e]) in_body[static_cast<std::size_t>(i)] = true;
  const auto counts = [&](std::size_t e, int node) {
    return s.region[e] != kToothLayerRegion || !in_body[static_cast<std::size_t>(node)];
  };
  Eigen::VectorXd weight = Eigen::VectorXd::Zero(nn);
  std::vector<double> area(s.triangles.size());
  for (std::size_t e = 0; e < s.triangles.size(); ++e) {
    const Mat6x2 X = coords(s, e);
    area[e] = 0;
    for (int k = 0; k < 7; ++k) area[e] += kRule.w[k] * std::abs((t6_shape_derivatives(kRule.xi[k], kRule.eta[k]) * X).determinant());
    for (int a = 0; a < 6; ++a)
      if (counts(e, s.triangles[e][a])) weight[s.triangles[e][a]] += area[e];
  }
  for (std::size_t n = 0; n < f.sym.size(); ++n) {
    if (f.sym[n].size() == 0) continue;
    sym[n] = Eigen::MatrixXd::Zero(nn, 6);
    anti[n] = Eigen::MatrixXd::Zero(nn, 6);
    for (std::size_t e = 0; e < s.triangles.size(); ++e) {
      const Mat6x2 X = coords(s, e);
      const auto& t = s.triangles[e];
      Eigen::Matrix<double, 18, 1> us, ua;
      for (int a = 0; a < 6; ++a) {
        us.segment<3>(3 * a) = f.sym[n].row(t[a]).transpose();
        ua.segment<3>(3 * a) = f.anti[n].row(t[a]).transpose();
      }
      for (int a = 0; a < 6; ++a) {
        if (!counts(e, t[a])) continue;
        double xi = kNodeXi[a], eta = kNodeEta[a];
        if (X(a, 0) <= 1e-12) {
          xi = (1 - 1e-6) * xi + 1e-6 / 3;
          eta = (1 - 1e-6) * eta + 1e-6 / 3;
        }
        const StrainPoint p = strain_matrix(X, xi, eta, static_cast<int>(n));
        const Mat6 D = elasticity_at(s, e, m, p.r);
        sym[n].row(t[a]) += area[e] * (D * (p.B * us)).transpose();
        anti[n].row(t[a]) += area[e] * (D * (p.B * ua)).transpose();
      }
    }
    for (Eigen::Index i = 0; i < nn; ++i) {
      sym[n].row(i) /= weight[i];
      anti[n].row(i) /= weight[i];
    }
  }
}

double hoop_at(const std::vector<Eigen::MatrixXd>& sym, const std::vector<Eigen::MatrixXd>& anti, const Probe& p,
               const Trig& trig) {
  double v = 0;
  for (std::size_t n = 0; n < sym.size(); ++n) {
    if (sym[n].size() == 0) continue;
    double as = 0, aa = 0;
    for (int j = 0; j < 6; ++j)
      if (p.weight[j] != 0) {
        as += p.weight[j] * sym[n](p.node[j], 2);
        aa += p.weight[j] * anti[n](p.node[j], 2);
      }
    v += as * trig.c[n] + aa * trig.s[n];
  }
  return v;
}

Eigen::Matrix<double, 1, 6> cartesian_stress(const Eigen::Matrix<double, 6, 1>& c, double theta) {
  const double co = std::cos(theta), si = std::sin(theta);
  const double sr = c[0], sz = c[1], st = c[2], trz = c[3], trt = c[4], ttz = c[5];
  Eigen::Matrix<double, 1, 6> v;
  v << sr * co * co + st * si * si - 2 * trt * si * co, sr * si * si + st * co * co + 2 * trt * si * co, sz,
      trz * si + ttz * co, trz * co - ttz * si, (sr - st) * si * co + trt * (co * co - si * si);
  return v;
}

/// The section revolved into TET10: nodes = every section node at 2·sectors angular stations (corners at even
/// stations are the prisms' corners; odd stations and midside nodes give every TET10 midside node exactly), each prism
/// (triangle × sector) split into three tets by Dompierre's rule on global corner numbers (conforming). Tets that
/// degenerate on the axis are dropped. Grid node k·n_section_nodes + i is section node i at station k (θ = kπ/sectors).
TetMesh revolve_section(const SectionMesh& s, int sectors) {
  const int stations = 2 * sectors;
  const long ns = static_cast<long>(s.n_nodes());
  TetMesh g;
  g.nodes.resize(ns * stations, 3);
  for (int k = 0; k < stations; ++k) {
    const double t = kPi * k / sectors;
    for (long i = 0; i < ns; ++i)
      g.nodes.row(k * ns + i) << s.nodes(i, 0) * std::cos(t), s.nodes(i, 0) * std::sin(t), s.nodes(i, 1);
  }
  std::map<std::pair<int, int>, int> mid_of_edge;  // section corner pair -> midside node
  for (const auto& t : s.triangles)
    for (int e = 0; e < 3; ++e) {
      const int a = t[e], b = t[(e + 1) % 3];
      mid_of_edge[{std::min(a, b), std::max(a, b)}] = t[3 + e];
    }
  auto station = [&](long id) { return static_cast<int>(id / ns); };
  auto section_node = [&](long id) { return static_cast<int>(id % ns); };
  auto midside = [&](long p, long q) -> int {
    const int kp = station(p), kq = station(q), ip = section_node(p), iq = section_node(q);
    int k;  // station of the midpoint
    if (kp == kq) k = kp;
    else {
      const int lo = std::min(kp, kq), hi = std::max(kp, kq);
      k = (hi - lo == 2) ? lo + 1 : (hi + 1) % stations;  // the wrap: stations 0 and stations − 2
    }
    const int m = ip == iq ? ip : mid_of_edge.at({std::min(ip, iq), std::max(ip, iq)});
    return static_cast<int>(static_cast<long>(k) * ns + m);
  };
  static constexpr int kRot[6][6] = {{0, 1, 2, 3, 4, 5}, {1, 2, 0, 4, 5, 3}, {2, 0, 1, 5, 3, 4},
                                     {3, 5, 4, 0, 2, 1}, {4, 3, 5, 1, 0, 2}, {5, 4, 3, 2, 1, 0}};
  for (std::size_t e = 0; e < s.triangles.size(); ++e) {
    const auto& t = s.triangles[e];
    for (int j = 0; j < sectors; ++j) {
      const long k0 = 2L * j, k1 = (2L * j + 2) % stations;
      const long v[6] = {k0 * ns + t[0], k0 * ns + t[1], k0 * ns + t[2], k1 * ns + t[0], k1 * ns + t[1], k1 * ns + t[2]};
      const int smallest = static_cast<int>(std::min_element(v, v + 6) - v);
      long w[6];
      for (int a = 0; a < 6; ++a) w[a] = v[kRot[smallest][a]];
      std::array<std::array<long, 4>, 3> tets;
      if (std::min(w[1], w[5]) < std::min(w[2], w[4]))
        tets = {{{w[0], w[1], w[2], w[5]}, {w[0], w[1], w[5], w[4]}, {w[0], w[4], w[5], w[3]}}};
      else
        tets = {{{w[0], w[1], w[2], w[4]}, {w[0], w[4], w[2], w[5]}, {w[0], w[4], w[5], w[3]}}};
      for (auto c : tets) {
        const Eigen::Vector3d p0 = g.nodes.row(c[0]), p1 = g.nodes.row(c[1]), p2 = g.nodes.row(c[2]),
                              p3 = g.nodes.row(c[3]);
        double vol = (p1 - p0).cross(p2 - p0).dot(p3 - p0);
        const double scale = std::pow((p1 - p0).norm() * (p2 - p0).norm() * (p3 - p0).norm(), 1.0);
        if (std::abs(vol) <= 1e-9 * scale) continue;
        if (vol < 0) std::swap(c[1], c[2]);
        std::array<int, 10> tet;
        for (int a = 0; a < 4; ++a) tet[a] = static_cast<int>(c[a]);
        const int edges[6][2] = {{0, 1}, {1, 2}, {0, 2}, {0, 3}, {1, 3}, {2, 3}};
        for (int a = 0; a < 6; ++a) tet[4 + a] = midside(c[edges[a][0]], c[edges[a][1]]);
        g.tets.push_back(tet);
        g.region.push_back(s.region[e]);
      }
    }
  }
  return g;
}

Eigen::VectorXd revolved_displacement(const SectionMesh& s, const HarmonicField& f, int sectors) {
  const Eigen::Index ns = static_cast<Eigen::Index>(s.n_nodes());
  Eigen::VectorXd U(3 * 2 * sectors * ns);
  for (int k = 0; k < 2 * sectors; ++k) {
    const double theta = kPi * k / sectors;
    const Trig trig(theta, f.sym.size());
    for (Eigen::Index i = 0; i < ns; ++i)
      U.segment<3>(3 * (k * ns + i)) = to_cartesian(displacement_at(f, probe_node(static_cast<int>(i)), trig), theta);
  }
  return U;
}

}  // namespace fourier

using namespace fourier;

Eigen::Vector3d HarmonicField::displacement(const SectionMesh& s, long e, const Eigen::Vector2d& q,
                                            double theta) const {
  Probe p;
  p.node = s.triangles[static_cast<std::size_t>(e)];
  p.weight = t6_shape(q[0], q[1]);
  return displacement_at(*this, p, theta);
}

HarmonicField& HarmonicField::operator+=(const HarmonicField& o) {
  if (sym.size() < o.sym.size()) {
    sym.resize(o.sym.size());
    anti.resize(o.anti.size());
  }
  for (std::size_t n = 0; n < o.sym.size(); ++n) {
    if (o.sym[n].size() == 0) continue;
    if (sym[n].size() == 0) {
      sym[n] = o.sym[n];
      anti[n] = o.anti[n];
    } else {
      sym[n] += o.sym[n];
      anti[n] += o.anti[n];
    }
  }
  return *this;
}

HarmonicField HarmonicField::operator*(double k) const {
  HarmonicField f = *this;
  for (auto& m : f.sym) m *= k;
  for (auto& m : f.anti) m *= k;
  return f;
}

}  // namespace sw
