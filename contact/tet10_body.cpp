#include "contact/tet10_body.hpp"

#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>
#include <string>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/SparseCore>

#include "common/constants.hpp"
#include "common/error.hpp"
#include "fem/assembly.hpp"
#include "fem/loads.hpp"
#include "fem/post.hpp"
#include "mesh/flexspline.hpp"

namespace sw {
namespace {

}  // namespace

std::vector<const BoundaryFace*> FlankLoads::rim(const TetMesh& mesh, double z_lo_m, double z_hi_m) {
  std::vector<const BoundaryFace*> faces;
  for (const BoundaryFace* f : select_faces(mesh, kSurfaceRimOuter)) {
    double z = 0;
    for (int k = 0; k < 3; ++k) z += mesh.nodes(f->nodes[k], 2) / 3;
    if (z >= z_lo_m && z <= z_hi_m) faces.push_back(f);
  }
  if (faces.empty()) throw InputError("contact: the flexspline mesh has no toothed rim surface" +
                                      std::string(std::isfinite(z_lo_m) ? " in an axial slice; refine mesh.size_mm" : ""));
  return faces;
}

FlankLoads::FlankLoads(const TetMesh& mesh, double pitch_rad, double z_lo_m, double z_hi_m)
    : mesh_(mesh), half_(pitch_rad), hats_(mesh, rim(mesh, z_lo_m, z_hi_m)) {}

Eigen::VectorXd FlankLoads::pattern(const std::vector<double>& stations, const Eigen::Vector2d& force_dir,
                                    double contact_radius_m) const {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * mesh_.n_nodes());
  for (std::size_t i = 0; i < stations.size(); ++i) {
    // The contact force at this station (turned by π at the partner) and its moment about the axis.
    const double s = stations[i];
    const Eigen::Vector2d F = i == 0 ? force_dir : Eigen::Vector2d(-force_dir);
    const Eigen::Vector2d P = contact_radius_m * Eigen::Vector2d(std::cos(s), std::sin(s));
    f += wrench(s, Eigen::Vector3d(F.x(), F.y(), P.x() * F.y() - P.y() * F.x()));
  }
  return f;
}

Eigen::VectorXd FlankLoads::wrench(double s, const Eigen::Vector3d& target) const {
  const auto radial_dir = [](double t) { return Eigen::Vector3d(std::cos(t), std::sin(t), 0); };
  const auto tangential_dir = [](double t) { return Eigen::Vector3d(-std::sin(t), std::cos(t), 0); };
  Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * mesh_.n_nodes());
  {
    const Eigen::VectorXd radial = hats_.load(s, half_, radial_dir), tangential = hats_.load(s, half_, tangential_dir),
                          outer = hats_.load(s + half_ / 2, half_ / 2, radial_dir),
                          inner = hats_.load(s - half_ / 2, half_ / 2, radial_dir);
    if (radial.size() == 0 || outer.size() == 0 || inner.size() == 0)
      throw InputError("contact: no rim faces under the tooth at " + std::to_string(s * 180 / kPi) +
                       " deg; refine mesh.size_mm");
    // The three amplitudes reproduce the target's force and moment about the axis exactly. Every sum runs over the
    // hats' nodes only (the radial hat's: the others lie within it); the full vectors are the mesh's size.
    std::vector<Eigen::Index> nodes;
    for (Eigen::Index n = 0; n < static_cast<Eigen::Index>(mesh_.n_nodes()); ++n)
      if (radial.segment<3>(3 * n).any()) nodes.push_back(n);
    const auto k = static_cast<Eigen::Index>(nodes.size());
    Eigen::MatrixXd H(3 * k, 3);  // radial, tangential, couple (outer − inner) at those nodes
    Eigen::Matrix3d R = Eigen::Matrix3d::Zero();
    for (Eigen::Index j = 0; j < k; ++j) {
      const Eigen::Index n = nodes[j];
      H.block<3, 1>(3 * j, 0) = radial.segment<3>(3 * n);
      H.block<3, 1>(3 * j, 1) = tangential.segment<3>(3 * n);
      H.block<3, 1>(3 * j, 2) = outer.segment<3>(3 * n) - inner.segment<3>(3 * n);
      for (int c = 0; c < 3; ++c) {
        const double fx = H(3 * j, c), fy = H(3 * j + 1, c);
        R.col(c) += Eigen::Vector3d(fx, fy, mesh_.nodes(n, 0) * fy - mesh_.nodes(n, 1) * fx);
      }
    }
    const Eigen::VectorXd h = H * R.fullPivLu().solve(target);
    for (Eigen::Index j = 0; j < k; ++j) f.segment<3>(3 * nodes[j]) += h.segment<3>(3 * j);
  }
  return f;
}

