#pragma once
// The flexspline body as the loaded contact sees it: the influence coefficients of the contacts' load patterns, read
// off either model of the flexspline (contact/tet10_body.hpp: the TET10 mesh's one factorisation;
// contact/harmonic_body.hpp: the harmonic solver's meridian section). The contact problem itself
// (contact/loaded_contact.hpp) does not know which.
#include <algorithm>
#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "fem/flexspline_analysis.hpp"

namespace sw {

/// Where a contact's load acts, described for either model to build: 1 N along `force_dir` (in the generator's frame)
/// at the point `contact_radius_m` out on the radial line at stations_rad[0], carried down a rigid tooth to the rim's
/// outer surface (force and moment about the tooth's foot, spread one tooth pitch wide; contact/README.md), and the
/// same turned by π at stations_rad[1] when the tooth has a half-turn partner. Scaled by `scale`.
struct FlankPattern {
  std::vector<double> stations_rad;
  Eigen::Vector2d force_dir = Eigen::Vector2d::Zero();
  double contact_radius_m = 0;
  int slice = -1;     ///< axial slice of the face (of ContactBody::influence's `slices`); −1: the whole face
  double scale = 1;
  /// For a body with explicit teeth: the loaded tooth's material angle (its centre line at rest; the partner's is
  /// + π) and the point of the load in the tooth's own frame (tooth on +x, the gear's centre at the origin). A ring
  /// body needs neither; NaN: not given.
  double tooth_angle_rad = std::numeric_limits<double>::quiet_NaN();
  Eigen::Vector2d tooth_point_m = Eigen::Vector2d::Zero();
};

/// Where the loaded contact samples the toothed face, as fractions of its width from the edge nearer the closed end:
/// n sections at the face's two ends and evenly between, each standing for the band of the face nearer to it than to
/// any other (the trapezoid rule across the width: an end section carries half a band), so the ends, where the cup's
/// coning makes the teeth tightest or loosest, are sampled themselves. n = 1: the centre section for the whole face.
struct FaceSlice {
  double at = 0.5, lo = 0, hi = 1;  ///< fractions of the face from its closed end: the section, its band's ends
  double width() const { return hi - lo; }
};
inline FaceSlice face_slice(int j, int n) {
  if (n <= 1) return {};
  const double h = 1.0 / (n - 1), at = j * h;
  return {at, std::max(0.0, at - h / 2), std::min(1.0, at + h / 2)};
}

/// Axial position of section j of n on a face of `face_m` centred at `centre_m` (any axial origin).
inline double face_section_z_m(double centre_m, double face_m, int j, int n) {
  return centre_m - face_m / 2 + face_m * face_slice(j, n).at;
}

/// Axial range (from the closed end) of slice j of n of the toothed face (the whole face for n = 1).
inline std::pair<double, double> face_slice_m(const FlexsplineParams& f, int j, int n) {
  const double face = f.rim_width_m, lo = f.length_m - face;
  const FaceSlice s = face_slice(j, n);
  return {lo + face * s.lo, lo + face * s.hi};
}

/// The independent check of a body's influence coefficients at one loaded state.
struct BodyCheck {
  double superposition_error_rel = 0;  ///< |direct − influence| over the largest displacement
  double clamp_reaction_torque_Nm = 0;  ///< moment about the axis of the clamp's reaction
};

/// The coefficients of patterns, then of the generator's stations (one unknown per station pair).
struct BodyInfluence {
  Eigen::MatrixXd A;       ///< work-conjugate displacement of each per unit force of each (m/N), symmetric
  /// Lever of each (m): the output torque a unit force of it carries, minus the moment about the axis of its load on
  /// the flexspline (the contact problem's λ).
  Eigen::VectorXd lever;
  /// The loads x (per column of A) applied to the body in one direct solve, read back independently of A.
  std::function<BodyCheck(const Eigen::VectorXd& x)> check;
  /// The strain energy (J) of the body under the loads x (per column of A), per region of its mesh (0 body wall, 1 the
  /// toothed rim, 2 diaphragm, 3 boss): from the field of a direct solve, so its sum is ½xᵀAx only as far as the
  /// coefficients are the field's (a check). Empty for a body without a mesh (the body's part is then not split).
  std::function<std::vector<double>(const Eigen::VectorXd& x)> energy_by_region_J;
};

/// The generator's stations on the bore (angles of the pairs' first stations, their hats' half-width).
struct BodyStations {
  bool unilateral = false;  ///< a cam or rollers (contact), else the force idealisation (held radially)
  std::vector<double> angle_rad;
  double half_width_rad = 0;
};

class ContactBody {
public:
  virtual ~ContactBody() = default;
  /// "tet10" or "fourier": which model of the flexspline the coefficients come from.
  virtual std::string solver() const = 0;
  virtual const BodyStations& stations() const = 0;
  /// The influence coefficients of `patterns` on the face cut into `slices` axial slices (a pattern's slice, or the
  /// whole face), and of the generator's stations after them.
  virtual BodyInfluence influence(const std::vector<FlankPattern>& patterns, int slices) const = 0;
  /// The rim's neutral curves of the generator case at axial sections z_m (from the closed end); empty when the
  /// body has no generator field at hand (a solution read back from result.json).
  virtual std::vector<NeutralCurveSamples> generator_curves_at(const std::vector<double>& z_m) const = 0;
};

}  // namespace sw
