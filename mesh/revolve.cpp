#include <array>
#include "mesh/revolve.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numeric>

#include <Eigen/Geometry>

#include "common/constants.hpp"
#include "common/error.hpp"
#include "mesh/tetgen_mesh.hpp"

namespace sw {
namespace {

Eigen::Vector2d closest_profile_point(const ProfileSurface& s, const Eigen::Vector2d& q) {
  if (s.kind == ProfileSurface::Kind::Line) {
    const Eigen::Vector2d d = s.b - s.a;
    return s.a + d * ((q - s.a).dot(d) / d.squaredNorm());
  }
  const Eigen::Vector2d v = q - s.centre;
  const double n = v.norm();
  return n > 0.0 ? Eigen::Vector2d(s.centre + v * (s.radius / n)) : Eigen::Vector2d(s.centre + Eigen::Vector2d(s.radius, 0));
}

// Interior split parameters t (0 < t < 1, increasing) of the edge qa..qb: sub-segments no longer than `size`, graded
// by the size field where it asks for less. Without refinement on the edge, n equal parts (n = ceil(length / size)).
// With it, the parameters equidistribute ∫ ds / h(s) (sampled finely: h is piecewise smooth and the edges are short
// against its scale away from the points), rounded up to a whole number of parts.
std::vector<double> split_parameters(const Eigen::Vector2d& qa, const Eigen::Vector2d& qb, double size,
                                     const ProfileSizeField& field) {
  const double length = (qb - qa).norm();
  constexpr int kSamples = 2000;
  bool graded = false;
  std::vector<double> density(kSamples + 1);  // length / h at t = k / kSamples
  for (int k = 0; k <= kSamples; ++k) {
    const double h = field.at(qa + (qb - qa) * (static_cast<double>(k) / kSamples), size);
    graded = graded || h < size * (1 - 1e-9);
    density[k] = length / h;
  }
  std::vector<double> t;
  if (!graded) {
    const int n = std::max(1, static_cast<int>(std::ceil(length / size - 1e-9)));
    for (int i = 1; i < n; ++i) t.push_back(static_cast<double>(i) / n);
    return t;
  }
  std::vector<double> cumulative(kSamples + 1, 0.0);  // trapezoidal ∫ density dt
  for (int k = 1; k <= kSamples; ++k) cumulative[k] = cumulative[k - 1] + 0.5 * (density[k - 1] + density[k]) / kSamples;
  const int n = std::max(1, static_cast<int>(std::ceil(cumulative.back() - 1e-9)));
  int k = 0;
  for (int i = 1; i < n; ++i) {
    const double target = cumulative.back() * i / n;
    while (cumulative[k + 1] < target) ++k;
    const double f = (target - cumulative[k]) / (cumulative[k + 1] - cumulative[k]);
    t.push_back((k + f) / kSamples);
  }
  return t;
}

// Union-find over profile vertices.
int find_root(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

// The profile's length scale: the largest distance of a vertex from the origin.
double profile_scale(const std::vector<Eigen::Vector2d>& vertices) {
  double scale = 0.0;
  for (const auto& v : vertices) scale = std::max(scale, v.norm());
  return scale;
}

// The point indices first, first + 1, ..., first + count - 1 (one ring of the revolved PLC).
std::vector<int> consecutive(int first, int count) {
  std::vector<int> r(count);
  std::iota(r.begin(), r.end(), first);
  return r;
}

}  // namespace

double ProfileSizeField::at(const Eigen::Vector2d& p, double edge_size_m) const {
  double h = edge_size_m;
  for (const auto& q : points) h = std::min(h, size_m + growth * (p - q).norm());
  return h;
}

Eigen::Vector3d project_to_surface(const ProfileSurface& s, const Eigen::Vector3d& p) {
  if (s.kind == ProfileSurface::Kind::Fixed) return p;
  const double r = std::hypot(p.x(), p.y());
  const Eigen::Vector2d q = closest_profile_point(s, Eigen::Vector2d(r, p.z()));
  if (r == 0.0) return {q.x(), 0.0, q.y()};
  return {p.x() * (q.x() / r), p.y() * (q.x() / r), q.y()};
}

namespace {

/// det of the TET10 map's Jacobian at natural point (a, b, c), VTK node order.
double tet10_det(const TetMesh& m, const std::array<int, 10>& t, double a, double b, double c) {
  const double L[4] = {1 - a - b - c, a, b, c};
  static const double dL[4][3] = {{-1, -1, -1}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) J.col(k) += (4 * L[i] - 1) * dL[i][k] * m.nodes.row(t[i]).transpose();
  for (int e = 0; e < 6; ++e) {
    const int p = kTetEdges[e][0], q = kTetEdges[e][1];
    for (int k = 0; k < 3; ++k) J.col(k) += 4 * (dL[p][k] * L[q] + L[p] * dL[q][k]) * m.nodes.row(t[4 + e]).transpose();
  }
  return J.determinant();
}

/// True if the curved element stays well shaped: det J at its corners, midsides and centre above a fifth of the
/// straight element's times kMinDetRatio (a projected midside node moved too far for the element's size fails this).
// Smallest det J (at corners, midsides, centre, Gauss points) relative to the straight element accepted for a curved
// one: any positive value keeps the map invertible; a small margin keeps the element usable.
constexpr double kMinDetRatio = 0.02;

bool well_shaped(const TetMesh& m, const std::array<int, 10>& t) {
  const double straight = (m.nodes.row(t[1]) - m.nodes.row(t[0])).dot(
      (m.nodes.row(t[2]) - m.nodes.row(t[0])).cross(m.nodes.row(t[3]) - m.nodes.row(t[0])));
  static const double kPoints[15][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.5, 0, 0},
                                        {0.5, 0.5, 0}, {0, 0.5, 0}, {0, 0, 0.5}, {0.5, 0, 0.5}, {0, 0.5, 0.5},
                                        {0.25, 0.25, 0.25}, {0.1381966, 0.1381966, 0.1381966},
                                        {0.5854102, 0.1381966, 0.1381966}, {0.1381966, 0.5854102, 0.1381966},
                                        {0.1381966, 0.1381966, 0.5854102}};
  for (const auto& p : kPoints)
    if (!(tet10_det(m, t, p[0], p[1], p[2]) > kMinDetRatio * straight)) return false;
  return true;
}

/// Where a projected midside node distorts its element too much (a coarse ring near the axis, a thin layer under a
/// strongly curved surface, an edge on two surfaces), puts that element's midside nodes back on its straight edges: a
/// valid straight element beats an inverted curved one. Repeats, since a node moved back changes its neighbours.
void straighten_distorted(TetMesh& mesh) {
  std::vector<bool> on_boundary(mesh.n_nodes(), false);
  for (const auto& f : mesh.faces)
    for (int v : f.nodes) on_boundary[v] = true;
  auto straighten = [&](const std::array<int, 10>& t, bool boundary_too) {
    for (int e = 0; e < 6; ++e)
      if (boundary_too || !on_boundary[t[4 + e]])
        mesh.nodes.row(t[4 + e]) = 0.5 * (mesh.nodes.row(t[kTetEdges[e][0]]) + mesh.nodes.row(t[kTetEdges[e][1]]));
  };
  // First only the element's interior midside nodes (chords of interior rings), which cost no boundary accuracy;
  // then, for elements still distorted, the boundary ones too.
  for (int pass = 0; pass < 6; ++pass) {
    bool changed = false;
    for (const auto& t : mesh.tets) {
      if (well_shaped(mesh, t)) continue;
      straighten(t, pass >= 2);
      changed = true;
    }
    if (!changed) break;
  }
}

}  // namespace

void project_boundary(TetMesh& mesh, const std::vector<int>& face_surface,
                      const std::vector<ProfileSurface>& surfaces) {
  assert(face_surface.size() == mesh.faces.size());
  auto move = [&](int node, const ProfileSurface& s) {
    const Eigen::Vector3d p = mesh.nodes.row(node);
    mesh.nodes.row(node) = project_to_surface(s, p).transpose();
  };
  // Corners first (each node once per distinct surface it touches; a node on two surfaces meeting at a ring gets
  // both projections, which commute there: the ring lies on both).
  std::vector<std::vector<int>> done(mesh.n_nodes());
  auto once = [&](int node, int s) {
    auto& d = done[node];
    if (std::find(d.begin(), d.end(), s) != d.end()) return false;
    d.push_back(s);
    return true;
  };
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    for (int k = 0; k < 3; ++k)
      if (once(mesh.faces[f].nodes[k], face_surface[f])) move(mesh.faces[f].nodes[k], surfaces[face_surface[f]]);
  for (const auto& t : mesh.tets)
    for (int e = 0; e < 6; ++e)
      mesh.nodes.row(t[4 + e]) = 0.5 * (mesh.nodes.row(t[kTetEdges[e][0]]) + mesh.nodes.row(t[kTetEdges[e][1]]));
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    for (int k = 3; k < 6; ++k)
      if (once(mesh.faces[f].nodes[k], face_surface[f])) move(mesh.faces[f].nodes[k], surfaces[face_surface[f]]);
}

std::vector<int> RevolvedPlc::ring(double r_m, double z_m) const {
  const double scale = profile_scale(vertex_rz);
  for (std::size_t v = 0; v < vertex_rz.size(); ++v)
    if (first[v] >= 0 && count[v] > 1 && (vertex_rz[v] - Eigen::Vector2d(r_m, z_m)).norm() <= 1e-9 * scale)
      return consecutive(first[v], count[v]);
  throw InputError("mesh: no ring of the revolved profile at r = " + std::to_string(r_m * 1e3) +
                   " mm, z = " + std::to_string(z_m * 1e3) + " mm to attach a facet to");
}

namespace {

// A piece of a profile edge after splitting: its two vertices (indices into the split vertex list), the surface it
// lies on, the edge's target size and whether it is horizontal (it then sweeps a planar annulus or disc).
struct Segment {
  int a, b, surface;
  double size;
  bool horizontal;
};

// The profile after step 1: its vertices (the profile's own, then the split points) and its segments.
struct SplitProfile {
  std::vector<Eigen::Vector2d> verts;
  std::vector<Segment> segs;
};

// Per profile vertex the first vertex coincident with it (builders may repeat the corners they share).
std::vector<int> coincident_vertices(const std::vector<Eigen::Vector2d>& V, double eps) {
  std::vector<int> same(V.size());
  for (std::size_t v = 0; v < V.size(); ++v) {
    same[v] = static_cast<int>(v);
    for (std::size_t u = 0; u < v; ++u)
      if ((V[u] - V[v]).norm() <= eps) {
        same[v] = same[u];
        break;
      }
  }
  return same;
}

// Step 1: splits every edge at the profile vertices lying on it (layer lines end on other edges), then into
// sub-segments no longer than its size; points on Circle edges are put on the arc. Edges along the axis are dropped
// (they sweep nothing).
SplitProfile split_edges(const RevolvedProfile& profile, double eps) {
  const auto& V = profile.vertices;
  const std::vector<int> same = coincident_vertices(V, eps);
  SplitProfile out{V, {}};
  for (std::size_t e = 0; e < profile.edges.size(); ++e) {
    const ProfileEdge& E = profile.edges[e];
    const int v0 = same[E.v0], v1 = same[E.v1];
    const Eigen::Vector2d pa = V[v0], pb = V[v1];
    const double size = profile.edge_size_m[e];
    if (pa.x() <= eps && pb.x() <= eps) continue;
    const Eigen::Vector2d d = pb - pa;
    std::vector<std::pair<double, int>> stops = {{0.0, v0}, {1.0, v1}};
    for (int v = 0; v < static_cast<int>(V.size()); ++v) {
      if (same[v] != v || v == v0 || v == v1) continue;
      const double t = (V[v] - pa).dot(d) / d.squaredNorm();
      if (t > 1e-9 && t < 1 - 1e-9 && (pa + t * d - V[v]).norm() <= eps) stops.emplace_back(t, v);
    }
    std::sort(stops.begin(), stops.end());
    const bool horizontal = std::abs(d.y()) <= eps;
    for (std::size_t k = 0; k + 1 < stops.size(); ++k) {
      const int a = stops[k].second, b = stops[k + 1].second;
      const Eigen::Vector2d qa = V[a], qb = V[b];
      const std::vector<double> cuts = split_parameters(qa, qb, size, profile.refine);
      const int n = static_cast<int>(cuts.size()) + 1;
      int prev = a;
      for (int i = 1; i <= n; ++i) {
        int next = b;
        if (i < n) {
          Eigen::Vector2d q = qa + (qb - qa) * cuts[i - 1];
          if (profile.surfaces[E.surface].kind == ProfileSurface::Kind::Circle)
            q = closest_profile_point(profile.surfaces[E.surface], q);
          out.verts.push_back(q);
          next = static_cast<int>(out.verts.size()) - 1;
        }
        out.segs.push_back({prev, next, E.surface, size, horizontal});
        prev = next;
      }
    }
  }
  return out;
}

// Points around a ring of radius r_m no farther apart than size_m: a multiple of 8 (so the axes x, y are node planes),
// at least 8.
int ring_count(double r_m, double size_m) {
  const int n = static_cast<int>(std::ceil(2.0 * kPi * r_m / size_m - 1e-9));
  return std::max(8, (n + 7) / 8 * 8);
}

// Step 2: the angular count per split vertex (0 on the axis). Each ring takes its count from its radius and the
// smallest size of its segments; rings joined by swept (non-horizontal) segments share the largest count of their
// group.
std::vector<int> angular_counts(const SplitProfile& split, const ProfileSizeField& field, double eps) {
  const auto& verts = split.verts;
  const int nv = static_cast<int>(verts.size());
  auto on_axis = [&](int v) { return verts[v].x() <= eps; };
  std::vector<int> parent(nv);
  std::iota(parent.begin(), parent.end(), 0);
  for (const auto& s : split.segs)
    if (!s.horizontal && !on_axis(s.a) && !on_axis(s.b)) parent[find_root(parent, s.a)] = find_root(parent, s.b);
  std::vector<int> group_n(nv, 8);
  for (const auto& s : split.segs)
    for (int v : {s.a, s.b})
      if (!on_axis(v)) {
        const int g = find_root(parent, v);
        const double angular = std::min(s.size, std::max(1.0, field.max_aspect) * field.at(verts[v], s.size));
        group_n[g] = std::max(group_n[g], ring_count(verts[v].x(), angular));
      }
  std::vector<int> n(nv, 0);
  for (int v = 0; v < nv; ++v)
    if (!on_axis(v)) n[v] = group_n[find_root(parent, v)];
  return n;
}

// Step 3: the PLC's points: a ring of N points per off-axis vertex (angle 2 pi k / N), one point per axis vertex that
// a swept segment uses (discs need no axis point).
RevolvedPlc ring_points(const SplitProfile& split, const std::vector<int>& angular_count, double eps) {
  RevolvedPlc out;
  out.vertex_rz = split.verts;
  const auto& verts = out.vertex_rz;
  const int nv = static_cast<int>(verts.size());
  auto on_axis = [&](int v) { return verts[v].x() <= eps; };
  out.first.assign(nv, -1);
  out.count.assign(nv, 0);
  std::vector<bool> used(nv, false);
  for (const auto& s : split.segs)
    for (int v : {s.a, s.b}) used[v] = used[v] || !on_axis(v) || !s.horizontal;
  for (int v = 0; v < nv; ++v) {
    if (!used[v]) continue;
    out.first[v] = static_cast<int>(out.plc.points.size());
    if (on_axis(v)) {
      out.count[v] = 1;
      out.ring_of_point.push_back(-1);
      out.index_in_ring.push_back(0);
      out.plc.points.emplace_back(0.0, 0.0, verts[v].y());
      continue;
    }
    const int n = angular_count[v];
    out.count[v] = n;
    for (int k = 0; k < n; ++k) {
      out.ring_of_point.push_back(v);
      out.index_in_ring.push_back(k);
      const double th = 2.0 * kPi * k / n;
      out.plc.points.emplace_back(verts[v].x() * std::cos(th), verts[v].x() * std::sin(th), verts[v].y());
    }
  }
  return out;
}

// Step 4: the facets each segment sweeps, marker = surface index + 1 (TetGen uses 0 for "none"): a horizontal segment
// an annulus (or a disc from the axis), a segment to the axis a cone of triangles, any other a band of quadrilaterals.
void add_swept_facets(RevolvedPlc& out, const std::vector<Segment>& segs, double eps) {
  const auto& verts = out.vertex_rz;
  const auto& first = out.first;
  const auto& count = out.count;
  auto on_axis = [&](int v) { return verts[v].x() <= eps; };
  auto ring = [&](int v) { return consecutive(first[v], count[v]); };
  for (const auto& s : segs) {
    const int marker = s.surface + 1;
    if (s.horizontal) {
      int lo = s.a, hi = s.b;
      if (verts[lo].x() > verts[hi].x()) std::swap(lo, hi);
      if (on_axis(lo)) {
        out.plc.facets.push_back({{ring(hi)}, {}, marker});
      } else {
        out.plc.facets.push_back({{ring(hi), ring(lo)}, {Eigen::Vector3d(0, 0, verts[lo].y())}, marker});
      }
      continue;
    }
    if (on_axis(s.a) || on_axis(s.b)) {  // cone to a tip on the axis
      const int tip = on_axis(s.a) ? s.a : s.b, base = on_axis(s.a) ? s.b : s.a;
      const int n = count[base];
      for (int k = 0; k < n; ++k)
        out.plc.facets.push_back({{{first[tip], first[base] + k, first[base] + (k + 1) % n}}, {}, marker});
      continue;
    }
    const int n = count[s.a];
    assert(count[s.b] == n);
    for (int k = 0; k < n; ++k) {
      const int k1 = (k + 1) % n;
      out.plc.facets.push_back(
          {{{first[s.a] + k, first[s.a] + k1, first[s.b] + k1, first[s.b] + k}}, {}, marker});
    }
  }
}

// The PLC's regions: each profile region's seed at polar angle 0, its tets bounded by the volume of a regular tet of
// its size.
void add_regions(Plc& plc, const std::vector<ProfileRegion>& regions) {
  for (const auto& r : regions) {
    const double h = r.size_m;
    plc.regions.push_back({Eigen::Vector3d(r.seed.x(), 0.0, r.seed.y()), r.id, h * h * h / (6.0 * std::sqrt(2.0))});
  }
}

}  // namespace

RevolvedPlc revolve_profile(const RevolvedProfile& profile) {
  assert(profile.edge_size_m.size() == profile.edges.size());
  const double eps = 1e-12 * profile_scale(profile.vertices);
  const SplitProfile split = split_edges(profile, eps);
  RevolvedPlc out = ring_points(split, angular_counts(split, profile.refine, eps), eps);
  add_swept_facets(out, split.segs, eps);
  add_regions(out.plc, profile.regions);
  return out;
}

TetMesh mesh_revolved(const RevolvedProfile& profile, const MeshParams& params, std::int64_t max_added_points) {
  return mesh_revolved_plc(revolve_profile(profile), profile.surfaces, params, max_added_points);
}

TetMesh mesh_revolved_plc(const RevolvedPlc& revolved, const std::vector<ProfileSurface>& surfaces,
                          const MeshParams& params, std::int64_t max_added_points) {
  const Plc& plc = revolved.plc;
  const auto& verts = revolved.vertex_rz;
  const auto& count = revolved.count;
  const auto& ring_of_point = revolved.ring_of_point;
  const auto& index_in_ring = revolved.index_in_ring;
  TetgenOptions options;
  options.max_radius_edge_ratio = params.max_radius_edge_ratio;
  options.min_dihedral_deg = params.min_dihedral_deg;
  options.preserve_boundary = true;  // the swept surfaces are already meshed: keep their nodes on the true surfaces
  options.max_added_points = max_added_points;
  TetMesh mesh = tetrahedralize_plc(plc, options);

  std::vector<int> face_surface(mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const int s = mesh.faces[f].marker - 1;
    if (s < 0 || s >= static_cast<int>(surfaces.size()))
      throw InputError("mesh: a boundary face of the revolved profile lies on no profile edge (marker " +
                       std::to_string(mesh.faces[f].marker) + "); the profile is not closed");
    face_surface[f] = s;
  }
  project_boundary(mesh, face_surface, surfaces);
  // Edges between neighbouring points of one ring are chords of a circle about the axis, on boundary and internal
  // surfaces alike (region interfaces, layer surfaces, rims of flat faces): their midside nodes go onto the circle.
  // TetGen keeps the input points first and in order, and -Y adds none on the facets. Points a caller appended
  // after the revolved ones are on no ring.
  const int n_input = static_cast<int>(ring_of_point.size());
  for (const auto& t : mesh.tets)
    for (int e = 0; e < 6; ++e) {
      const int a = t[kTetEdges[e][0]], b = t[kTetEdges[e][1]];
      if (a >= n_input || b >= n_input || ring_of_point[a] < 0 || ring_of_point[a] != ring_of_point[b]) continue;
      const int n = count[ring_of_point[a]];
      const int dk = (index_in_ring[a] - index_in_ring[b] + n) % n;
      if (dk != 1 && dk != n - 1) continue;
      const double r = verts[ring_of_point[a]].x();
      const int m = t[4 + e];
      const double rm = std::hypot(mesh.nodes(m, 0), mesh.nodes(m, 1));
      mesh.nodes(m, 0) *= r / rm;
      mesh.nodes(m, 1) *= r / rm;
    }
  straighten_distorted(mesh);
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) mesh.faces[f].marker = surfaces[face_surface[f]].marker;
  mesh.quality = mesh_quality(mesh);
  return mesh;
}

}  // namespace sw
