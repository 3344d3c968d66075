#include "mesh/shapes.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "common/error.hpp"
#include "mesh/revolve.hpp"
#include "mesh/tetgen_mesh.hpp"

namespace sw {
namespace {


void require_positive(const char* what, double value_m) {
  if (!(value_m > 0.0)) throw InputError(std::string(what) + " = " + mm_text(value_m) + " mm; must be > 0");
}

}  // namespace

TetMesh mesh_tube(double r_inner_m, double r_outer_m, double length_m, const MeshParams& mesh) {
  require_positive("tube inner radius", r_inner_m);
  require_positive("tube length", length_m);
  if (!(r_outer_m > r_inner_m))
    throw InputError("tube outer radius = " + mm_text(r_outer_m) + " mm; must be > inner radius = " + mm_text(r_inner_m) +
                     " mm");
  const WallSize w = wall_size(r_outer_m - r_inner_m, mesh);
  // Profile: bottom and top edges across the wall, inner and outer walls, and w.layers - 1 internal layer lines.
  RevolvedProfile p;
  auto line = [](Eigen::Vector2d a, Eigen::Vector2d b, int marker) {
    ProfileSurface s;
    s.a = a;
    s.b = b;
    s.marker = marker;
    return s;
  };
  auto add_edge = [&](Eigen::Vector2d a, Eigen::Vector2d b, int marker, double size) {
    const int ia = static_cast<int>(p.vertices.size());
    p.vertices.push_back(a);
    p.vertices.push_back(b);
    p.surfaces.push_back(line(a, b, marker));
    p.edges.push_back({ia, ia + 1, static_cast<int>(p.surfaces.size()) - 1});
    p.edge_size_m.push_back(size);
  };
  add_edge({r_inner_m, 0.0}, {r_outer_m, 0.0}, kSurfaceClamped, w.across_m);
  add_edge({r_outer_m, 0.0}, {r_outer_m, length_m}, kSurfaceOuter, w.along_m);
  add_edge({r_outer_m, length_m}, {r_inner_m, length_m}, kSurfaceOpenEnd, w.across_m);
  add_edge({r_inner_m, length_m}, {r_inner_m, 0.0}, kSurfaceInner, w.along_m);
  for (int k = 0; k < w.layers; ++k) {
    const double r = r_inner_m + k * w.across_m;
    if (k > 0) add_edge({r, 0.0}, {r, length_m}, kSurfaceOther, w.along_m);
    p.regions.push_back({Eigen::Vector2d(r + 0.5 * w.across_m, 0.5 * length_m), 0, w.along_m});
  }
  return mesh_revolved(p, mesh);
}

TetMesh mesh_bar(double length_x_m, double width_y_m, double height_z_m, const MeshParams& mesh) {
  require_positive("bar length", length_x_m);
  require_positive("bar width", width_y_m);
  require_positive("bar height", height_z_m);
  const double h = wall_size(std::min(width_y_m, height_z_m), mesh).across_m;
  // The faces are pre-split into a grid of spacing <= h, so the surface mesh has the target size everywhere.
  const int nx = std::max(1, static_cast<int>(std::ceil(length_x_m / h - 1e-9)));
  const int ny = std::max(1, static_cast<int>(std::ceil(width_y_m / h - 1e-9)));
  const int nz = std::max(1, static_cast<int>(std::ceil(height_z_m / h - 1e-9)));
  Plc plc;
  std::vector<int> index((nx + 1) * (ny + 1) * (nz + 1), -1);
  auto id = [&](int i, int j, int k) {
    int& slot = index[(i * (ny + 1) + j) * (nz + 1) + k];
    if (slot < 0) {
      slot = static_cast<int>(plc.points.size());
      plc.points.emplace_back(length_x_m * i / nx, width_y_m * (static_cast<double>(j) / ny - 0.5),
                              height_z_m * (static_cast<double>(k) / nz - 0.5));
    }
    return slot;
  };
  for (int j = 0; j < ny; ++j)
    for (int k = 0; k < nz; ++k) {
      plc.facets.push_back({{{id(0, j, k), id(0, j + 1, k), id(0, j + 1, k + 1), id(0, j, k + 1)}}, {}, kSurfaceClamped});
      plc.facets.push_back(
          {{{id(nx, j, k), id(nx, j + 1, k), id(nx, j + 1, k + 1), id(nx, j, k + 1)}}, {}, kSurfaceBarEnd});
    }
  for (int i = 0; i < nx; ++i) {
    for (int k = 0; k < nz; ++k) {
      plc.facets.push_back({{{id(i, 0, k), id(i + 1, 0, k), id(i + 1, 0, k + 1), id(i, 0, k + 1)}}, {}, kSurfaceOther});
      plc.facets.push_back(
          {{{id(i, ny, k), id(i + 1, ny, k), id(i + 1, ny, k + 1), id(i, ny, k + 1)}}, {}, kSurfaceOther});
    }
    for (int j = 0; j < ny; ++j) {
      plc.facets.push_back({{{id(i, j, 0), id(i + 1, j, 0), id(i + 1, j + 1, 0), id(i, j + 1, 0)}}, {}, kSurfaceOther});
      plc.facets.push_back(
          {{{id(i, j, nz), id(i + 1, j, nz), id(i + 1, j + 1, nz), id(i, j + 1, nz)}}, {}, kSurfaceOther});
    }
  }
  plc.regions.push_back({Eigen::Vector3d(0.5 * length_x_m, 0.0, 0.0), 0, h * h * h / (6.0 * std::sqrt(2.0))});
  TetgenOptions options;
  options.max_radius_edge_ratio = mesh.max_radius_edge_ratio;
  options.min_dihedral_deg = mesh.min_dihedral_deg;
  return tetrahedralize_plc(plc, options);
}

}  // namespace sw
