#pragma once
// Test fixture: a structured TET10 mesh of the box [0,1]^3 (scaled), n³ cubes of six tets each, with interior corner
// nodes moved randomly so the elements are distorted; midside nodes at edge midpoints (straight edges).
#include <map>
#include <random>

#include <Eigen/Geometry>

#include "mesh/tet_mesh.hpp"

namespace sw::test {

inline TetMesh distorted_box(int n, double size, double distortion, unsigned seed = 7) {
  TetMesh m;
  const int np = n + 1;
  auto id = [&](int i, int j, int k) { return (k * np + j) * np + i; };
  std::vector<Eigen::Vector3d> pts(np * np * np);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-distortion, distortion);
  const double h = size / n;
  for (int k = 0; k < np; ++k)
    for (int j = 0; j < np; ++j)
      for (int i = 0; i < np; ++i) {
        Eigen::Vector3d p(i * h, j * h, k * h);
        const bool interior = i > 0 && j > 0 && k > 0 && i < n && j < n && k < n;
        if (interior) p += h * Eigen::Vector3d(jitter(rng), jitter(rng), jitter(rng));
        pts[id(i, j, k)] = p;
      }
  std::map<std::pair<int, int>, int> mid;
  auto midside = [&](int a, int b) {
    const auto key = std::minmax(a, b);
    auto it = mid.find(key);
    if (it != mid.end()) return it->second;
    pts.push_back(0.5 * (pts[a] + pts[b]));
    return mid[key] = static_cast<int>(pts.size() - 1);
  };
  // Kuhn split of a cube into 6 tets along the diagonal 0-7.
  static const int kKuhn[6][4] = {{0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7}, {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7}};
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        int c[8];
        for (int b = 0; b < 8; ++b) c[b] = id(i + (b & 1), j + ((b >> 1) & 1), k + ((b >> 2) & 1));
        for (const auto& t : kKuhn) {
          std::array<int, 4> v = {c[t[0]], c[t[1]], c[t[2]], c[t[3]]};
          const double vol = (pts[v[1]] - pts[v[0]]).dot((pts[v[2]] - pts[v[0]]).cross(pts[v[3]] - pts[v[0]]));
          if (vol < 0) std::swap(v[2], v[3]);
          std::array<int, 10> tet = {v[0], v[1], v[2], v[3], midside(v[0], v[1]), midside(v[1], v[2]),
                                     midside(v[0], v[2]), midside(v[0], v[3]), midside(v[1], v[3]),
                                     midside(v[2], v[3])};
          m.tets.push_back(tet);
          m.region.push_back(0);
        }
      }
  m.nodes.resize(static_cast<Eigen::Index>(pts.size()), 3);
  for (std::size_t i = 0; i < pts.size(); ++i) m.nodes.row(i) = pts[i].transpose();
  return m;
}

/// True for nodes on the box surface.
inline std::vector<bool> box_boundary_nodes(const TetMesh& m, double size) {
  std::vector<bool> on(m.n_nodes());
  constexpr double kTol = 1e-12;
  for (std::size_t i = 0; i < m.n_nodes(); ++i)
    for (int k = 0; k < 3; ++k)
      if (std::abs(m.nodes(i, k)) < kTol * size || std::abs(m.nodes(i, k) - size) < kTol * size) on[i] = true;
  return on;
}

}  // namespace sw::test
