#include "fem/assembly.hpp"

#include <algorithm>
#include <stdexcept>

#include "fem/elasticity.hpp"

namespace sw {

DofMap make_dof_map(const std::vector<bool>& fixed) {
  DofMap d;
  d.equation.resize(fixed.size());
  for (std::size_t i = 0; i < fixed.size(); ++i) d.equation[i] = fixed[i] ? -1 : d.n_equations++;
  return d;
}

std::vector<std::int64_t> equation_nodes(const DofMap& dofs) {
  std::vector<std::int64_t> node(dofs.n_equations);
  for (std::size_t g = 0; g < dofs.equation.size(); ++g)
    if (dofs.equation[g] >= 0) node[dofs.equation[g]] = static_cast<std::int64_t>(g / 3);
  return node;
}

Eigen::Matrix<double, 10, 3> element_coordinates(const TetMesh& mesh, std::size_t e) {
  Eigen::Matrix<double, 10, 3> x;
  for (int a = 0; a < 10; ++a) x.row(a) = mesh.nodes.row(mesh.tets[e][a]);
  return x;
}

namespace {

/// Node → elements incidence in compressed form.
struct Incidence {
  std::vector<std::int64_t> start;
  std::vector<std::int64_t> element;
};

Incidence node_elements(const TetMesh& mesh) {
  Incidence inc;
  const std::size_t n = mesh.n_nodes();
  inc.start.assign(n + 1, 0);
  for (const auto& t : mesh.tets)
    for (int v : t) ++inc.start[v + 1];
  for (std::size_t i = 0; i < n; ++i) inc.start[i + 1] += inc.start[i];
  inc.element.resize(inc.start[n]);
  std::vector<std::int64_t> next(inc.start.begin(), inc.start.end() - 1);
  for (std::size_t e = 0; e < mesh.tets.size(); ++e)
    for (int v : mesh.tets[e]) inc.element[next[v]++] = static_cast<std::int64_t>(e);
  return inc;
}

/// Element stiffness with the frames of its nodes applied: K' = Tᵀ·K·T, T = blockdiag(R_a).
Matrix30d element_stiffness(const TetMesh& mesh, std::size_t e, const Matrix6d& D, const NodeFrames& frames) {
  Matrix30d K = tet10_stiffness(element_coordinates(mesh, e), D);
  if (frames.empty()) return K;
  for (int a = 0; a < 10; ++a) {
    const int f = frames.frame_of_node[mesh.tets[e][a]];
    if (f < 0) continue;
    const Eigen::Matrix3d& R = frames.rotations[f];
    K.middleCols<3>(3 * a) = (K.middleCols<3>(3 * a) * R).eval();
    K.middleRows<3>(3 * a) = (R.transpose() * K.middleRows<3>(3 * a)).eval();
  }
  return K;
}

}  // namespace

Eigen::VectorXd to_local(const NodeFrames& frames, const Eigen::VectorXd& global) {
  Eigen::VectorXd v = global;
  for (std::size_t i = 0; i < frames.frame_of_node.size(); ++i)
    if (frames.frame_of_node[i] >= 0)
      v.segment<3>(3 * i) = frames.rotations[frames.frame_of_node[i]].transpose() * global.segment<3>(3 * i);
  return v;
}

Eigen::VectorXd to_global(const NodeFrames& frames, const Eigen::VectorXd& local) {
  Eigen::VectorXd v = local;
  for (std::size_t i = 0; i < frames.frame_of_node.size(); ++i)
    if (frames.frame_of_node[i] >= 0)
      v.segment<3>(3 * i) = frames.rotations[frames.frame_of_node[i]] * local.segment<3>(3 * i);
  return v;
}

SymmetricCsc assemble_stiffness(const TetMesh& mesh, const Material& material, const DofMap& dofs,
                                const NodeFrames& frames) {
  const std::size_t n_nodes = mesh.n_nodes();
  const Incidence inc = node_elements(mesh);

  // Pattern: column dof (b, cb) holds rows of every neighbour node a <= b (and comps <= cb when a == b).
  SymmetricCsc K;
  K.n = dofs.n_equations;
  K.column_start.assign(K.n + 1, 0);
  std::vector<int> neighbours;
  std::vector<std::int64_t> mark(n_nodes, -1);
  // First pass: count; second pass: fill. Neighbours are recomputed rather than stored to keep memory at the pattern.
  auto neighbours_below = [&](std::size_t b) {
    neighbours.clear();
    for (std::int64_t k = inc.start[b]; k < inc.start[b + 1]; ++k)
      for (int a : mesh.tets[inc.element[k]])
        if (static_cast<std::size_t>(a) <= b && mark[a] != static_cast<std::int64_t>(b)) {
          mark[a] = static_cast<std::int64_t>(b);
          neighbours.push_back(a);
        }
    std::sort(neighbours.begin(), neighbours.end());
  };
  for (int pass = 0; pass < 2; ++pass) {
    std::fill(mark.begin(), mark.end(), -1);
    for (std::size_t b = 0; b < n_nodes; ++b) {
      neighbours_below(b);
      for (int cb = 0; cb < 3; ++cb) {
        const std::int64_t j = dofs.equation[3 * b + cb];
        if (j < 0) continue;
        std::int64_t count = 0;
        for (int a : neighbours)
          for (int ca = 0; ca < 3; ++ca) {
            const std::int64_t i = dofs.equation[3 * a + ca];
            if (i < 0 || i > j) continue;
            if (pass == 0) ++count;
            else K.row[K.column_start[j] + count++] = i;
          }
        if (pass == 0) K.column_start[j + 1] = count;
      }
    }
    if (pass == 0) {
      for (std::int64_t j = 0; j < K.n; ++j) K.column_start[j + 1] += K.column_start[j];
      K.row.resize(K.column_start[K.n]);
    }
  }
  K.value.assign(K.row.size(), 0.0);

  const Matrix6d D = elasticity_matrix(material);
  std::array<std::int64_t, 30> eq;
  for (std::size_t e = 0; e < mesh.tets.size(); ++e) {
    Matrix30d Ke;
    try {
      Ke = element_stiffness(mesh, e, D, frames);
    } catch (const std::runtime_error& err) {
      throw std::runtime_error("element " + std::to_string(e) + ": " + err.what());
    }
    for (int a = 0; a < 10; ++a)
      for (int c = 0; c < 3; ++c) eq[3 * a + c] = dofs.equation[3 * mesh.tets[e][a] + c];
    for (int q = 0; q < 30; ++q) {
      const std::int64_t j = eq[q];
      if (j < 0) continue;
      const auto first = K.row.begin() + K.column_start[j], last = K.row.begin() + K.column_start[j + 1];
      for (int p = 0; p < 30; ++p) {
        const std::int64_t i = eq[p];
        if (i < 0 || i > j) continue;
        const auto at = std::lower_bound(first, last, i);
        K.value[at - K.row.begin()] += Ke(p, q);
      }
    }
  }
  return K;
}

Eigen::VectorXd dirichlet_lift(const TetMesh& mesh, const Material& material, const DofMap& dofs,
                               const Eigen::VectorXd& prescribed, const NodeFrames& frames) {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(dofs.n_equations);
  const Matrix6d D = elasticity_matrix(material);
  for (std::size_t e = 0; e < mesh.tets.size(); ++e) {
    Eigen::Matrix<double, 30, 1> ue = Eigen::Matrix<double, 30, 1>::Zero();
    bool any = false;
    for (int a = 0; a < 10; ++a)
      for (int c = 0; c < 3; ++c) {
        const std::size_t g = 3 * mesh.tets[e][a] + c;
        if (dofs.equation[g] < 0 && prescribed[g] != 0.0) {
          ue[3 * a + c] = prescribed[g];
          any = true;
        }
      }
    if (!any) continue;
    const Eigen::Matrix<double, 30, 1> fe = element_stiffness(mesh, e, D, frames) * ue;
    for (int a = 0; a < 10; ++a)
      for (int c = 0; c < 3; ++c) {
        const std::int64_t i = dofs.equation[3 * mesh.tets[e][a] + c];
        if (i >= 0) f[i] -= fe[3 * a + c];
      }
  }
  return f;
}

Eigen::VectorXd internal_forces(const TetMesh& mesh, const Material& material, const Eigen::VectorXd& u) {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(u.size());
  const Matrix6d D = elasticity_matrix(material);
  for (std::size_t e = 0; e < mesh.tets.size(); ++e) {
    Eigen::Matrix<double, 30, 1> ue;
    for (int a = 0; a < 10; ++a) ue.segment<3>(3 * a) = u.segment<3>(3 * mesh.tets[e][a]);
    const Eigen::Matrix<double, 30, 1> fe = tet10_stiffness(element_coordinates(mesh, e), D) * ue;
    for (int a = 0; a < 10; ++a) f.segment<3>(3 * mesh.tets[e][a]) += fe.segment<3>(3 * a);
  }
  return f;
}

std::vector<double> strain_energy_by_region_J(const TetMesh& mesh, const Material& material, const Eigen::VectorXd& u) {
  const int regions = mesh.region.empty() ? 1 : *std::max_element(mesh.region.begin(), mesh.region.end()) + 1;
  std::vector<double> U(static_cast<std::size_t>(regions), 0.0);
  const Matrix6d D = elasticity_matrix(material);
  for (std::size_t e = 0; e < mesh.tets.size(); ++e) {
    Eigen::Matrix<double, 30, 1> ue;
    for (int a = 0; a < 10; ++a) ue.segment<3>(3 * a) = u.segment<3>(3 * mesh.tets[e][a]);
    U[mesh.region.empty() ? 0 : static_cast<std::size_t>(mesh.region[e])] +=
        0.5 * ue.dot(tet10_stiffness(element_coordinates(mesh, e), D) * ue);
  }
  return U;
}

Eigen::VectorXd restrict_to_free(const DofMap& dofs, const Eigen::VectorXd& full) {
  Eigen::VectorXd r(dofs.n_equations);
  for (std::size_t g = 0; g < dofs.equation.size(); ++g)
    if (dofs.equation[g] >= 0) r[dofs.equation[g]] = full[g];
  return r;
}

Eigen::VectorXd expand_to_full(const DofMap& dofs, const Eigen::VectorXd& free, const Eigen::VectorXd& fixed_values) {
  Eigen::VectorXd u = fixed_values;
  for (std::size_t g = 0; g < dofs.equation.size(); ++g)
    if (dofs.equation[g] >= 0) u[g] = free[dofs.equation[g]];
  return u;
}

}  // namespace sw
