#pragma once
// The flexspline body of the loaded contact on the TET10 model: each contact's load pattern as nodal loads on the
// mesh, the influence coefficients Lᵀ·K⁻¹·L from the FEM's one factorisation (half solves, contact/README.md), the
// generator's stations as the FEM's generator contact (fem/generator_contact.hpp). The reference for explicit teeth and
// for verification; a body of revolution has the faster contact/harmonic_body.hpp.
#include <limits>
#include <vector>

#include <Eigen/Core>

#include "contact/contact_body.hpp"
#include "fem/flexspline_model.hpp"
#include "fem/flexspline_system.hpp"
#include "fem/loads.hpp"
#include "mesh/tet_mesh.hpp"

namespace sw {

/// Load patterns of the flanks on the rim's outer surface. A flexspline tooth is a short rigid post on the rim: a force
/// at its flank reaches the rim as that force at the tooth's foot plus the moment of the force about the foot (force ×
/// height above the surface). Per station (a contact's polar angle): a linear hat one tooth pitch wide of radial and of
/// tangential traction, and the foot's moment as a radial couple (outward on one side of the station, inward on the
/// other, each a hat half as wide), their amplitudes such that the station's load has exactly the resultant of the
/// contact force: its force and its moment about the axis. Read work-conjugately (fᵀu), a pattern's displacement is
/// the contact point's on a rigid tooth: the rim's turn under the tooth tilts it. Teeth at θ and θ + π (half-turn
/// pairs) carry the force turned by π.
class FlankLoads {
public:
  /// On the rim's faces whose centroid lies in [z_lo_m, z_hi_m] (an axial slice of the face width; the default: all).
  FlankLoads(const TetMesh& mesh, double pitch_rad, double z_lo_m = -std::numeric_limits<double>::infinity(),
             double z_hi_m = std::numeric_limits<double>::infinity());
  /// Nodal loads of 1 N along `force_dir` (2-D, frame of the generator) at the point `contact_radius_m` out on the
  /// radial line of stations[0], and of the same turned by π at a partner stations[1] = stations[0] + π.
  Eigen::VectorXd pattern(const std::vector<double>& stations, const Eigen::Vector2d& force_dir,
                          double contact_radius_m) const;
  /// Nodal loads at one station of the three hats whose resultant is `target` = (F_x, F_y, M_z about the axis).
  Eigen::VectorXd wrench(double station_rad, const Eigen::Vector3d& target) const;

private:
  static std::vector<const BoundaryFace*> rim(const TetMesh& mesh, double z_lo_m, double z_hi_m);
  const TetMesh& mesh_;
  double half_;
  AngularHats hats_;
};

/// Load patterns on explicit teeth (flexspline.teeth = "explicit": the rim's outer surface is the tooth outline). A
/// flank's force acts on the tooth's own surface where the teeth touch: a traction along the force, spread along the
/// profile by a linear hat of half-width `spread_m` about the contact point and uniform across the face width (or
/// the pattern's slice), on the faces of the tooth's flank side (both sides for a point on the centre line, the tip
/// land included), its resultant exactly the force. The mesh is the rim at rest, so the force sits at the contact's
/// material point, whose moment about the axis differs from the force's at its place on the generator-deformed rim
/// (the ring patterns' and the contact's lever) by the generator's displacement of that point × the force: that
/// difference is added as a pure moment by the ring patterns' three hats (FlankLoads::wrench, zero resultant force),
/// so both bodies carry each contact force with the same force and moment.
class ExplicitToothLoads {
public:
  ExplicitToothLoads(const TetMesh& mesh, double pitch_rad, double spread_m,
                     double z_lo_m = -std::numeric_limits<double>::infinity(),
                     double z_hi_m = std::numeric_limits<double>::infinity());
  /// The loads of a pattern with its tooth given (FlankPattern::tooth_angle_rad, tooth_point_m): 1 N along
  /// `force_dir` at the tooth's point, its moment made that of the force at `contact_radius_m` on the radial line of
  /// stations[0]; the partner tooth (+ π) with the force turned by π.
  Eigen::VectorXd pattern(const std::vector<double>& stations, const Eigen::Vector2d& force_dir,
                          double contact_radius_m, double tooth_angle_rad, const Eigen::Vector2d& tooth_point_m) const;

private:
  const TetMesh& mesh_;
  double pitch_, spread_;
  std::vector<const BoundaryFace*> faces_;
  std::vector<Eigen::Vector3d> centroid_;
  std::vector<double> reach_;  ///< per face: its corners' largest distance from its centroid, transverse plane
  FlankLoads hats_;
};

/// The body on a mesh and its factorised system; `generator_u` (3·n_nodes, the FEM's generator case) may be null
/// (a solution read back: no curves off the face's centre). The mesh, the system and the field must outlive the body.
class Tet10Body final : public ContactBody {
public:
  Tet10Body(const FlexsplineModel& c, const TetMesh& mesh, const FlexsplineSystem& system,
            const Eigen::VectorXd* generator_u);
  std::string solver() const override { return "tet10"; }
  const BodyStations& stations() const override { return stations_; }
  BodyInfluence influence(const std::vector<FlankPattern>& patterns, int slices) const override;
  std::vector<NeutralCurveSamples> generator_curves_at(const std::vector<double>& z_m) const override;

private:
  const FlexsplineModel c_;  ///< a copy: the caller's may be a temporary
  const TetMesh& mesh_;
  const FlexsplineSystem& sys_;
  const Eigen::VectorXd* generator_u_;
  GeneratorStations generator_;
  BodyStations stations_;
};

}  // namespace sw
