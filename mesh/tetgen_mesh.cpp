#include "mesh/tetgen_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <unordered_map>

#include <Eigen/Dense>
#include <tetgen.h>

#include <cerrno>
#include <csignal>
#include <sys/time.h>
#include <sys/wait.h>
#include <unistd.h>

#include "common/constants.hpp"
#include "common/error.hpp"
#include "mesh/tetgen_terminate.hpp"

namespace sw {
namespace {

/// TetGen -o2 stores the six midside nodes of a tet at [4..9] for edges (2,3),(0,3),(0,1),(1,2),(1,3),(2,0)
/// (measured; the unit test checks every midside node is the midpoint of its edge). VTK slot k takes TetGen slot:
constexpr int kTetgenSlotOfVtkMidside[6] = {6, 7, 9, 5, 8, 4};

std::string tetgen_failure(int code) {
  switch (code) {
    case 1: return "TetGen ran out of memory";
    case 2: return "TetGen hit an internal error";
    case 3: return "the boundary facets intersect each other";
    case 4: return "an input feature is smaller than TetGen's tolerance (a very short edge or thin facet)";
    case 5: return "two input facets are too close to each other";
    case 10: return "the input PLC is invalid";
    default: return "TetGen failed with code " + std::to_string(code);
  }
}

std::uint64_t face_key(int a, int b, int c) {
  std::array<int, 3> v{a, b, c};
  std::sort(v.begin(), v.end());
  return (static_cast<std::uint64_t>(v[0]) << 42) | (static_cast<std::uint64_t>(v[1]) << 21) |
         static_cast<std::uint64_t>(v[2]);
}

// Fills a tetgenio from the PLC. tetgenio frees its arrays with delete[], so allocate with new[].
void fill_input(const Plc& plc, tetgenio& in) {
  in.firstnumber = 0;
  in.numberofpoints = static_cast<int>(plc.points.size());
  in.pointlist = new REAL[3 * plc.points.size()];
  for (std::size_t i = 0; i < plc.points.size(); ++i)
    for (int d = 0; d < 3; ++d) in.pointlist[3 * i + d] = plc.points[i][d];

  in.numberoffacets = static_cast<int>(plc.facets.size());
  in.facetlist = new tetgenio::facet[plc.facets.size()];
  in.facetmarkerlist = new int[plc.facets.size()];
  for (std::size_t f = 0; f < plc.facets.size(); ++f) {
    const PlcFacet& src = plc.facets[f];
    tetgenio::facet& dst = in.facetlist[f];
    tetgenio::init(&dst);
    dst.numberofpolygons = static_cast<int>(src.polygons.size());
    dst.polygonlist = new tetgenio::polygon[src.polygons.size()];
    for (std::size_t p = 0; p < src.polygons.size(); ++p) {
      tetgenio::polygon& poly = dst.polygonlist[p];
      tetgenio::init(&poly);
      poly.numberofvertices = static_cast<int>(src.polygons[p].size());
      poly.vertexlist = new int[src.polygons[p].size()];
      std::copy(src.polygons[p].begin(), src.polygons[p].end(), poly.vertexlist);
    }
    if (!src.holes.empty()) {
      dst.numberofholes = static_cast<int>(src.holes.size());
      dst.holelist = new REAL[3 * src.holes.size()];
      for (std::size_t h = 0; h < src.holes.size(); ++h)
        for (int d = 0; d < 3; ++d) dst.holelist[3 * h + d] = src.holes[h][d];
    }
    in.facetmarkerlist[f] = src.marker;
  }
  if (!plc.holes.empty()) {
    in.numberofholes = static_cast<int>(plc.holes.size());
    in.holelist = new REAL[3 * plc.holes.size()];
    for (std::size_t h = 0; h < plc.holes.size(); ++h)
      for (int d = 0; d < 3; ++d) in.holelist[3 * h + d] = plc.holes[h][d];
  }
  if (!plc.regions.empty()) {
    in.numberofregions = static_cast<int>(plc.regions.size());
    in.regionlist = new REAL[5 * plc.regions.size()];
    for (std::size_t r = 0; r < plc.regions.size(); ++r) {
      for (int d = 0; d < 3; ++d) in.regionlist[5 * r + d] = plc.regions[r].seed[d];
      in.regionlist[5 * r + 3] = plc.regions[r].id;
      // TetGen reads a non-positive region volume as "no bound".
      in.regionlist[5 * r + 4] = plc.regions[r].max_volume_m3 > 0.0 ? plc.regions[r].max_volume_m3 : -1.0;
    }
  }
}

std::string switches_for(const Plc& plc, const TetgenOptions& o) {
  char buf[64];
  std::string s = "pQo2";
  if (o.max_radius_edge_ratio > 0.0) {
    std::snprintf(buf, sizeof buf, "q%.6g", o.max_radius_edge_ratio);
    s += buf;
    if (o.min_dihedral_deg > 0.0) {
      std::snprintf(buf, sizeof buf, "/%.6g", o.min_dihedral_deg);
      s += buf;
    }
  }
  if (!plc.regions.empty()) s += "A";
  const bool region_bounds = std::any_of(plc.regions.begin(), plc.regions.end(),
                                         [](const PlcRegion& r) { return r.max_volume_m3 > 0.0; });
  if (region_bounds) s += "a";
  if (o.max_volume_m3 > 0.0) {
    std::snprintf(buf, sizeof buf, "a%.9g", o.max_volume_m3);
    s += buf;
  }
  if (o.preserve_boundary) s += "Y";
  if (o.max_added_points > 0) s += "S" + std::to_string(o.max_added_points);
  return s;
}

// What the parent needs from tetgenio's output.
struct RawTetgenOutput {
  int n_points = 0, n_tets = 0, n_trifaces = 0;
  std::vector<double> points;       // 3 per point
  std::vector<int> tets;            // 10 per tet, TetGen's -o2 order
  std::vector<double> region;       // 1 per tet (empty without regions)
  std::vector<int> trifaces;        // 3 per face
  std::vector<int> trifacemarkers;  // 1 per face
};

template <class T>
void write_all(int fd, const T* data, std::size_t count) {
  const char* p = reinterpret_cast<const char*>(data);
  std::size_t left = count * sizeof(T);
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n <= 0) ::_exit(98);
    p += n;
    left -= static_cast<std::size_t>(n);
  }
}