ExplicitToothLoads::ExplicitToothLoads(const TetMesh& mesh, double pitch_rad, double spread_m, double z_lo_m,
                                       double z_hi_m)
    : mesh_(mesh), pitch_(pitch_rad), spread_(spread_m), hats_(mesh, pitch_rad, z_lo_m, z_hi_m) {
  for (const BoundaryFace* f : select_faces(mesh, kSurfaceRimOuter)) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) c += mesh.nodes.row(f->nodes[k]).transpose() / 3;
    if (c.z() < z_lo_m || c.z() > z_hi_m) continue;
    double reach = 0;  // the face's largest corner distance from its centroid, in the transverse plane
    for (int k = 0; k < 3; ++k) reach = std::max(reach, (mesh.nodes.row(f->nodes[k]).head<2>().transpose() - c.head<2>()).norm());
    faces_.push_back(f);
    centroid_.push_back(c);
    reach_.push_back(reach);
  }
}

Eigen::VectorXd ExplicitToothLoads::pattern(const std::vector<double>& stations, const Eigen::Vector2d& force_dir,
                                            double contact_radius_m, double tooth_angle_rad,
                                            const Eigen::Vector2d& tooth_point_m) const {
  if (!std::isfinite(tooth_angle_rad))
    throw InputError("contact: a load pattern on explicit teeth needs its tooth (angle and point on the tooth)");
  Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * mesh_.n_nodes());
  const std::vector<bool> all(mesh_.n_nodes(), true);
  for (std::size_t i = 0; i < stations.size(); ++i) {
    const double a = tooth_angle_rad + (i == 0 ? 0.0 : kPi);
    const Eigen::Vector2d F = i == 0 ? force_dir : Eigen::Vector2d(-force_dir);
    const Eigen::Vector2d p = Eigen::Rotation2Dd(a) * tooth_point_m;
    // The tooth's faces on the contact's side of its centre line (both sides for a point on it) within the hat.
    const double side = std::abs(tooth_point_m.y()) > 1e-3 * spread_ ? (tooth_point_m.y() > 0 ? 1.0 : -1.0) : 0.0;
    const Eigen::Vector2d across(-std::sin(a), std::cos(a));
    std::vector<const BoundaryFace*> faces;
    for (std::size_t k = 0; k < faces_.size(); ++k) {
      const Eigen::Vector2d c = centroid_[k].head<2>();
      if (std::abs(std::remainder(std::atan2(c.y(), c.x()) - a, 2 * kPi)) > pitch_ / 2) continue;
      if (side != 0 && side * c.dot(across) < 0) continue;
      if ((c - p).norm() < spread_ + reach_[k]) faces.push_back(faces_[k]);
    }
    const auto hat = [&](const Eigen::Vector3d& x) { return std::max(0.0, 1 - (x.head<2>() - p).norm() / spread_); };
    const double integral = faces.empty() ? 0.0 : faces_integral(mesh_, faces, hat);
    if (!(integral > 0))
      throw InputError("contact: no flank faces of the explicit tooth at " + std::to_string(a * 180 / kPi) +
                       " deg under the contact point; refine mesh.size_mm");
    const Eigen::Vector3d F3(F.x(), F.y(), 0);
    const Eigen::VectorXd flank =
        traction_load(mesh_, faces, [&](const Eigen::Vector3d& x, const Eigen::Vector3d&) { return F3 * hat(x) / integral; });
    // The moment the force has at its place on the deformed rim (the contact's lever), the difference as a pure moment.
    const double s = stations[i];
    const Eigen::Vector2d P = contact_radius_m * Eigen::Vector2d(std::cos(s), std::sin(s));
    const double moment = P.x() * F.y() - P.y() * F.x();
    f += flank + hats_.wrench(s, Eigen::Vector3d(0, 0, moment - moment_about_z(mesh_, flank, all)));
  }
  return f;
}

