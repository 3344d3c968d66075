#include "generator/cam_profile.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <Eigen/Dense>

namespace sw {

PeriodicSpline::PeriodicSpline(std::vector<double> x, std::vector<double> y, double period)
    : x_(std::move(x)), y_(std::move(y)), period_(period) {
  const std::size_t n = x_.size();
  if (n < 3 || y_.size() != n) throw std::invalid_argument("PeriodicSpline: needs 3 or more points");
  // Continuity of the first derivative at every knot (the last interval closes over the seam):
  // h_{i−1}·M_{i−1} + 2(h_{i−1} + h_i)·M_i + h_i·M_{i+1} = 6[(y_{i+1} − y_i)/h_i − (y_i − y_{i−1})/h_{i−1}].
  auto h = [&](std::size_t i) { return i + 1 < n ? x_[i + 1] - x_[i] : x_[0] + period_ - x_[n - 1]; };
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
  Eigen::VectorXd rhs(static_cast<Eigen::Index>(n));
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t prev = (i + n - 1) % n, next = (i + 1) % n;
    const double hp = h(prev), hi = h(i);
    A(i, prev) += hp;
    A(i, i) += 2 * (hp + hi);
    A(i, next) += hi;
    rhs[i] = 6 * ((y_[next] - y_[i]) / hi - (y_[i] - y_[prev]) / hp);
  }
  const Eigen::VectorXd M = A.partialPivLu().solve(rhs);
  m_.assign(M.data(), M.data() + n);
}

std::size_t PeriodicSpline::interval(double& x) const {
  x = x_[0] + std::fmod(std::fmod(x - x_[0], period_) + period_, period_);
  const auto it = std::upper_bound(x_.begin(), x_.end(), x);
  return static_cast<std::size_t>(it - x_.begin()) - 1;
}

double PeriodicSpline::operator()(double x) const {
  const std::size_t i = interval(x), j = (i + 1) % x_.size();
  const double xj = j == 0 ? x_[0] + period_ : x_[j], hi = xj - x_[i];
  const double a = (xj - x) / hi, b = (x - x_[i]) / hi;
  return a * y_[i] + b * y_[j] + ((a * a * a - a) * m_[i] + (b * b * b - b) * m_[j]) * hi * hi / 6;
}

double PeriodicSpline::derivative(double x) const {
  const std::size_t i = interval(x), j = (i + 1) % x_.size();
  const double xj = j == 0 ? x_[0] + period_ : x_[j], hi = xj - x_[i];
  const double a = (xj - x) / hi, b = (x - x_[i]) / hi;
  return (y_[j] - y_[i]) / hi + ((1 - 3 * a * a) * m_[i] + (3 * b * b - 1) * m_[j]) * hi / 6;
}

namespace {

PeriodicSpline list_spline(const std::vector<CamPoint>& points) {
  std::vector<double> x, y;
  for (const auto& p : points) {
    x.push_back(p.angle_rad);
    y.push_back(p.radius_m);
  }
  return PeriodicSpline(x, y, std::numbers::pi);
}

}  // namespace

double cam_list_w0_m(const std::vector<CamPoint>& points, double bore_radius_m) {
  return list_spline(points)(0.0) - bore_radius_m;
}

CamSurface::CamSurface(const Cam& cam, double w0_m, double bore_radius_m)
    : profile_(cam.profile), r_(bore_radius_m), w0_(w0_m), fit_(cam.clearance_m) {
  if (profile_ == CamProfile::List) list_.push_back(list_spline(cam.points));
}

double CamSurface::radius_m(double t) const {
  switch (profile_) {
    case CamProfile::Polar:
      return r_ + w0_ * std::cos(2 * t);
    case CamProfile::Ellipse: {
      const double a = r_ + w0_, b = r_ - w0_;
      return a * b / std::hypot(b * std::cos(t), a * std::sin(t));
    }
    case CamProfile::List:
      return list_[0](t);
  }
  return r_;
}

double CamSurface::standoff_m(double t) const { return radius_m(t) - r_ - fit_; }

double CamSurface::tilt(double t) const {
  switch (profile_) {
    case CamProfile::Polar:
      return -2 * w0_ * std::sin(2 * t) / radius_m(t);
    case CamProfile::Ellipse: {  // ρ = ab/q, q² = b²cos²t + a²sin²t: ρ'/ρ = −q'/q = −(a² − b²)·sin2t/(2q²)
      const double a = r_ + w0_, b = r_ - w0_;
      const double q2 = b * b * std::cos(t) * std::cos(t) + a * a * std::sin(t) * std::sin(t);
      return -(a * a - b * b) * std::sin(2 * t) / (2 * q2);
    }
    case CamProfile::List:
      return list_[0].derivative(t) / list_[0](t);
  }
  return 0.0;
}

}  // namespace sw