template <class T>
bool read_all(int fd, T* data, std::size_t count) {
  char* p = reinterpret_cast<char*>(data);
  std::size_t left = count * sizeof(T);
  while (left > 0) {
    const ssize_t n = ::read(fd, p, left);
    if (n <= 0) return false;
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  return true;
}

// Child side: mesh and write the output to fd, then _exit. TetGen 1.5 frees its memory in terminatetetgen() and
// again in ~tetgenmesh() while the thrown int unwinds, so a failing run crashes the process instead of reaching a
// catch. Running it in a forked child keeps that crash away from the caller; tetgen_terminate.cpp replaces
// terminatetetgen() so the child exits with status kExitBase + TetGen's code where the library calls it.
[[noreturn]] void tetgen_child(const Plc& plc, const std::string& switches, double time_limit_s, int fd) {
  // The budget: SIGALRM (default action: terminate) ends the child when TetGen runs past it.
  itimerval limit{};
  limit.it_value.tv_sec = static_cast<time_t>(time_limit_s);
  limit.it_value.tv_usec = static_cast<suseconds_t>((time_limit_s - std::floor(time_limit_s)) * 1e6);
  ::setitimer(ITIMER_REAL, &limit, nullptr);
  tetgenio in, out;
  fill_input(plc, in);
  try {
    std::string sw = switches;  // TetGen takes a non-const char*
    tetrahedralize(sw.data(), &in, &out);
  } catch (int code) {
    ::_exit(detail::tetgen_exit_base() + code);
  } catch (...) {
    ::_exit(detail::tetgen_exit_base() + 1);
  }
  const int header[4] = {out.numberofpoints, out.numberoftetrahedra, out.numberoftetrahedronattributes,
                         out.numberoftrifaces};
  if (out.numberofcorners != 10) ::_exit(97);
  write_all(fd, header, 4);
  write_all(fd, out.pointlist, 3 * static_cast<std::size_t>(out.numberofpoints));
  write_all(fd, out.tetrahedronlist, 10 * static_cast<std::size_t>(out.numberoftetrahedra));
  for (int t = 0; t < out.numberoftetrahedra && out.numberoftetrahedronattributes > 0; ++t)
    write_all(fd, out.tetrahedronattributelist + t * out.numberoftetrahedronattributes, 1);
  write_all(fd, out.trifacelist, 3 * static_cast<std::size_t>(out.numberoftrifaces));
  std::vector<int> markers(out.numberoftrifaces, 0);
  if (out.trifacemarkerlist) std::copy(out.trifacemarkerlist, out.trifacemarkerlist + out.numberoftrifaces,
                                       markers.begin());
  write_all(fd, markers.data(), markers.size());
  ::close(fd);
  ::_exit(0);
}

RawTetgenOutput run_tetgen_isolated(const Plc& plc, const std::string& switches, double time_limit_s,
                                    const std::string& request) {
  int fds[2];
  if (::pipe(fds) != 0) throw InputError("mesh: " + request + ": cannot create a pipe for the TetGen process");
  std::fflush(nullptr);
  const pid_t pid = ::fork();
  if (pid < 0) throw InputError("mesh: " + request + ": cannot fork the TetGen process");
  if (pid == 0) {
    ::close(fds[0]);
    tetgen_child(plc, switches, time_limit_s, fds[1]);
  }
  ::close(fds[1]);
  RawTetgenOutput out;
  int header[4] = {0, 0, 0, 0};
  bool ok = read_all(fds[0], header, 4);
  if (ok) {
    out.n_points = header[0];
    out.n_tets = header[1];
    out.n_trifaces = header[3];
    out.points.resize(3 * static_cast<std::size_t>(out.n_points));
    out.tets.resize(10 * static_cast<std::size_t>(out.n_tets));
    out.region.resize(header[2] > 0 ? out.n_tets : 0);
    out.trifaces.resize(3 * static_cast<std::size_t>(out.n_trifaces));
    out.trifacemarkers.resize(out.n_trifaces);
    ok = read_all(fds[0], out.points.data(), out.points.size()) &&
         read_all(fds[0], out.tets.data(), out.tets.size()) &&
         read_all(fds[0], out.region.data(), out.region.size()) &&
         read_all(fds[0], out.trifaces.data(), out.trifaces.size()) &&
         read_all(fds[0], out.trifacemarkers.data(), out.trifacemarkers.size());
  }
  ::close(fds[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0 && ok) return out;
  std::string why;
  if (WIFEXITED(status) && WEXITSTATUS(status) > detail::tetgen_exit_base())
    why = tetgen_failure(WEXITSTATUS(status) - detail::tetgen_exit_base());
  else if (WIFSIGNALED(status) && WTERMSIG(status) == SIGALRM)
  {
    char budget[32];
    std::snprintf(budget, sizeof budget, "%g", time_limit_s);
    why = std::string("TetGen did not finish within its budget of ") + budget +
          " s (it stalls on some inputs and has no limit of its own)";
  }
  else if (WIFSIGNALED(status))
    why = "TetGen crashed (signal " + std::to_string(WTERMSIG(status)) +
          "), which TetGen 1.5 does after rejecting an input (intersecting facets or a too-small feature)";
  else
    why = "TetGen's output could not be read back (exit status " + std::to_string(WEXITSTATUS(status)) + ")";
  throw InputError("mesh: " + request + " failed: " + why +
                   "; check the geometry (overlapping or degenerate surfaces) or coarsen mesh.size_mm");
}

double signed_volume6(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                      const Eigen::Vector3d& d) {
  return (b - a).cross(c - a).dot(d - a);
}

// Face of a tet opposite corner k, ordered for an outward normal of a positively oriented tet.
constexpr int kTetFaces[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};

// What TetGen was asked to do, for the messages: its switches and the PLC's size.
std::string describe_request(const Plc& plc, const std::string& switches) {
  return "TetGen -" + switches + " on a PLC of " + std::to_string(plc.points.size()) + " points, " +
         std::to_string(plc.facets.size()) + " facets, " + std::to_string(plc.regions.size()) + " regions";
}

// Refuses a run that reached its node budget: as many tet corners beyond the PLC's points as the budget allows
// (TetGen's -S stops adding points there, leaving a mesh that is not the refinement asked for).
void check_node_budget(const RawTetgenOutput& out, const Plc& plc, const TetgenOptions& options,
                       const std::string& request) {
  if (options.max_added_points <= 0) return;
  std::vector<bool> corner(out.n_points, false);
  for (int t = 0; t < out.n_tets; ++t)
    for (int k = 0; k < 4; ++k) corner[out.tets[10 * static_cast<std::size_t>(t) + k]] = true;
  const auto added = std::count(corner.begin(), corner.end(), true) - static_cast<std::int64_t>(plc.points.size());
  if (added >= options.max_added_points)
    throw InputError("mesh: " + request + " reached its node budget of " + std::to_string(options.max_added_points) +
                     " added points, far beyond the model-size estimate; coarsen mesh.size_mm or check the geometry");
}

// The TET10 mesh of TetGen's nodes and tets, in VTK node order and positively oriented, with each tet's region.
TetMesh tets_from_output(const RawTetgenOutput& out) {
  TetMesh mesh;
  mesh.nodes.resize(out.n_points, 3);
  for (int i = 0; i < out.n_points; ++i)
    for (int d = 0; d < 3; ++d) mesh.nodes(i, d) = out.points[3 * i + d];
  const int nt = out.n_tets;
  mesh.tets.resize(nt);
  mesh.region.assign(nt, 0);
  for (int t = 0; t < nt; ++t) {
    const int* src = out.tets.data() + 10 * t;
    std::array<int, 10>& tet = mesh.tets[t];
    for (int k = 0; k < 4; ++k) tet[k] = src[k];
    for (int k = 0; k < 6; ++k) tet[4 + k] = src[kTetgenSlotOfVtkMidside[k]];
    const Eigen::Vector3d a = mesh.nodes.row(tet[0]), b = mesh.nodes.row(tet[1]), c = mesh.nodes.row(tet[2]),
                          d = mesh.nodes.row(tet[3]);
    if (signed_volume6(a, b, c, d) < 0.0) {  // swap corners 1 and 2: edges 01<->02, 13<->23
      std::swap(tet[1], tet[2]);
      std::swap(tet[4], tet[6]);
      std::swap(tet[8], tet[9]);
    }
    if (!out.region.empty()) mesh.region[t] = static_cast<int>(std::lround(out.region[t]));
  }
  return mesh;
}

// The boundary faces (faces of exactly one tet), as (tet, local face) sorted for a deterministic order.
std::vector<std::pair<int, int>> boundary_tet_faces(const TetMesh& mesh) {
  std::unordered_map<std::uint64_t, std::pair<int, int>> seen;  // key -> (tet, local face), or tet = -1 if shared
  seen.reserve(4 * mesh.tets.size());
  for (int t = 0; t < static_cast<int>(mesh.tets.size()); ++t)
    for (int k = 0; k < 4; ++k) {
      const auto& tet = mesh.tets[t];
      const auto key = face_key(tet[kTetFaces[k][0]], tet[kTetFaces[k][1]], tet[kTetFaces[k][2]]);
      auto [it, inserted] = seen.try_emplace(key, t, k);
      if (!inserted) it->second.first = -1;
    }
  std::vector<std::pair<int, int>> boundary;
  for (const auto& [key, tf] : seen)
    if (tf.first >= 0) boundary.push_back(tf);
  std::sort(boundary.begin(), boundary.end());
  return boundary;
}

// The mesh's boundary faces with outward normals, their midside nodes looked up from the tets' edges, each marked
// with the marker TetGen gave its subface (boundary and region-interface faces), kSurfaceOther where it gave none.
std::vector<BoundaryFace> boundary_faces(const TetMesh& mesh, const RawTetgenOutput& out) {
  std::unordered_map<std::uint64_t, int> marker_of;
  marker_of.reserve(2 * static_cast<std::size_t>(out.n_trifaces));
  for (int f = 0; f < out.n_trifaces; ++f) {
    const int* v = out.trifaces.data() + 3 * f;
    marker_of[face_key(v[0], v[1], v[2])] = out.trifacemarkers[f];
  }
  auto edge_slot = [](int i, int j) {
    for (int e = 0; e < 6; ++e)
      if ((kTetEdges[e][0] == i && kTetEdges[e][1] == j) || (kTetEdges[e][0] == j && kTetEdges[e][1] == i))
        return 4 + e;
    return -1;
  };
  const std::vector<std::pair<int, int>> boundary = boundary_tet_faces(mesh);
  std::vector<BoundaryFace> faces;
  faces.reserve(boundary.size());
  for (const auto& [t, k] : boundary) {
    const auto& tet = mesh.tets[t];
    BoundaryFace face;
    const int* c = kTetFaces[k];
    for (int i = 0; i < 3; ++i) face.nodes[i] = tet[c[i]];
    for (int i = 0; i < 3; ++i) face.nodes[3 + i] = tet[edge_slot(c[i], c[(i + 1) % 3])];
    const auto it = marker_of.find(face_key(face.nodes[0], face.nodes[1], face.nodes[2]));
    face.marker = it != marker_of.end() ? it->second : kSurfaceOther;
    faces.push_back(face);
  }
  return faces;
}

}  // namespace

TetMesh tetrahedralize_plc(const Plc& plc, const TetgenOptions& options) {
  const std::string switches = switches_for(plc, options);
  const std::string request = describe_request(plc, switches);
  if (plc.points.size() < 4 || plc.facets.size() < 4)
    throw InputError("mesh: " + request + "; a closed PLC needs at least 4 points and 4 facets");
  const RawTetgenOutput out = run_tetgen_isolated(plc, switches, options.time_limit_s, request);
  if (out.n_tets == 0)
    throw InputError("mesh: " + request + " produced no tetrahedra; is the boundary closed?");
  check_node_budget(out, plc, options, request);
  TetMesh mesh = tets_from_output(out);
  mesh.faces = boundary_faces(mesh, out);
  mesh.quality = mesh_quality(mesh);
  return mesh;
}

MeshQuality mesh_quality(const TetMesh& mesh) {
  MeshQuality q;
  q.min_dihedral_deg = 180.0;
  q.max_dihedral_deg = 0.0;
  q.max_radius_edge_ratio = 0.0;
  for (const auto& tet : mesh.tets) {
    Eigen::Vector3d p[4];
    for (int k = 0; k < 4; ++k) p[k] = mesh.nodes.row(tet[k]);
    // Outward face normals; the dihedral angle at edge (i,j) is pi minus the angle between the normals of the two
    // faces sharing it (faces opposite the other two corners).
    Eigen::Vector3d n[4];
    for (int k = 0; k < 4; ++k) {
      n[k] = (p[kTetFaces[k][1]] - p[kTetFaces[k][0]]).cross(p[kTetFaces[k][2]] - p[kTetFaces[k][0]]);
      n[k].normalize();
    }
    double shortest = std::numeric_limits<double>::infinity();
    for (const auto& e : kTetEdges) {
      int others[2], m = 0;
      for (int k = 0; k < 4; ++k)
        if (k != e[0] && k != e[1]) others[m++] = k;
      const double cosang = std::clamp(-n[others[0]].dot(n[others[1]]), -1.0, 1.0);
      const double ang = std::acos(cosang) * kDeg;
      q.min_dihedral_deg = std::min(q.min_dihedral_deg, ang);
      q.max_dihedral_deg = std::max(q.max_dihedral_deg, ang);
      shortest = std::min(shortest, (p[e[0]] - p[e[1]]).norm());
    }
    // Circumcentre c solves 2 (p_i - p_0) . c' = |p_i - p_0|^2 with c' = c - p_0.
    Eigen::Matrix3d A;
    Eigen::Vector3d rhs;
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector3d d = p[i + 1] - p[0];
      A.row(i) = 2.0 * d.transpose();
      rhs[i] = d.squaredNorm();
    }
    const double radius = A.partialPivLu().solve(rhs).norm();
    q.max_radius_edge_ratio = std::max(q.max_radius_edge_ratio, radius / shortest);
  }
  return q;
}

