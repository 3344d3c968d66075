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

const std::vector<CaseKey<WaveGeneratorParams>>& wave_generator_keys() {
  using W = WaveGeneratorParams;
  const auto is = [](std::initializer_list<const char*> models) {
    std::vector<std::string> names(models.begin(), models.end());
    return [names](const W& w) {
      for (const auto& n : names)
        if (n == model_name(w.model)) return true;
      return false;
    };
  };
  auto beta = [](const W& w) -> std::optional<KeyValue> {
    if (const auto* f = std::get_if<FourForce>(&w.model)) return file_units(f->beta_rad, kPi / 180);
    if (const auto* r = std::get_if<Rollers>(&w.model)) return file_units(r->beta_rad, kPi / 180);
    return std::nullopt;
  };
  auto cam_value = [](auto read) {
    return [read](const W& w) -> std::optional<KeyValue> {
      if (const Cam* cam = cam_of(w)) return read(*cam);
      return std::nullopt;
    };
  };
  CaseKey<W> model{"model", KeyKind::Choice, "", {}, {"four_force", "two_force", "forces", "cam", "rollers"},
                   "four forces at +-beta_deg from each end of the major axis, two on it, a list of forces, an "
                   "elliptical cam (a body that pushes) or rollers at +-beta_deg (bodies that push)"};
  model.get = [](const W& w) -> std::optional<KeyValue> { return std::string(model_name(w.model)); };
  model.set = [](W&, const KeyValue&) {};
  CaseKey<W> beta_key{"beta_deg", KeyKind::Number, "deg", within(0, 90, true, true), {},
                      "where the four forces or the rollers sit from each end of the major axis"};
  beta_key.get = beta;
  beta_key.set = [](W&, const KeyValue&) {};
  CaseKey<W> profile{"profile", KeyKind::Choice, "", {}, {"polar", "ellipse", "list"},
                     "the cam's outline: a polar two-lobe curve, an ellipse, or a list of points"};
  profile.get = cam_value([](const Cam& c) -> KeyValue {
    return std::string(c.profile == CamProfile::Ellipse ? "ellipse" : c.profile == CamProfile::List ? "list" : "polar");
  });
  profile.set = [](W&, const KeyValue&) {};
  CaseKey<W> fit{"fit_um", KeyKind::Number, "um", {}, {},
                 "the cam's radial fit to the bore: clearance > 0, interference < 0; smaller in size than w0"};
  fit.get = cam_value([](const Cam& c) -> KeyValue { return file_units(c.clearance_m, 1e-6); });
  fit.set = [](W&, const KeyValue&) {};
  static const std::vector<CaseKey<W>> keys = {
      std::move(model),
      std::move(beta_key).only_when(is({"four_force", "rollers"}), "model = \"four_force\" or \"rollers\""),
      optional_number_key<W>("radial_deformation_mm", &W::radial_deformation_m, 1e-3, "mm", above(0),
                             "w0, the generator's radial push on the bore at the major axis; the forces scale to it")
          .with_default("required for a cam or rollers (a list cam: its radius at 0 deg less the bore); else "
                        "none, and force_N sets the forces"),
      number_key<W>("force_N", &W::force_N, 1, "N", above(0),
                    "the total of one end's forces when radial_deformation_mm is not given")
          .only_when(is({"four_force", "two_force", "forces"}), "model = \"four_force\", \"two_force\" or \"forces\""),
      number_key<W>("axial_position_mm", &W::axial_position_m, 1e-3, "mm", at_least(0),
                    "the generator band's centre from the open end, <= flexspline.length_mm"),
      number_key<W>("band_width_mm", &W::band_width_m, 1e-3, "mm", above(0), "axial width of the generator's band"),
      std::move(profile).only_when(is({"cam"}), "model = \"cam\""),
      structured_key<W>("profile_points", KeyKind::List,
                        "[{angle_deg, radius_mm}, ...]: 4 or more points over a half turn from the major axis, angles "
                        "increasing in [0, 180)")
          .only_when(is({"cam"}), "model = \"cam\" and profile = \"list\""),
      std::move(fit).only_when(is({"cam"}), "model = \"cam\"").with_default("0"),
      structured_key<W>("forces", KeyKind::List,
                        "[{angle_deg, weight > 0}, ...]: the forces at one end of the major axis (the other end's "
                        "mirror them)")
          .only_when(is({"forces"}), "model = \"forces\""),
      structured_key<W>("bearing", KeyKind::Table,
                        "the ball bearing between the cam and the bore, [wave_generator.bearing] below; absent: a "
                        "rigid generator"),
  };
  return keys;
}

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
  std::visit(overloaded{[&](const Cam& c) {
                          const auto cam = std::make_shared<const CamSurface>(
                              c, w.radial_deformation_m.value_or(0.0), bore_radius_m);
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
