#include "fem/loads.hpp"

#include <array>
#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

namespace sw {
namespace {

// Dunavant degree-5 rule on the reference triangle (area 1/2): (s, t, weight) with weights summing to 1/2.
struct TriPoint {
  double s, t, w;
};
const std::array<TriPoint, 7> kTriRule = [] {
  const double a1 = 0.059715871789770, b1 = 0.470142064105115;
  const double a2 = 0.797426985353087, b2 = 0.101286507323456;
  const double w0 = 0.225 / 2, w1 = 0.132394152788506 / 2, w2 = 0.125939180544827 / 2;
  return std::array<TriPoint, 7>{{{1.0 / 3, 1.0 / 3, w0},
                                  {b1, b1, w1}, {a1, b1, w1}, {b1, a1, w1},
                                  {b2, b2, w2}, {a2, b2, w2}, {b2, a2, w2}}};
}();

/// TRI6 shape values and derivatives at (s, t): corners 0..2, midsides (0,1), (1,2), (2,0).
void tri6(double s, double t, double N[6], double dNs[6], double dNt[6]) {
  const double L1 = 1 - s - t, L2 = s, L3 = t;
  N[0] = L1 * (2 * L1 - 1); N[1] = L2 * (2 * L2 - 1); N[2] = L3 * (2 * L3 - 1);
  N[3] = 4 * L1 * L2; N[4] = 4 * L2 * L3; N[5] = 4 * L3 * L1;
  dNs[0] = -(4 * L1 - 1); dNs[1] = 4 * L2 - 1; dNs[2] = 0;
  dNs[3] = 4 * (L1 - L2); dNs[4] = 4 * L3; dNs[5] = -4 * L3;
  dNt[0] = -(4 * L1 - 1); dNt[1] = 0; dNt[2] = 4 * L3 - 1;
  dNt[3] = -4 * L2; dNt[4] = 4 * L2; dNt[5] = 4 * (L1 - L3);
}

template <class Visit>
void integrate_face(const TetMesh& mesh, const BoundaryFace& f, Visit visit) {
  for (const auto& q : kTriRule) {
    double N[6], dNs[6], dNt[6];
    tri6(q.s, q.t, N, dNs, dNt);
    Eigen::Vector3d x = Eigen::Vector3d::Zero(), xs = Eigen::Vector3d::Zero(), xt = Eigen::Vector3d::Zero();
    for (int a = 0; a < 6; ++a) {
      const Eigen::Vector3d p = mesh.nodes.row(f.nodes[a]).transpose();
      x += N[a] * p;
      xs += dNs[a] * p;
      xt += dNt[a] * p;
    }
    const Eigen::Vector3d normal = xs.cross(xt);
    const double jac = normal.norm();
    visit(x, normal / jac, N, q.w * jac);
  }
}

}  // namespace

Eigen::VectorXd traction_load(const TetMesh& mesh, const std::vector<const BoundaryFace*>& faces,
                              const TractionField& traction) {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * mesh.n_nodes());
  for (const BoundaryFace* face : faces)
    integrate_face(mesh, *face, [&](const Eigen::Vector3d& x, const Eigen::Vector3d& n, const double* N, double w) {
      const Eigen::Vector3d t = traction(x, n);
      for (int a = 0; a < 6; ++a) f.segment<3>(3 * face->nodes[a]) += (w * N[a]) * t;
    });
  return f;
}

std::vector<const BoundaryFace*> select_faces(const TetMesh& mesh, int marker,
                                              const std::function<bool(const Eigen::Vector3d&)>& keep) {
  std::vector<const BoundaryFace*> out;
  for (const auto& f : mesh.faces) {
    if (f.marker != marker) continue;
    const Eigen::Vector3d c =
        (mesh.nodes.row(f.nodes[0]) + mesh.nodes.row(f.nodes[1]) + mesh.nodes.row(f.nodes[2])).transpose() / 3.0;
    if (!keep || keep(c)) out.push_back(&f);
  }
  return out;
}

double faces_area(const TetMesh& mesh, const std::vector<const BoundaryFace*>& faces) {
  return faces_integral(mesh, faces, [](const Eigen::Vector3d&) { return 1.0; });
}

double faces_integral(const TetMesh& mesh, const std::vector<const BoundaryFace*>& faces,
                      const std::function<double(const Eigen::Vector3d&)>& field) {
  double sum = 0;
  for (const BoundaryFace* face : faces)
    integrate_face(mesh, *face, [&](const Eigen::Vector3d& x, const Eigen::Vector3d&, const double*, double w) {
      sum += w * field(x);
    });
  return sum;
}

Resultant load_resultant(const TetMesh& mesh, const Eigen::VectorXd& f) {
  Resultant r;
  for (std::size_t i = 0; i < mesh.n_nodes(); ++i) {
    const Eigen::Vector3d fi = f.segment<3>(3 * i);
    r.force += fi;
    r.moment += mesh.nodes.row(i).transpose().cross(fi);
  }
  return r;
}


AngularHats::AngularHats(const TetMesh& mesh, std::vector<const BoundaryFace*> faces)
    : mesh_(mesh), faces_(std::move(faces)) {
  for (const auto* f : faces_) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int a = 0; a < 3; ++a) c += mesh.nodes.row(f->nodes[a]).transpose();
    const double t = theta_of(c / 3);
    double reach = 0;
    for (int v : f->nodes) reach = std::max(reach, std::abs(wrap_pi(theta_of(mesh.nodes.row(v).transpose()) - t)));
    theta_.push_back(t);
    reach_.push_back(reach);
  }
}

Eigen::VectorXd AngularHats::load(double station_rad, double half_width_rad,
                                  const std::function<Eigen::Vector3d(double)>& direction) const {
  std::vector<const BoundaryFace*> under;
  for (std::size_t i = 0; i < faces_.size(); ++i)
    if (std::abs(wrap_pi(theta_[i] - station_rad)) <= half_width_rad + reach_[i]) under.push_back(faces_[i]);
  auto hat = [&](const Eigen::Vector3d& x) {
    return std::max(0.0, 1.0 - std::abs(wrap_pi(theta_of(x) - station_rad)) / half_width_rad);
  };
  const double total = faces_integral(mesh_, under, hat);
  if (!(total > 0)) return {};
  return traction_load(mesh_, under, [&](const Eigen::Vector3d& x, const Eigen::Vector3d&) -> Eigen::Vector3d {
    return direction(theta_of(x)) * (hat(x) / total);
  });
}

}  // namespace sw
