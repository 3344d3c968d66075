#include "generator/wave_generator.hpp"

#include <memory>
#include <numbers>
#include <stdexcept>

#include "common/constants.hpp"
#include "common/overloaded.hpp"
#include "generator/cam_profile.hpp"

namespace sw {
namespace {
}  // namespace

const char* model_name(const GeneratorModel& m) {
  return std::visit(overloaded{[](const FourForce&) { return "four_force"; },
                               [](const TwoForce&) { return "two_force"; },
                               [](const GivenForces&) { return "forces"; }, [](const Cam&) { return "cam"; },
                               [](const Rollers&) { return "rollers"; }},
                    m);
}

bool pushes_only(const GeneratorModel& m) {
  return std::visit(overloaded{[](const FourForce&) { return false; }, [](const TwoForce&) { return false; },
                               [](const GivenForces&) { return false; }, [](const Cam&) { return true; },
                               [](const Rollers&) { return true; }},
                    m);
}

std::vector<WaveGeneratorForce> generator_forces(const WaveGeneratorParams& w) {
  const auto four = [](double beta) -> std::vector<WaveGeneratorForce> {
    return {{beta, 0.5}, {-beta, 0.5}, {kPi + beta, 0.5}, {kPi - beta, 0.5}};
  };
  return std::visit(
      overloaded{[&](const FourForce& f) { return four(f.beta_rad); },
                 [&](const Rollers& r) { return four(r.beta_rad); },  // where the rollers touch (for ring theory)
                 [](const TwoForce&) { return std::vector<WaveGeneratorForce>{{0.0, 1.0}, {kPi, 1.0}}; },
                 [](const GivenForces& g) { return g.forces; },
                 [](const Cam&) -> std::vector<WaveGeneratorForce> {
                   throw std::logic_error("generator_forces: a cam's forces come from its contact");
                 }},
      w.model);
}

double point_force_share(const GeneratorModel& m) { return std::holds_alternative<FourForce>(m) ? 0.5 : 1.0; }

StationLayout station_layout(const WaveGeneratorParams& w, double bore_radius_m, double spacing_rad) {
  StationLayout s;
  s.unilateral = pushes_only(w.model);
  const auto every_spacing = [&] {
    for (int k = 0; k * spacing_rad < kPi - 1e-9; ++k) s.angle_rad.push_back(k * spacing_rad);
  };
  const auto radial_support = [&] {  // the given forces: stations all round the band, for radial support
    every_spacing();
    s.obstacle_m = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(s.angle_rad.size()));
  };
  std::visit(overloaded{[&](const Cam&) {
                          const auto cam = std::make_shared<const CamSurface>(w, bore_radius_m);
                          every_spacing();
                          s.tilt = [cam](double t) { return cam->tilt(t); };
                          s.obstacle_m.resize(static_cast<Eigen::Index>(s.angle_rad.size()));
                          for (std::size_t j = 0; j < s.angle_rad.size(); ++j)
                            s.obstacle_m[static_cast<Eigen::Index>(j)] = 2 * cam->standoff_m(s.angle_rad[j]);
                        },
                        [&](const Rollers& r) {
                          // Two pairs: β with π + β, π − β with −β. A roller's normal passes through its centre:
                          // radial where it touches. 2 per metre the rollers stand out; scaled to w0.
                          s.angle_rad = {r.beta_rad, kPi - r.beta_rad};
                          s.obstacle_m = Eigen::Vector2d(2.0, 2.0);
                        },
                        [&](const FourForce&) { radial_support(); }, [&](const TwoForce&) { radial_support(); },
                        [&](const GivenForces&) { radial_support(); }},
             w.model);
  return s;
}

}  // namespace sw
