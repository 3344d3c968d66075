#include "fem/rib_cell.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include <Eigen/Core>
#include <Eigen/LU>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "common/interpolate.hpp"

namespace sw {
namespace {

/// A node of the cell: (s, r), r = 0 at the root, negative in the rim.
struct CellNode {
  double s, r;
};

/// A bilinear quadrilateral, nodes counter-clockwise in (s, r); a quad across the period's seam adds the pitch to the
/// s of its wrapped nodes.
struct CellQuad {
  std::array<int, 4> nodes{};
  std::array<double, 4> s_shift{};
};

/// The cell's mesh and which nodes are held.
struct CellMesh {
  std::vector<CellNode> nodes;
  std::vector<CellQuad> quads;
  std::vector<bool> held;
  double rim_area = 0;  ///< of the quads below the root
  double rib_area = 0;  ///< of the quads above it
};

/// The quad's corners in (s, r), its seam shift applied.
Eigen::Matrix<double, 4, 2> corners(const CellMesh& m, const CellQuad& q) {
  Eigen::Matrix<double, 4, 2> X;
  for (int a = 0; a < 4; ++a) X.row(a) << m.nodes[q.nodes[a]].s + q.s_shift[a], m.nodes[q.nodes[a]].r;
  return X;
}

double cell_quad_area(const CellMesh& m, const CellQuad& q) {
  const Eigen::Matrix<double, 4, 2> X = corners(m, q);
  double a = 0;
  for (int i = 0; i < 4; ++i) a += X(i, 0) * X((i + 1) % 4, 1) - X((i + 1) % 4, 0) * X(i, 1);
  return 0.5 * a;
}

/// The rib on rows of constant height (its width mapped, s = ξ·w(h)); under it, when the rim is there, the rim on
/// columns of constant s, periodic: the spaces' floor beside the root, then the root's nodes, shared with the rib.
CellMesh cell_mesh(const RibCell& c) {
  CellMesh m;
  const int ns = c.cells_across;
  const double h = c.height_m.back(), w0 = c.width_m.front(), P = c.pitch_m;
  const double size = w0 / ns;
  const int nr = std::max(static_cast<int>(c.height_m.size()) - 1, static_cast<int>(std::ceil(h / size)));
  auto add = [&](double s, double r) {
    m.nodes.push_back({s, r});
    m.held.push_back(false);
    return static_cast<int>(m.nodes.size()) - 1;
  };
  // The root's row and the rim below it.
  std::vector<int> root(static_cast<std::size_t>(ns + 1));
  if (c.rim_thickness_m > 0) {
    const double gap = 0.5 * (P - w0);
    const int ng = gap > 1e-9 * P ? std::max(1, static_cast<int>(std::ceil(gap / size))) : 0;
    const int nc = ns + 2 * ng;  // columns around the period (periodic: column nc is column 0)
    std::vector<double> col_s(static_cast<std::size_t>(nc));
    for (int k = 0; k < nc; ++k)
      col_s[k] = k < ng ? -0.5 * P + gap * k / ng : k <= ng + ns ? -0.5 * w0 + w0 * (k - ng) / ns
                                                                 : 0.5 * w0 + gap * (k - ng - ns) / ng;
    const int nt = std::max(2, static_cast<int>(std::ceil(c.rim_thickness_m / size)));
    std::vector<std::vector<int>> rows(static_cast<std::size_t>(nt + 1));
    for (int i = 0; i <= nt; ++i)
      for (int k = 0; k < nc; ++k) rows[i].push_back(add(col_s[k], -c.rim_thickness_m * (nt - i) / nt));
    for (int i = 0; i < nt; ++i)
      for (int k = 0; k < nc; ++k) {
        const int k1 = (k + 1) % nc;
        const double wrap = k1 == 0 ? P : 0.0;
        m.quads.push_back({{rows[i][k], rows[i][k1], rows[i + 1][k1], rows[i + 1][k]}, {0.0, wrap, wrap, 0.0}});
        m.rim_area += cell_quad_area(m, m.quads.back());
      }
    for (int j = 0; j <= ns; ++j) root[j] = rows[nt][(ng + j) % nc];
  } else {
    for (int j = 0; j <= ns; ++j) {
      root[j] = add(-0.5 * w0 + w0 * j / ns, 0.0);
      m.held[root[j]] = true;
    }
  }
  // The rib: a root node shared across the seam (a rib as wide as the pitch) keeps its own s by the shift.
  std::vector<int> below = root;
  for (int i = 1; i <= nr; ++i) {
    const double r = h * i / nr, w = interpolate_clamped(c.height_m, c.width_m, r);
    std::vector<int> row;
    for (int j = 0; j <= ns; ++j) row.push_back(add(-0.5 * w + w * j / ns, r));
    for (int j = 0; j < ns; ++j) {
      const bool seam = i == 1 && j + 1 == ns && below[ns] == below[0];
      m.quads.push_back({{below[j], below[j + 1], row[j + 1], row[j]}, {0.0, seam ? P : 0.0, 0.0, 0.0}});
      m.rib_area += cell_quad_area(m, m.quads.back());
    }
    below = row;
  }
  return m;
}

}  // namespace

double rib_shear_factor(const RibCell& c) {
  const std::size_t n = c.height_m.size();
  if (n < 2 || c.width_m.size() != n || c.height_m.front() != 0.0 || c.pitch_m <= 0 || c.rim_thickness_m < 0 ||
      c.cells_across < 1)
    throw std::invalid_argument("rib_shear_factor: a cell needs heights from 0, a width per height and a pitch");
  for (std::size_t k = 0; k < n; ++k)
    if (c.width_m[k] <= 0 || c.width_m[k] > c.pitch_m * (1 + 1e-12) || (k > 0 && c.height_m[k] <= c.height_m[k - 1]))
      throw std::invalid_argument("rib_shear_factor: widths in (0, pitch] on increasing heights");
  const CellMesh m = cell_mesh(c);

  // Unknowns: the fluctuation w at every node not held; the rim's constant is pinned at its first node (w is
  // determined up to a constant there, and the energy does not see it).
  std::vector<int> eq(m.nodes.size(), -1);
  int neq = 0;
  for (std::size_t i = 0; i < m.nodes.size(); ++i)
    if (!m.held[i] && !(c.rim_thickness_m > 0 && i == 0)) eq[i] = neq++;

  // U = ½∫ (1 + w_s)² + w_r² at unit shear (G = 1): K w = −b, b_i = ∫ ∂N_i/∂s, and at the minimum U = ½A − ½ wᵀK w.
  std::vector<Eigen::Triplet<double>> kt;
  Eigen::VectorXd b = Eigen::VectorXd::Zero(neq);
  const double g = 1.0 / std::sqrt(3.0);
  const double xi[4] = {-1, 1, 1, -1}, eta[4] = {-1, -1, 1, 1};
  for (const CellQuad& quad : m.quads) {
    const auto& q = quad.nodes;
    const Eigen::Matrix<double, 4, 2> X = corners(m, quad);
    Eigen::Matrix4d ke = Eigen::Matrix4d::Zero();
    Eigen::Vector4d be = Eigen::Vector4d::Zero();
    for (const double gx : {-g, g})
      for (const double gy : {-g, g}) {
        Eigen::Matrix<double, 2, 4> dN;
        for (int a = 0; a < 4; ++a) {
          dN(0, a) = 0.25 * xi[a] * (1 + eta[a] * gy);
          dN(1, a) = 0.25 * eta[a] * (1 + xi[a] * gx);
        }
        const Eigen::Matrix2d J = dN * X;
        const double det = J.determinant();
        if (det <= 0) throw std::invalid_argument("rib_shear_factor: an inverted cell (widths too steep)");
        const Eigen::Matrix<double, 2, 4> B = J.inverse() * dN;  // rows ∂/∂s, ∂/∂r
        ke += B.transpose() * B * det;
        be += B.row(0).transpose() * det;
      }
    for (int a = 0; a < 4; ++a) {
      const int ia = eq[q[a]];
      if (ia < 0) continue;
      b[ia] += be[a];
      for (int k = 0; k < 4; ++k)
        if (eq[q[k]] >= 0) kt.emplace_back(ia, eq[q[k]], ke(a, k));
    }
  }
  Eigen::SparseMatrix<double> K(neq, neq);
  K.setFromTriplets(kt.begin(), kt.end());
  // A few thousand unknowns: Eigen's own sparse Cholesky is enough (the drive's systems use CHOLMOD).
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(K);
  if (solver.info() != Eigen::Success) throw std::invalid_argument("rib_shear_factor: the cell's system is singular");
  const Eigen::VectorXd w = solver.solve(-b);
  const double energy = 0.5 * (m.rim_area + m.rib_area) - 0.5 * w.dot(K * w);
  return (energy - 0.5 * m.rim_area) / (0.5 * m.rib_area);
}

}  // namespace sw
