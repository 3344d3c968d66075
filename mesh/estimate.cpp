#include "mesh/estimate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <sstream>
#include <vector>

#include <Eigen/Core>

#include "common/constants.hpp"
#include "common/error.hpp"
#include "gear/tooth_profile.hpp"
#include "mesh/flexspline_sizes.hpp"
#include "mesh/shapes.hpp"

namespace sw {

namespace {

// TET10 nodes per layered cell (along² × across) of a wall, measured: the seed cup (182,783 nodes at 0.6 mm, 2
// layers) and the size-17 cup (119,688 at 0.8 mm, 1 layer) both give 11.8 (within 1 %); the structured tube mesh of
// mesh_tube() gives 20.6 (tube_torsion.toml: 147,864 nodes).
constexpr double kNodesPerCellCup = 11.8;
constexpr double kNodesPerCellTube = 20.6;
// nnz(L) ≈ c · n_eq^(4/3) for nested dissection on these thin 3-D shells, measured: seed cup c = 7.7 (3.39e8 at
// 540,783 equations), tube 6.1, size-17 cup 5.8. The largest is used, so the estimate errs on the safe side.
constexpr double kFactorCoefficient = 7.7;
// Peak resident memory ≈ 1.5 × the factor's 8-byte values (seed cup: 4.09 GB for a 2.71 GB factor; tube benches
// 0.75–1.08 × (factor + mesh)), plus ~2 kB per node for the mesh, stresses and output.
constexpr double kPeakOverFactor = 1.5;
constexpr double kBytesPerNode = 2048.0;

/// Nodes of a wall region of volume V and thickness t meshed with the case's sizes.
double cells(double volume_m3, double thickness_m, const MeshParams& mesh) {
  if (volume_m3 <= 0 || thickness_m <= 0) return 0.0;
  const WallSize w = wall_size(thickness_m, mesh);
  return volume_m3 / (w.along_m * w.along_m * w.across_m);
}

double annulus(double r_in, double r_out, double length) { return kPi * (r_out * r_out - r_in * r_in) * length; }

// Nodes per cell (h_meridian² × h_angular) in the graded zone of corner_size_field, measured on the seed cup at
// 0.6 mm / 2 layers: 18,686 and 45,571 nodes added at corner_levels 2 and 3 against 13.5 and 13.8 × the integral below.
constexpr double kNodesPerCellCorner = 13.7;

/// Cell coordinates for a midpoint rule on [lo, hi] graded toward the coordinates `at` (the corners' r or z): steps
/// from h0 / 4 growing by 15 % away from each, never longer than `coarse`.
std::vector<double> graded_cells(double lo, double hi, std::vector<double> at, double h0, double coarse) {
  std::vector<double> x = {lo, hi};
  for (const double c : at)
    for (const double dir : {-1.0, 1.0})
      for (double d = 0.25 * h0, step = 0.25 * h0; c + dir * d > lo && c + dir * d < hi; step = std::min(1.15 * step, coarse), d += step)
        x.push_back(c + dir * d);
  for (const double c : at) x.push_back(c);
  std::sort(x.begin(), x.end());
  x.erase(std::unique(x.begin(), x.end()), x.end());
  return x;
}

/// Nodes the cup's corner size field adds to the uniform mesh of the diaphragm and the boss: ∫ 2πr (ρ_field − ρ_base)
/// over the section, the densities from the edge lengths (meridian h, angular min(aspect · h, base)).
double corner_refinement_nodes(const FlexsplineParams& f, const MeshParams& mesh) {
  const ProfileSizeField field = corner_size_field(f, mesh);
  if (field.points.empty()) return 0.0;
  const double td = f.diaphragm_thickness_m, rb = f.boss_radius_m, ri = f.inner_radius_m, hb = 2.0 * td;
  const WallSize wd = wall_size(td, mesh);
  const double boss = kBossSizeFactor * mesh.size_m;
  const double reach = (boss - field.size_m) / field.growth;  // beyond it the field asks for nothing
  const std::vector<double> rs = graded_cells(std::max(0.0, rb - reach), std::min(ri, rb + reach), {rb}, field.size_m, wd.along_m);
  const std::vector<double> zs = graded_cells(0.0, hb, {0.0, td}, field.size_m, wd.across_m);
  double n = 0.0;
  for (std::size_t i = 0; i + 1 < rs.size(); ++i)
    for (std::size_t j = 0; j + 1 < zs.size(); ++j) {
      const Eigen::Vector2d p(0.5 * (rs[i] + rs[i + 1]), 0.5 * (zs[j] + zs[j + 1]));
      const bool in_boss = p.x() < rb;
      if (!in_boss && p.y() > td) continue;
      const double base = in_boss ? boss : wd.along_m;
      const double h = field.at(p, base);
      const double rho = 1.0 / (h * h * std::min(base, field.max_aspect * h));
      const double rho0 = in_boss ? 1.0 / (boss * boss * boss) : 1.0 / (wd.along_m * wd.along_m * wd.across_m);
      n += 2.0 * kPi * p.x() * (rs[i + 1] - rs[i]) * (zs[j + 1] - zs[j]) * std::max(rho - rho0, 0.0);
    }
  return kNodesPerCellCorner * n;
}

}  // namespace

ModelSizeEstimate estimate_model_size(const FlexsplineParams& f, const std::optional<GearParams>& gear,
                                      const MeshParams& mesh) {
  const double ri = f.inner_radius_m, ro = ri + f.wall_thickness_m, L = f.length_m, w = f.rim_width_m;
  const bool cup = f.shape == FlexsplineShape::Cup;
  const double td = cup ? f.diaphragm_thickness_m : 0.0;
  if (!(mesh.size_m > 0) || mesh.wall_layers < 1) return {};  // wall_size() refuses these with their own message
  double n = cells(annulus(ri, ro, std::max(L - w - td, 0.0)), ro - ri, mesh);
  if (f.teeth == TeethModel::Explicit && gear) {
    // The rim under the roots as a wall, the teeth (half the band from root to tip) at their own edge lengths: as one
    // wall of the band's thickness they were counted 3.5× short (seed cup, 1.5 mm: 2.4e5 equations against 6.1e5).
    const GearRadii r = gear_radii(*gear);
    const ToothMeshSize t = tooth_mesh_size(*gear, mesh);
    n += cells(annulus(ri, r.root_f, w), r.root_f - ri, mesh);
    n += 0.5 * annulus(r.root_f, r.tip_f, w) / (t.across_m * t.across_m * t.axial_m);
  } else {
    const double rr = f.teeth == TeethModel::None ? ro : rim_outer_radius(f, gear);
    n += cells(annulus(ri, rr, w), rr - ri, mesh);
  }
  if (cup) {
    n += cells(annulus(f.boss_radius_m, ro, td), td, mesh);
    const double sboss = kBossSizeFactor * mesh.size_m;
    n += annulus(0.0, f.boss_radius_m, 2.0 * td) / (sboss * sboss * sboss);
  }
  const bool plain_tube = !cup && f.teeth == TeethModel::None;
  const double nodes = n * (plain_tube ? kNodesPerCellTube : kNodesPerCellCup) + corner_refinement_nodes(f, mesh);
  ModelSizeEstimate e;
  e.nodes = nodes;
  e.equations = 3.0 * nodes;
  e.factor_nnz = kFactorCoefficient * std::pow(e.equations, 4.0 / 3.0);
  e.peak_bytes = kPeakOverFactor * 8.0 * e.factor_nnz + kBytesPerNode * nodes;
  e.mesh_text = mesh_size_text(mesh);
  return e;
}

double available_memory_bytes() {
  std::ifstream in("/proc/meminfo");
  std::string key;
  double kb = 0;
  std::string unit;
  while (in >> key >> kb >> unit)
    if (key == "MemAvailable:") return kb * 1024.0;
  return 0.0;
}

namespace {
std::string fmt_g(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.3g", v);
  return b;
}
}  // namespace

void refuse_if_too_large(const ModelSizeEstimate& e, double limit_bytes, const std::string& file) {
  const bool machine = limit_bytes <= 0;
  const double limit = machine ? available_memory_bytes() : limit_bytes;
  if (limit <= 0 || e.peak_bytes <= limit) return;
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "%s: the %s would have about %.3g nodes and %.3g equations and need about %.3g GB%s; %s %.3g GB. ",
                file.c_str(), e.model.c_str(), e.nodes, e.equations, e.peak_bytes / 1e9,
                e.factor_nnz > 0 ? (" (factor " + fmt_g(e.factor_nnz) + " nonzeros)").c_str() : "",
                machine ? "this machine has" : "--max-memory allows", limit / 1e9);
  throw InputError(buf + std::string("At ") + e.mesh_text + ": " + e.remedy);
}

}  // namespace sw
