#pragma once
// The cam's outer surface as the generator's contact sees it: the radial standoff s(θ) of the surface from the
// unloaded bore (less the fit) and the tilt ρ'(θ)/ρ(θ) of its normal from the radial direction, θ from the major axis.
//  - polar:   ρ = r + w0·cos2θ, the first-order shape the linear model works in;
//  - ellipse: semi-axes r + w0 and r − w0, inside the polar form by up to 1.5·w0²/r at ±45°;
//  - list:    the case's radius against angle over a half turn, interpolated by a periodic cubic spline of period 180°
//             (the generator's half-turn symmetry, which the stations' pairing relies on); C², so the normal turns
//             smoothly between the points.
#include <vector>

namespace sw {

/// A point of a listed cam: the radius of the generator's surface that touches the bore, at an angle from the major
/// axis.
struct CamPoint {
  double angle_rad = 0.0;
  double radius_m = 0.0;
};

/// The cam's outer surface: polar r + w0·cos2φ (the first-order shape the linear model works in; the default), a
/// true ellipse of semi-axes r + w0 and r − w0 (inside the polar form by up to 1.5·w0²/r at ±45°), or a list of radii
/// against angle over a half turn (generator/cam_profile.hpp).
enum class CamProfile { Polar, Ellipse, List };

/// An elliptical cam pushing on the bore.
struct Cam {
  CamProfile profile = CamProfile::Polar;
  double clearance_m = 0.0;     ///< radial fit to the bore, clearance > 0, interference < 0
  std::vector<CamPoint> points; ///< profile = List: angles in [0, π), increasing
};

/// Periodic cubic interpolating spline (natural in the sense of C² across the period's seam). Written here because
/// Eigen 3.4's unsupported Splines module has no periodic interpolation and the knots are few (a dense solve).
class PeriodicSpline {
public:
  /// Strictly increasing x in [x0, x0 + period), at least 3 points.
  PeriodicSpline(std::vector<double> x, std::vector<double> y, double period);
  double operator()(double x) const;
  double derivative(double x) const;

private:
  std::vector<double> x_, y_, m_;  // knots, values, second derivatives
  double period_;
  std::size_t interval(double& x) const;  // wraps x into the period and finds its interval
};

class CamSurface {
public:
  CamSurface(const Cam& cam, double w0_m, double bore_radius_m);
  double radius_m(double theta_rad) const;   ///< ρ(θ)
  double standoff_m(double theta_rad) const; ///< ρ(θ) − r − fit: > 0 where the cam would push the bore out
  double tilt(double theta_rad) const;       ///< ρ'/ρ: the normal n ∝ e_r − tilt·e_θ

private:
  CamProfile profile_;
  double r_, w0_, fit_;
  std::vector<PeriodicSpline> list_;  // one for a list profile
};

/// The radius of a listed cam at the major axis less the bore: the w0 it stands for (m).
double cam_list_w0_m(const std::vector<CamPoint>& points, double bore_radius_m);

}  // namespace sw
