#include "app/reconcile_baseline.hpp"

#include <cmath>
#include <fstream>

#include <nlohmann/json.hpp>

#include "common/error.hpp"
#include "kinematics/backlash.hpp"
#include "kinematics/neutral_curve.hpp"

namespace sw::app {

using reconcile::Kind;

namespace {

double compliance_from_fem(const std::string& path) {
  std::ifstream f(path);
  if (!f) throw InputError(path + ": cannot be read; give the FEM result.json written by `strainwave fem`");
  nlohmann::json j;
  try {
    f >> j;
  } catch (const std::exception& e) {
    throw InputError(path + ": not valid JSON (" + std::string(e.what()) + ")");
  }
  if (!j.contains("compliance_rad_per_Nm") || !j["compliance_rad_per_Nm"].is_number())
    throw InputError(path + ": compliance_rad_per_Nm missing or not a number; expected the FEM result of `strainwave fem`");
  const double c = j["compliance_rad_per_Nm"].get<double>();
  if (!(c > 0.0)) throw InputError(path + ": compliance_rad_per_Nm = " + std::to_string(c) + "; must be > 0");
  return c;
}

std::optional<int> meta_int(const reconcile::Recording* r, const std::string& key) {
  if (!r) return std::nullopt;
  const auto v = r->meta_number(key);
  if (!v) return std::nullopt;
  return static_cast<int>(std::lround(*v));
}

double radial_deformation(const Case& c) {
  if (c.wave_generator && c.wave_generator->radial_deformation_m) return *c.wave_generator->radial_deformation_m;
  return c.gear->module_m * (c.gear->teeth_circular - c.gear->teeth_flexspline) / 2.0;
}

}  // namespace

reconcile::Baseline make_baseline(Kind kind, const BaselineSources& src, std::vector<std::string>& notes) {
  reconcile::Baseline b;
  const Case* c = src.case_file ? &*src.case_file : nullptr;
  // Teeth: the case wins; the recording's metadata fills in and is checked against it.
  const auto zf_meta = meta_int(src.recording, "teeth_flexspline");
  const auto zc_meta = meta_int(src.recording, "teeth_circular");
  if (c && c->gear) {
    b.teeth_flexspline = c->gear->teeth_flexspline;
    b.teeth_circular = c->gear->teeth_circular;
    b.pitch_radius_m = 0.5 * c->gear->module_m * c->gear->teeth_flexspline;
    if ((zf_meta && *zf_meta != b.teeth_flexspline) || (zc_meta && *zc_meta != b.teeth_circular))
      notes.push_back("the case (" + c->path + ") has teeth z_f = " + std::to_string(b.teeth_flexspline) +
                      ", z_c = " + std::to_string(b.teeth_circular) + " but the recording's metadata says z_f = " +
                      (zf_meta ? std::to_string(*zf_meta) : "?") + ", z_c = " + (zc_meta ? std::to_string(*zc_meta) : "?") +
                      "; the case is used");
  } else {
    if (zf_meta) b.teeth_flexspline = *zf_meta;
    if (zc_meta) b.teeth_circular = *zc_meta;
  }
  switch (kind) {
    case Kind::Torsion:
      if (src.compliance) {
        b.compliance_rad_per_Nm = *src.compliance;
        notes.push_back("C_tau = " + std::to_string(*src.compliance) + " rad/(N*m) from --compliance");
      } else if (!src.fem_result.empty()) {
        b.compliance_rad_per_Nm = compliance_from_fem(src.fem_result);
        notes.push_back("C_tau from " + src.fem_result);
      } else {
        throw InputError("--fem: missing; a torsion baseline needs C_tau: give --fem DIR/result.json (from "
                         "`strainwave fem CASE.toml`) or --compliance RAD_PER_NM");
      }
      break;
    case Kind::Transmission:
      if (b.teeth_flexspline <= 0 || b.teeth_circular <= 0)
        throw InputError((c ? c->path : std::string("case")) +
                         ": [gear] teeth missing; the transmission baseline needs z_f and z_c (case [gear] or the "
                         "recording's teeth_flexspline/teeth_circular metadata)");
      break;
    case Kind::Backlash: {
      if (!c || !c->gear)
        throw InputError((c ? c->path : std::string("case")) +
                         ": [gear] missing; the backlash baseline (basic kinematic model) needs the gear and flexspline");
      const double rm = rim_mean_radius(c->flexspline);
      const NeutralCurve curve = c->wave_generator
                                     ? generator_neutral_curve(rm, radial_deformation(*c), *c->wave_generator)
                                     : cam_neutral_curve(rm, radial_deformation(*c));
      const BacklashModel model = make_backlash_model(*c->gear, curve);
      b.backlash_um = [model](double wg_angle_rad) { return 1e6 * min_backlash_m(model, wg_angle_rad, 0.0); };
      notes.push_back("backlash baseline: basic kinematic model (phi0 = 0) of " + c->path);
      break;
    }
    case Kind::Dynamics:
      throw InputError("kind = dynamics; reconcile does not analyse dynamics recordings yet");
  }
  return b;
}

}  // namespace sw::app
