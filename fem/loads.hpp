#pragma once
// Consistent nodal loads: surface tractions integrated over quadratic (TRI6) boundary faces with the isoparametric
// map, so curved faces get their true area. For a uniform traction on a flat TRI6 the corner loads are zero and each
// midside node takes one third of the face's resultant.
#include <cmath>
#include <functional>
#include <numbers>
#include <vector>

#include <Eigen/Core>

#include "mesh/tet_mesh.hpp"

namespace sw {

/// An angle brought into (−π, π].
inline double wrap_pi(double a) { return std::remainder(a, 2 * std::numbers::pi); }
/// The polar angle of a point about the axis (z), in (−π, π].
inline double theta_of(const Eigen::Vector3d& x) { return std::atan2(x[1], x[0]); }

/// Traction (Pa, 3-vector) at surface point x (m) with outward unit normal n.
using TractionField = std::function<Eigen::Vector3d(const Eigen::Vector3d& x, const Eigen::Vector3d& n)>;

/// Consistent load vector (3·n_nodes, N) of `traction` over the listed boundary faces.
/// Integrated with the 7-point degree-5 rule on each face.
Eigen::VectorXd traction_load(const TetMesh& mesh, const std::vector<const BoundaryFace*>& faces,
                              const TractionField& traction);

/// Faces with the given marker whose centroid satisfies `keep` (any face if `keep` is empty).
std::vector<const BoundaryFace*> select_faces(const TetMesh& mesh, int marker,
                                              const std::function<bool(const Eigen::Vector3d&)>& keep = {});

/// Area (m²) of the faces, from the isoparametric map.
double faces_area(const TetMesh& mesh, const std::vector<const BoundaryFace*>& faces);

/// Integral of a scalar field over the faces (same rule as traction_load, so it normalises a traction exactly).
double faces_integral(const TetMesh& mesh, const std::vector<const BoundaryFace*>& faces,
                      const std::function<double(const Eigen::Vector3d&)>& field);

/// Loads spread over part of a surface by a linear hat in the polar angle θ about the axis z: 1 at a station, 0 at
/// ±half-width, normalised so the hat integrates to one over the faces it reaches. The faces are indexed by angle once,
/// so each station only integrates the faces its hat can reach. Serves the generator's stations on the bore and the
/// tooth flanks' patterns on the rim.
class AngularHats {
public:
  AngularHats(const TetMesh& mesh, std::vector<const BoundaryFace*> faces);
  /// Nodal loads (3·n_nodes) of the traction direction(θ)·hat(θ)/∫hat; its resultant is 1 N along a uniform
  /// direction. Empty (size 0) when no face lies under the hat.
  Eigen::VectorXd load(double station_rad, double half_width_rad,
                       const std::function<Eigen::Vector3d(double theta_rad)>& direction) const;

private:
  const TetMesh& mesh_;
  std::vector<const BoundaryFace*> faces_;
  std::vector<double> theta_, reach_;  ///< per face: centroid angle, largest angular distance of its corners from it
};

/// Resultant force (N) and moment about the origin (N·m) of a full dof load vector.
struct Resultant {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
};
Resultant load_resultant(const TetMesh& mesh, const Eigen::VectorXd& f);

}  // namespace sw