namespace {
// Gauss-Legendre nodes and weights on [0, 1].
struct Gauss1D {
  std::vector<double> x, w;
};
Gauss1D gauss01(int n) {
  Gauss1D g;
  if (n == 3) {
    const double a = std::sqrt(0.6);
    g.x = {0.5 * (1 - a), 0.5, 0.5 * (1 + a)};
    g.w = {5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0};
  } else {  // n == 6
    const double xs[6] = {-0.9324695142031521, -0.6612093864662645, -0.2386191860831969,
                          0.2386191860831969,  0.6612093864662645,  0.9324695142031521};
    const double ws[6] = {0.1713244923791704, 0.3607615730481386, 0.4679139345726910,
                          0.4679139345726910, 0.3607615730481386, 0.1713244923791704};
    for (int i = 0; i < 6; ++i) {
      g.x.push_back(0.5 * (1 + xs[i]));
      g.w.push_back(0.5 * ws[i]);
    }
  }
  return g;
}
}  // namespace

double mesh_volume(const TetMesh& mesh) {
  // det J of a TET10 is a cubic in (x,y,z); through the collapse x=u, y=v(1-u), z=w(1-u)(1-v) (Jacobian
  // (1-u)^2 (1-v)) the integrand is at most degree 5 per variable, so 3-point Gauss per direction is exact.
  const Gauss1D g = gauss01(3);
  struct Point { double L[4]; double w; };
  std::vector<Point> pts;
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = 0; j < 3; ++j)
      for (std::size_t k = 0; k < 3; ++k) {
        const double u = g.x[i], v = g.x[j], w = g.x[k];
        const double x = u, y = v * (1 - u), z = w * (1 - u) * (1 - v);
        pts.push_back({{1 - x - y - z, x, y, z}, g.w[i] * g.w[j] * g.w[k] * (1 - u) * (1 - u) * (1 - v)});
      }
  double volume = 0.0;
  for (const auto& tet : mesh.tets) {
    Eigen::Matrix<double, 10, 3> X;
    for (int a = 0; a < 10; ++a) X.row(a) = mesh.nodes.row(tet[a]);
    for (const auto& p : pts) {
      // dN/dL for N_corner = L(2L-1), N_mid(i,j) = 4 L_i L_j; dx/dxi_k = sum_a X_a (dN_a/dL_k - dN_a/dL_0).
      Eigen::Matrix<double, 10, 4> dNdL = Eigen::Matrix<double, 10, 4>::Zero();
      for (int c = 0; c < 4; ++c) dNdL(c, c) = 4 * p.L[c] - 1;
      for (int e = 0; e < 6; ++e) {
        const int i = kTetEdges[e][0], j = kTetEdges[e][1];
        dNdL(4 + e, i) = 4 * p.L[j];
        dNdL(4 + e, j) = 4 * p.L[i];
      }
      Eigen::Matrix3d J;
      for (int k = 0; k < 3; ++k) J.col(k) = X.transpose() * (dNdL.col(k + 1) - dNdL.col(0));
      volume += p.w * J.determinant();
    }
  }
  return volume;
}

