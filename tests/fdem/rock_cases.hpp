//! \file rock_cases.hpp
//! \brief Shared set-ups of the FDEM validation tests: meshes, node selections, running to a time.
#pragma once

#include "blastsim/fdem/mesh.hpp"
#include "blastsim/fdem/rock_solver.hpp"

#include <cmath>
#include <functional>
#include <vector>

namespace blastsim::fdem::testing {

//! Nodes whose initial position satisfies `where`.
inline std::vector<int> nodes_where(const FdemTopology& topo, const std::function<bool(double, double)>& where) {
  std::vector<int> out;
  for (size_t n = 0; n < topo.node_positions.size(); ++n)
    if (where(topo.node_positions[n][0], topo.node_positions[n][1])) out.push_back(static_cast<int>(n));
  return out;
}

//! Appends mesh b to mesh a (two separate bodies in one mesh).
inline TriangleMesh merge(TriangleMesh a, const TriangleMesh& b) {
  const int offset = static_cast<int>(a.vertices.size());
  a.vertices.insert(a.vertices.end(), b.vertices.begin(), b.vertices.end());
  for (auto t : b.triangles) a.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  return a;
}

//! Two strips of near-equilateral triangles meeting along the line y = 0, x in [0, n s]: the only joints
//! are the n edges of that line and the inclined edges inside each strip (none vertical or horizontal),
//! so a uniform pull or shear across y = 0 loads that line most. Strip height s sqrt(3)/2 each side.
inline TriangleMesh two_strips(int n, double s) {
  TriangleMesh m;
  const double h = s * std::sqrt(3.0) / 2;
  auto add = [&](double x, double y) {
    m.vertices.push_back({x, y});
    return static_cast<int>(m.vertices.size()) - 1;
  };
  std::vector<int> mid(n + 1);
  for (int i = 0; i <= n; ++i) mid[i] = add(i * s, 0.0);
  for (int side = -1; side <= 1; side += 2) {
    std::vector<int> outer;  // corner, the n offset vertices, corner
    outer.push_back(add(0.0, side * h));
    for (int i = 0; i < n; ++i) outer.push_back(add((i + 0.5) * s, side * h));
    outer.push_back(add(n * s, side * h));
    for (int i = 0; i < n; ++i) {  // triangle on edge (mid i, mid i+1) with apex outer[i + 1]
      if (side < 0) m.triangles.push_back({outer[i + 1], mid[i + 1], mid[i]});
      else m.triangles.push_back({outer[i + 1], mid[i], mid[i + 1]});
    }
    for (int i = 0; i <= n; ++i) {  // triangle on edge (outer i, outer i+1) with apex mid i
      if (side < 0) m.triangles.push_back({outer[i], outer[i + 1], mid[i]});
      else m.triangles.push_back({outer[i + 1], outer[i], mid[i]});
    }
  }
  return m;
}

//! Lumped node masses [kg/m] of the FDEM topology (rho A / 3 per node of each triangle, as the solver has them).
inline std::vector<double> node_masses(const FdemTopology& topo, double density) {
  std::vector<double> m;
  for (int t = 0; t < topo.triangle_count(); ++t) {
    const auto& a = topo.node_positions[3 * t];
    const auto& b = topo.node_positions[3 * t + 1];
    const auto& c = topo.node_positions[3 * t + 2];
    const double area = 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]));
    for (int k = 0; k < 3; ++k) m.push_back(density * area / 3);
  }
  return m;
}

//! Runs the solver to time `t_end` with steps of dt, calling `each` after every step.
inline void run_to(RockSolver& s, double t_end, double dt, const std::function<void()>& each = {}) {
  while (s.time() < t_end - 1e-12 * t_end) {
    s.step(std::fmin(dt, t_end - s.time()));
    if (each) each();
  }
}

}  // namespace blastsim::fdem::testing