namespace {

Eigen::SparseMatrix<double> sparse_columns(const std::vector<Eigen::VectorXd>& cols, const Eigen::SparseMatrix<double>& more) {
  std::vector<Eigen::Triplet<double>> t;
  for (std::size_t j = 0; j < cols.size(); ++j)
    for (Eigen::Index i = 0; i < cols[j].size(); ++i)
      if (cols[j][i] != 0.0) t.emplace_back(static_cast<int>(i), static_cast<int>(j), cols[j][i]);
  for (Eigen::Index j = 0; j < more.outerSize(); ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(more, j); it; ++it)
      t.emplace_back(static_cast<int>(it.row()), static_cast<int>(cols.size() + j), it.value());
  Eigen::SparseMatrix<double> L(more.rows() ? more.rows() : (cols.empty() ? 0 : cols[0].size()),
                                static_cast<Eigen::Index>(cols.size()) + more.cols());
  L.setFromTriplets(t.begin(), t.end());
  return L;
}

/// Nodal loads of each pattern on its slice's faces: `make(z_lo, z_hi)` builds the loads of a band of the face (the
/// whole face once, a slice when a pattern first asks for it), `load(loads, pattern)` one pattern's.
template <class Make, class Load>
std::vector<Eigen::VectorXd> loads_by_slice(const FlexsplineParams& f, const std::vector<FlankPattern>& patterns,
                                            int slices, const Make& make, const Load& load) {
  using Loads = decltype(make(0.0, 0.0));
  constexpr double kAll = std::numeric_limits<double>::infinity();
  const Loads face = make(-kAll, kAll);
  std::vector<std::optional<Loads>> slice(static_cast<std::size_t>(std::max(slices, 1)));
  std::vector<Eigen::VectorXd> cols;
  for (const FlankPattern& p : patterns) {
    const Loads* loads = &face;
    if (p.slice >= 0 && slices > 1) {
      auto& s = slice.at(static_cast<std::size_t>(p.slice));
      if (!s) {
        const auto [lo, hi] = face_slice_m(f, p.slice, slices);
        s.emplace(make(lo, hi));
      }
      loads = &*s;
    }
    cols.push_back(p.scale * load(*loads, p));
  }
  return cols;
}

/// Nodal loads of each pattern, on its slice's rim faces: on the teeth's own flanks for explicit teeth, else the ring
/// patterns on the rim's surface.
std::vector<Eigen::VectorXd> pattern_loads(const FlexsplineModel& c, const TetMesh& mesh,
                                           const std::vector<FlankPattern>& patterns, int slices) {
  const double pitch = 2 * kPi / c.gear->teeth_flexspline;
  if (c.flexspline.teeth == TeethModel::Explicit) {
    // The hat along the profile as wide as an element across the tooth: the load resolved by the mesh that carries it.
    const double spread = tooth_mesh_size(*c.gear, c.mesh).across_m;
    return loads_by_slice(
        c.flexspline, patterns, slices,
        [&](double lo, double hi) { return ExplicitToothLoads(mesh, pitch, spread, lo, hi); },
        [](const ExplicitToothLoads& l, const FlankPattern& p) {
          return l.pattern(p.stations_rad, p.force_dir, p.contact_radius_m, p.tooth_angle_rad, p.tooth_point_m);
        });
  }
  return loads_by_slice(
      c.flexspline, patterns, slices, [&](double lo, double hi) { return FlankLoads(mesh, pitch, lo, hi); },
      [](const FlankLoads& l, const FlankPattern& p) {
        return l.pattern(p.stations_rad, p.force_dir, p.contact_radius_m);
      });
}

}  // namespace

Tet10Body::Tet10Body(const FlexsplineModel& c, const TetMesh& mesh, const FlexsplineSystem& system,
                     const Eigen::VectorXd* generator_u)
    : c_(c), mesh_(mesh), sys_(system), generator_u_(generator_u), generator_(generator_stations(c, mesh)) {
  stations_.unilateral = generator_.unilateral;
  stations_.angle_rad = generator_.stations.angle_rad;
  stations_.half_width_rad = generator_.stations.half_width_rad;
}

BodyInfluence Tet10Body::influence(const std::vector<FlankPattern>& patterns, int slices) const {
  auto L = std::make_shared<const Eigen::SparseMatrix<double>>(
      sparse_columns(pattern_loads(c_, mesh_, patterns, slices), generator_.stations.loads));
  BodyInfluence b;
  b.A = sys_.influence(*L);
  b.lever.resize(L->cols());
  const std::vector<bool> all(mesh_.n_nodes(), true);
  for (Eigen::Index j = 0; j < L->cols(); ++j) b.lever[j] = -moment_about_z(mesh_, Eigen::VectorXd(L->col(j)), all);
  b.check = [this, L, A = b.A](const Eigen::VectorXd& x) {
    const Eigen::VectorXd f = *L * x;
    const Eigen::VectorXd u = sys_.solve(f).col(0);
    const Eigen::VectorXd direct = L->transpose() * u, by_influence = A * x;
    BodyCheck c;
    c.superposition_error_rel = (direct - by_influence).cwiseAbs().maxCoeff() / direct.cwiseAbs().maxCoeff();
    c.clamp_reaction_torque_Nm = moment_about_z(mesh_, internal_forces(mesh_, c_.material, u) - f, sys_.clamped);
    return c;
  };
  b.energy_by_region_J = [this, L](const Eigen::VectorXd& x) {
    return strain_energy_by_region_J(mesh_, c_.material, sys_.solve(*L * x).col(0));
  };
  return b;
}

std::vector<NeutralCurveSamples> Tet10Body::generator_curves_at(const std::vector<double>& z_m) const {
  if (!generator_u_ || z_m.empty()) return {};
  return neutral_curves_at(c_, mesh_, *generator_u_, z_m);
}

}  // namespace sw