double boundary_area(const TetMesh& mesh, int marker) {
  const Gauss1D g = gauss01(6);
  double area = 0.0;
  for (const auto& f : mesh.faces) {
    if (f.marker != marker) continue;
    Eigen::Matrix<double, 6, 3> X;
    for (int a = 0; a < 6; ++a) X.row(a) = mesh.nodes.row(f.nodes[a]);
    for (std::size_t i = 0; i < g.x.size(); ++i)
      for (std::size_t j = 0; j < g.x.size(); ++j) {
        const double u = g.x[i], v = g.x[j];
        const double s = u, t = v * (1 - u);  // collapsed square -> triangle, Jacobian (1-u)
        const double L[3] = {1 - s - t, s, t};
        // TRI6: corners L(2L-1), midsides (0,1),(1,2),(2,0): 4 L_i L_j. Derivatives w.r.t. (s, t).
        Eigen::Matrix<double, 6, 3> dNdL = Eigen::Matrix<double, 6, 3>::Zero();
        for (int c = 0; c < 3; ++c) dNdL(c, c) = 4 * L[c] - 1;
        const int ed[3][2] = {{0, 1}, {1, 2}, {2, 0}};
        for (int e = 0; e < 3; ++e) {
          dNdL(3 + e, ed[e][0]) = 4 * L[ed[e][1]];
          dNdL(3 + e, ed[e][1]) = 4 * L[ed[e][0]];
        }
        const Eigen::Vector3d xs = X.transpose() * (dNdL.col(1) - dNdL.col(0));
        const Eigen::Vector3d xt = X.transpose() * (dNdL.col(2) - dNdL.col(0));
        area += g.w[i] * g.w[j] * (1 - u) * xs.cross(xt).norm();
      }
  }
  return area;
}

}  // namespace sw
