//! \file mesh.cpp
//! \brief Mesh checks, FDEM topology (owned nodes, joints, boundary edges) and a structured rectangle mesh.
#include "blastsim/fdem/mesh.hpp"

#include "blastsim/core/error.hpp"
#include "splitmix.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <utility>

namespace blastsim::fdem {

namespace {

double signed_area(const TriangleMesh& m, const std::array<int, 3>& t) {
  const auto& a = m.vertices[t[0]];
  const auto& b = m.vertices[t[1]];
  const auto& c = m.vertices[t[2]];
  return 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]));
}

std::string describe(const TriangleMesh& m, size_t t) {
  std::ostringstream os;
  os << "triangle " << t << " (vertices " << m.triangles[t][0] << ", " << m.triangles[t][1] << ", "
     << m.triangles[t][2] << ")";
  return os.str();
}

//! Edge key with the smaller vertex first; value: (triangle, local edge k: vertices k -> k+1).
using EdgeMap = std::map<std::pair<int, int>, std::vector<std::pair<int, int>>>;

EdgeMap edges_of(const TriangleMesh& m) {
  EdgeMap edges;
  for (size_t t = 0; t < m.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = m.triangles[t][k], b = m.triangles[t][(k + 1) % 3];
      edges[{std::min(a, b), std::max(a, b)}].push_back({static_cast<int>(t), k});
    }
  return edges;
}

}  // namespace

void check_mesh(const TriangleMesh& m) {
  if (m.triangles.empty()) throw InputError("mesh has no triangles");
  const int nv = static_cast<int>(m.vertices.size());
  for (size_t t = 0; t < m.triangles.size(); ++t) {
    for (int v : m.triangles[t])
      if (v < 0 || v >= nv)
        throw InputError(describe(m, t) + ": vertex index " + std::to_string(v) + " outside [0, " +
                         std::to_string(nv) + ")");
    double longest = 0;
    for (int k = 0; k < 3; ++k) {
      const auto& a = m.vertices[m.triangles[t][k]];
      const auto& b = m.vertices[m.triangles[t][(k + 1) % 3]];
      longest = std::max(longest, std::hypot(b[0] - a[0], b[1] - a[1]));
    }
    const double area = signed_area(m, m.triangles[t]);
    if (!(std::fabs(area) > 1e-12 * longest * longest))
      throw InputError(describe(m, t) + " is degenerate (area " + std::to_string(area) + " m2)");
    if (area < 0) throw InputError(describe(m, t) + " is inverted (clockwise); triangles must be counter-clockwise");
  }
  for (const auto& [edge, users] : edges_of(m)) {
    if (users.size() > 2)
      throw InputError("non-manifold mesh: edge between vertices " + std::to_string(edge.first) + " and " +
                       std::to_string(edge.second) + " is shared by " + std::to_string(users.size()) + " triangles");
    if (users.size() == 2) {
      // Two counter-clockwise triangles traverse a shared edge in opposite directions.
      const auto& [t0, k0] = users[0];
      const auto& [t1, k1] = users[1];
      if (m.triangles[t0][k0] == m.triangles[t1][k1])
        throw InputError("inconsistent orientation across the edge between vertices " + std::to_string(edge.first) +
                         " and " + std::to_string(edge.second));
    }
  }
}

std::vector<std::array<double, 2>> joint_midpoints(const FdemTopology& topo) {
  std::vector<std::array<double, 2>> mid(topo.joints.size());
  for (std::size_t j = 0; j < mid.size(); ++j) {
    const std::array<double, 2>& p = topo.node_positions[topo.joints[j].a0];
    const std::array<double, 2>& q = topo.node_positions[topo.joints[j].a1];
    mid[j] = {0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1])};
  }
  return mid;
}

FdemTopology build_topology(const TriangleMesh& m) {
  check_mesh(m);
  FdemTopology topo;
  topo.node_positions.reserve(3 * m.triangles.size());
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) {
      topo.node_positions.push_back(m.vertices[t[k]]);
      topo.node_vertex.push_back(t[k]);
    }
  for (const auto& [edge, users] : edges_of(m)) {  // std::map: deterministic order
    const auto& [ta, ka] = users[0];
    if (users.size() == 1) {
      topo.boundary_edges.push_back({ta, 3 * ta + ka, 3 * ta + (ka + 1) % 3});
      continue;
    }
    const auto& [tb, kb] = users[1];
    topo.joints.push_back({ta, tb, 3 * ta + ka, 3 * ta + (ka + 1) % 3, 3 * tb + kb, 3 * tb + (kb + 1) % 3});
  }
  return topo;
}

TriangleMesh structured_rectangle(int nx, int ny, double x0, double x1, double y0, double y1) {
  if (nx < 1 || ny < 1) throw InputError("structured_rectangle needs at least one square each way");
  TriangleMesh m;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) m.vertices.push_back({x0 + (x1 - x0) * i / nx, y0 + (y1 - y0) * j / ny});
  auto v = [&](int i, int j) { return j * (nx + 1) + i; };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      if ((i + j) % 2 == 0) {
        m.triangles.push_back({v(i, j), v(i + 1, j), v(i + 1, j + 1)});
        m.triangles.push_back({v(i, j), v(i + 1, j + 1), v(i, j + 1)});
      } else {
        m.triangles.push_back({v(i, j), v(i + 1, j), v(i, j + 1)});
        m.triangles.push_back({v(i + 1, j), v(i + 1, j + 1), v(i, j + 1)});
      }
    }
  return m;
}

NamedMesh ring_disc_with_hole(double cx, double cy, double r, double r_hole, double h, double growth) {
  if (!(r_hole > 0) || !(r > r_hole) || !(h > 0) || !(h < r - r_hole))
    throw InputError("ring_disc_with_hole: need 0 < hole radius < radius and 0 < element size < radius - hole radius");
  if (!(growth >= 1.0 && growth <= 2.0)) throw InputError("ring_disc_with_hole: the growth ratio must be in [1, 2]");
  // Ring widths w0 growth^k adding up to r - r_hole, the first about h; the element size of circle k is the mean
  // width of the rings beside it (h itself for equal rings).
  const double span = r - r_hole;
  const int rings = growth == 1.0 ? std::max(1, static_cast<int>(std::lround(span / h)))
                                  : std::max(1, static_cast<int>(std::lround(std::log1p(span * (growth - 1) / h) /
                                                                             std::log(growth))));
  const double w0 = growth == 1.0 ? span / rings : span * (growth - 1) / (std::pow(growth, rings) - 1);
  std::vector<double> radius_of(rings + 1, r_hole), size_of(rings + 1, h);
  for (int k = 1; k <= rings; ++k) {
    radius_of[k] = growth == 1.0 ? r_hole + k * span / rings : radius_of[k - 1] + w0 * std::pow(growth, k - 1);
    if (growth != 1.0) size_of[k] = w0 * std::pow(growth, std::min(k, rings - 1) - (k < rings ? 0.5 : 0.0));
  }
  if (growth != 1.0) size_of[0] = w0, radius_of[rings] = r;
  NamedMesh out;
  std::vector<int> first(rings + 2, 0), count(rings + 1, 0);
  std::vector<double> offset(rings + 1, 0.0);
  for (int k = 0; k <= rings; ++k) {
    const double radius = radius_of[k];
    count[k] = std::max(6, static_cast<int>(std::lround(2 * M_PI * radius / size_of[k])));
    offset[k] = k % 2 ? M_PI / count[k] : 0.0;
    first[k + 1] = first[k] + count[k];
    for (int m = 0; m < count[k]; ++m) {
      const double th = offset[k] + 2 * M_PI * m / count[k];
      out.mesh.vertices.push_back({cx + radius * std::cos(th), cy + radius * std::sin(th)});
    }
  }
  auto vertex = [&](int k, int m) { return first[k] + m % count[k]; };
  for (int k = 0; k < rings; ++k) {  // merge walk between circle k (inner) and k + 1 (outer), by angle
    const int ni = count[k], no = count[k + 1];
    auto angle = [&](int c, int m) { return offset[c] + 2 * M_PI * m / count[c]; };
    int i = 0, o = 0;
    while (i < ni || o < no) {
      const bool advance_outer = i == ni || (o < no && angle(k + 1, o + 1) <= angle(k, i + 1));
      if (advance_outer) {
        out.mesh.triangles.push_back({vertex(k, i), vertex(k + 1, o), vertex(k + 1, o + 1)});
        ++o;
      } else {
        out.mesh.triangles.push_back({vertex(k, i), vertex(k + 1, o), vertex(k, i + 1)});
        ++i;
      }
    }
  }
  for (int m = 0; m < count[0]; ++m) out.boundary_groups["hole"].push_back({vertex(0, m + 1), vertex(0, m)});
  for (int m = 0; m < count[rings]; ++m) out.boundary_groups["outer"].push_back({vertex(rings, m), vertex(rings, m + 1)});
  check_mesh(out.mesh);
  return out;
}

using detail::splitmix64;
using detail::unit_interval;

void perturb_mesh(TriangleMesh& mesh, double fraction, std::uint64_t seed, const std::vector<int>& fixed) {
  if (!(fraction >= 0 && fraction <= 0.25))
    throw InputError("mesh perturbation fraction = " + std::to_string(fraction) + ": must be in [0, 0.25] of the local element size");
  check_mesh(mesh);
  if (fraction == 0) return;
  const size_t nv = mesh.vertices.size();
  std::vector<char> keep(nv, 0);
  std::vector<double> shortest(nv, 1e308);
  std::map<std::pair<int, int>, int> edge_count;  // an edge of one triangle only is on the boundary
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      const int a = t[k], b = t[(k + 1) % 3];
      ++edge_count[{std::min(a, b), std::max(a, b)}];
      const double len = std::hypot(mesh.vertices[b][0] - mesh.vertices[a][0], mesh.vertices[b][1] - mesh.vertices[a][1]);
      shortest[a] = std::min(shortest[a], len), shortest[b] = std::min(shortest[b], len);
    }
  for (const auto& [edge, count] : edge_count)
    if (count == 1) keep[edge.first] = keep[edge.second] = 1;
  for (int v : fixed) {
    if (v < 0 || static_cast<size_t>(v) >= nv) throw InputError("perturb_mesh: fixed vertex " + std::to_string(v) + " does not exist");
    keep[v] = 1;
  }
  for (size_t v = 0; v < nv; ++v) {
    if (keep[v] || shortest[v] >= 1e308) continue;
    const std::uint64_t h = splitmix64(seed ^ splitmix64(v));
    const double radius = fraction * shortest[v] * std::sqrt(unit_interval(h));
    const double angle = 2 * M_PI * unit_interval(splitmix64(h));
    mesh.vertices[v][0] += radius * std::cos(angle);
    mesh.vertices[v][1] += radius * std::sin(angle);
  }
  check_mesh(mesh);
}

}  // namespace blastsim::fdem
