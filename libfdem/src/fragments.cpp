//! \file fragments.cpp
//! \brief Host analysis of rock states: fragments, sieve sizes, size distribution and its fits, damage zone.
#include "blastsim/fdem/fragments.hpp"

#include "blastsim/core/error.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <string>

namespace blastsim::fdem {

namespace {
//! Area [m2] of triangle t from per-node coordinates x, y (node 3t + k is its corner k), positive when its corners
//! run counter-clockwise, as the mesh's do.
double triangle_area(const std::vector<double>& x, const std::vector<double>& y, size_t t) {
  const size_t n = 3 * t;
  return 0.5 * ((x[n + 1] - x[n]) * (y[n + 2] - y[n]) - (x[n + 2] - x[n]) * (y[n + 1] - y[n]));
}

using Point = std::array<double, 2>;

double cross(const Point& o, const Point& a, const Point& b) {
  return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

//! Convex hull, counter-clockwise, without collinear points (Andrew's monotone chain).
std::vector<Point> convex_hull(std::vector<Point> p) {
  std::sort(p.begin(), p.end());
  p.erase(std::unique(p.begin(), p.end()), p.end());
  if (p.size() < 3) return p;
  std::vector<Point> h(2 * p.size());
  size_t k = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (size_t i = p.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  h.resize(k - 1);
  return h;
}

//! Solves the small dense system A x = b (Gaussian elimination with partial pivoting); false if singular.
template <int N>
bool solve(std::array<std::array<double, N>, N> A, std::array<double, N> b, std::array<double, N>& x) {
  for (int c = 0; c < N; ++c) {
    int piv = c;
    for (int r = c + 1; r < N; ++r)
      if (std::fabs(A[r][c]) > std::fabs(A[piv][c])) piv = r;
    if (!(std::fabs(A[piv][c]) > 0)) return false;
    std::swap(A[c], A[piv]), std::swap(b[c], b[piv]);
    for (int r = c + 1; r < N; ++r) {
      const double f = A[r][c] / A[c][c];
      for (int k = c; k < N; ++k) A[r][k] -= f * A[c][k];
      b[r] -= f * b[c];
    }
  }
  for (int c = N - 1; c >= 0; --c) {
    double s = b[c];
    for (int k = c + 1; k < N; ++k) s -= A[c][k] * x[k];
    x[c] = s / A[c][c];
  }
  return true;
}

//! Levenberg-Marquardt on parameters q (Marquardt 1963): minimises the sum over points of (model(q, x) - P)^2
//! with a forward-difference Jacobian. Returns the sum of squares at the end.
template <int N>
double levenberg_marquardt(std::array<double, N>& q, const std::vector<double>& x, const std::vector<double>& P,
                           const std::function<double(const std::array<double, N>&, double)>& model) {
  auto sse = [&](const std::array<double, N>& p) {
    double s = 0;
    for (size_t i = 0; i < x.size(); ++i) s += std::pow(model(p, x[i]) - P[i], 2);
    return std::isfinite(s) ? s : std::numeric_limits<double>::infinity();
  };
  double f = sse(q), lambda = 1e-3;
  for (int it = 0; it < 500; ++it) {
    std::array<std::array<double, N>, N> JtJ{};
    std::array<double, N> Jtr{};
    for (size_t i = 0; i < x.size(); ++i) {
      const double r = model(q, x[i]) - P[i];
      std::array<double, N> J{};
      for (int k = 0; k < N; ++k) {
        std::array<double, N> qk = q;
        const double h = 1e-7 * std::max(1.0, std::fabs(q[k]));
        qk[k] += h;
        J[k] = (model(qk, x[i]) - model(q, x[i])) / h;
      }
      for (int a = 0; a < N; ++a) {
        Jtr[a] += J[a] * r;
        for (int b = 0; b < N; ++b) JtJ[a][b] += J[a] * J[b];
      }
    }
    bool improved = false;
    while (lambda < 1e12) {
      std::array<std::array<double, N>, N> A = JtJ;
      std::array<double, N> rhs{}, step{};
      for (int a = 0; a < N; ++a) A[a][a] *= 1 + lambda, rhs[a] = -Jtr[a];
      if (solve<N>(A, rhs, step)) {
        std::array<double, N> trial = q;
        for (int a = 0; a < N; ++a) trial[a] += step[a];
        const double ft = sse(trial);
        if (ft < f) {
          const double gain = f - ft;
          q = trial, lambda = std::max(lambda / 10, 1e-12), improved = true;
          const bool converged = gain <= 1e-14 * f;
          f = ft;
          if (converged) return f;
          break;
        }
      }
      lambda *= 10;
    }
    if (!improved) break;
  }
  return f;
}

//! R^2 and RMS of a fitted passing function over the points.
template <class Fit, class Model>
void fit_quality(Fit& fit, const std::vector<double>& x, const std::vector<double>& P, Model model) {
  double mean = 0, ss_res = 0, ss_tot = 0;
  for (double p : P) mean += p / P.size();
  for (size_t i = 0; i < x.size(); ++i) ss_res += std::pow(model(x[i]) - P[i], 2), ss_tot += std::pow(P[i] - mean, 2);
  fit.rms = std::sqrt(ss_res / x.size());
  fit.r_squared = ss_tot > 0 ? 1 - ss_res / ss_tot : 0;
}

//! The points of a passing curve strictly between 0 and 1 (where both fits are defined).
void interior_points(const std::vector<double>& size, const std::vector<double>& passing, std::vector<double>& x,
                     std::vector<double>& P) {
  if (size.size() != passing.size()) throw InputError("passing curve: size and passing have different lengths");
  for (size_t i = 0; i < size.size(); ++i)
    if (passing[i] > 0 && passing[i] < 1 && size[i] > 0) x.push_back(size[i]), P.push_back(passing[i]);
}

//! Least-squares line Y = slope X + intercept; false when the X do not vary.
bool line_fit(const std::vector<double>& X, const std::vector<double>& Y, double& slope, double& intercept) {
  const double n = static_cast<double>(X.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (size_t i = 0; i < X.size(); ++i) sx += X[i], sy += Y[i], sxx += X[i] * X[i], sxy += X[i] * Y[i];
  const double det = n * sxx - sx * sx;
  if (!(det > 1e-300 * n * sxx)) return false;
  slope = (n * sxy - sx * sy) / det;
  intercept = (sy - slope * sx) / n;
  return true;
}

}  // namespace

double minimum_feret_width(const std::vector<Point>& points) {
  const std::vector<Point> h = convex_hull(points);
  if (h.size() < 3) return 0;
  double width = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < h.size(); ++i) {  // the hull is small (a fragment's outline): O(h^2) is enough
    const Point& a = h[i];
    const Point& b = h[(i + 1) % h.size()];
    const double len = std::hypot(b[0] - a[0], b[1] - a[1]);
    double far = 0;
    for (const Point& p : h) far = std::max(far, cross(a, b, p) / len);
    width = std::min(width, far);
  }
  return width;
}

std::vector<Fragment> measure_fragments(const RockSnapshot& s, const std::vector<int>& labels, double density,
                                        int min_triangles) {
  const size_t T = s.x.size() / 3;
  if (labels.size() != T)
    throw InputError("measure_fragments: " + std::to_string(labels.size()) + " labels for " + std::to_string(T) +
                     " triangles");
  if (!(density > 0)) throw InputError("measure_fragments: density = " + std::to_string(density) + ": must be > 0");
  if (min_triangles < 1)
    throw InputError("measure_fragments: min_triangles = " + std::to_string(min_triangles) + ": must be >= 1");
  std::vector<int> index(T, -1);
  std::vector<Fragment> out;
  std::vector<std::vector<Point>> nodes;
  for (size_t t = 0; t < T; ++t) {
    const int L = labels[t];
    if (L < 0 || static_cast<size_t>(L) > t)
      throw InputError("measure_fragments: label " + std::to_string(L) + " of triangle " + std::to_string(t) +
                       " is not a triangle index <= its own");
    if (index[L] < 0) {
      index[L] = static_cast<int>(out.size());
      out.push_back(Fragment{});
      out.back().label = L;
      nodes.emplace_back();
    }
    Fragment& f = out[index[L]];
    const size_t n = 3 * t;
    const double m = density * triangle_area(s.x0, s.y0, t);
    f.triangles += 1;
    f.area += triangle_area(s.x, s.y, t);
    f.mass += m;
    for (int k = 0; k < 3; ++k) {
      f.centroid[0] += m / 3 * s.x[n + k], f.centroid[1] += m / 3 * s.y[n + k];  // lumped node masses m / 3
      f.velocity[0] += m / 3 * s.vx[n + k], f.velocity[1] += m / 3 * s.vy[n + k];
      nodes[index[L]].push_back({s.x[n + k], s.y[n + k]});
    }
  }
  for (size_t i = 0; i < out.size(); ++i) {
    Fragment& f = out[i];
    for (int k = 0; k < 2; ++k) f.centroid[k] /= f.mass, f.velocity[k] /= f.mass;
    f.equivalent_diameter = std::sqrt(4 * f.area / M_PI);
    f.fines = f.triangles < min_triangles;
    f.sieve_size = minimum_feret_width(nodes[i]);
  }
  return out;
}

double swebrec_passing(double x, double x50, double xmax, double b) {
  if (x <= 0) return 0;
  if (x >= xmax) return 1;
  return 1 / (1 + std::pow(std::log(xmax / x) / std::log(xmax / x50), b));
}

double rosin_rammler_passing(double x, double x50, double n) {
  return x <= 0 ? 0 : 1 - std::exp(-std::log(2.0) * std::pow(x / x50, n));
}

RosinRammlerFit fit_rosin_rammler(const std::vector<double>& size, const std::vector<double>& passing) {
  RosinRammlerFit fit;
  std::vector<double> x, P;
  interior_points(size, passing, x, P);
  if (x.size() < 3) return fit;
  // Start: the straight line of ln(-ln(1 - P)) = n ln x + ln(ln 2) - n ln x50 (the Rosin-Rammler plot).
  std::vector<double> X, Y;
  for (size_t i = 0; i < x.size(); ++i) X.push_back(std::log(x[i])), Y.push_back(std::log(-std::log(1 - P[i])));
  double slope, intercept;
  if (!line_fit(X, Y, slope, intercept) || !(slope > 0)) return fit;
  std::array<double, 2> q{(std::log(std::log(2.0)) - intercept) / slope, std::log(slope)};  // ln x50, ln n
  levenberg_marquardt<2>(q, x, P, [](const std::array<double, 2>& p, double xi) {
    return rosin_rammler_passing(xi, std::exp(p[0]), std::exp(p[1]));
  });
  fit.x50 = std::exp(q[0]), fit.n = std::exp(q[1]);
  fit.valid = std::isfinite(fit.x50) && std::isfinite(fit.n);
  fit_quality(fit, x, P, [&](double xi) { return rosin_rammler_passing(xi, fit.x50, fit.n); });
  return fit;
}

SwebrecFit fit_swebrec(const std::vector<double>& size, const std::vector<double>& passing) {
  SwebrecFit fit;
  std::vector<double> x, P;
  interior_points(size, passing, x, P);
  if (x.size() < 4) return fit;
  const double largest = *std::max_element(size.begin(), size.end());
  // Parameters q = (ln x50, logit((xmax / x50 - 1) / (R - 1)), ln b): x50 > 0, b > 0 and 1 < xmax / x50 < R for
  // every q. Without the bound R a sample of a few large pieces drives xmax to infinity and b with it (the
  // function's limit is a log-logistic law); R = 100 is far above the ratios of measured muck piles (2-20).
  constexpr double R = kSwebrecMaxRatio;
  auto ratio = [](double q1) { return 1 + (R - 1) / (1 + std::exp(-q1)); };
  auto model = [&](const std::array<double, 3>& p, double xi) {
    const double x50 = std::exp(p[0]);
    return swebrec_passing(xi, x50, x50 * ratio(p[1]), std::exp(p[2]));
  };
  // Start: for trial xmax above the largest fragment, ln(1/P - 1) = b ln ln(xmax/x) - b ln ln(xmax/x50) is a
  // straight line in ln ln(xmax/x); keep the trial whose line fits P best.
  std::array<double, 3> best{};
  double best_sse = std::numeric_limits<double>::infinity();
  for (double f : {1.001, 1.01, 1.05, 1.1, 1.2, 1.5, 2.0, 3.0, 5.0, 10.0, 30.0}) {
    const double xmax = f * largest;
    std::vector<double> X, Y;
    for (size_t i = 0; i < x.size(); ++i) X.push_back(std::log(std::log(xmax / x[i]))), Y.push_back(std::log(1 / P[i] - 1));
    double b, intercept;
    if (!line_fit(X, Y, b, intercept) || !(b > 0)) continue;
    const double x50 = xmax / std::exp(std::exp(-intercept / b));
    if (!(x50 > 0 && x50 < xmax && xmax < 0.99 * R * x50)) continue;
    const double u = (xmax / x50 - 1) / (R - 1);  // in (0, 1)
    const std::array<double, 3> q{std::log(x50), std::log(u / (1 - u)), std::log(b)};
    double sse = 0;
    for (size_t i = 0; i < x.size(); ++i) sse += std::pow(model(q, x[i]) - P[i], 2);
    if (sse < best_sse) best_sse = sse, best = q;
  }
  if (!std::isfinite(best_sse)) return fit;
  levenberg_marquardt<3>(best, x, P, model);
  fit.x50 = std::exp(best[0]), fit.xmax = fit.x50 * ratio(best[1]), fit.b = std::exp(best[2]);
  fit.valid = std::isfinite(fit.x50) && std::isfinite(fit.xmax) && std::isfinite(fit.b);
  fit.xmax_at_bound = fit.xmax > 0.99 * R * fit.x50;
  fit_quality(fit, x, P, [&](double xi) { return swebrec_passing(xi, fit.x50, fit.xmax, fit.b); });
  return fit;
}

double passing_size(const SizeDistribution& d, double p) {
  if (!(p > 0 && p < 1)) throw InputError("passing_size: p = " + std::to_string(p) + ": must be in (0, 1)");
  if (d.total_mass <= 0 || p <= d.fines_mass / d.total_mass || d.size.empty()) return 0;
  if (p <= d.passing[0]) return d.size[0];
  for (size_t i = 1; i < d.size.size(); ++i)
    if (d.passing[i] >= p) {
      const double w = (p - d.passing[i - 1]) / (d.passing[i] - d.passing[i - 1]);
      return std::exp((1 - w) * std::log(d.size[i - 1]) + w * std::log(d.size[i]));
    }
  return d.size.back();
}

SizeDistribution size_distribution(const std::vector<Fragment>& fragments, double oversize_size) {
  if (!(oversize_size > 0))
    throw InputError("size_distribution: oversize size = " + std::to_string(oversize_size) + " m: must be > 0");
  SizeDistribution d;
  d.oversize_size = oversize_size;
  std::vector<const Fragment*> sized;
  for (const Fragment& f : fragments) {
    ++d.fragments;
    d.total_mass += f.mass;
    if (f.fines) d.fines_mass += f.mass;
    else sized.push_back(&f);
  }
  std::stable_sort(sized.begin(), sized.end(),
                   [](const Fragment* a, const Fragment* b) { return a->sieve_size < b->sieve_size; });
  d.sized = static_cast<int>(sized.size());
  double passed = d.fines_mass, oversize = 0;
  for (const Fragment* f : sized) {
    passed += f->mass;
    d.size.push_back(f->sieve_size);
    d.passing.push_back(passed / d.total_mass);
    if (f->sieve_size > oversize_size) oversize += f->mass;
  }
  if (d.total_mass > 0) {
    d.oversize_fraction = oversize / d.total_mass;
    d.x20 = passing_size(d, 0.2), d.x50 = passing_size(d, 0.5), d.x80 = passing_size(d, 0.8);
  }
  d.swebrec = fit_swebrec(d.size, d.passing);
  d.rosin_rammler = fit_rosin_rammler(d.size, d.passing);
  return d;
}

std::vector<double> triangle_damage(const RockSnapshot& s) {
  std::vector<double> d(s.x.size() / 3, 0.0);
  for (size_t j = 0; j < s.joint_nodes.size(); ++j) {
    const double D = s.joint_broken[j] ? 1.0 : s.joint_damage[j];
    for (int face : {0, 2}) {  // a0 and b0: first nodes of the two faces
      double& t = d[s.joint_nodes[j][face] / 3];
      t = std::max(t, D);
    }
  }
  return d;
}

DamageZone damage_zone(const RockSnapshot& s, const std::array<double, 2>& center, double hole_radius, double ring_width,
                       double crushed_fraction, const std::array<double, 2>& behind) {
  if (!(ring_width > 0)) throw InputError("damage_zone: ring width = " + std::to_string(ring_width) + " m: must be > 0");
  if (!(crushed_fraction > 0 && crushed_fraction <= 1))
    throw InputError("damage_zone: crushed fraction = " + std::to_string(crushed_fraction) + ": must be in (0, 1]");
  DamageZone z;
  std::vector<DamageRing>& rings = z.rings;
  // The ring of a point (px, py) relative to the centre, or -1 outside the hole's side or half plane.
  const auto ring_of = [&](double px, double py) -> long {
    const double r = std::hypot(px, py);
    if (r < hole_radius || px * behind[0] + py * behind[1] < 0) return -1;
    const size_t k = static_cast<size_t>((r - hole_radius) / ring_width);
    if (k >= rings.size()) rings.resize(k + 1);
    return static_cast<long>(k);
  };
  for (size_t j = 0; j < s.joint_nodes.size(); ++j) {
    const int a = s.joint_nodes[j][0], b = s.joint_nodes[j][1];
    const long k = ring_of(0.5 * (s.x0[a] + s.x0[b]) - center[0], 0.5 * (s.y0[a] + s.y0[b]) - center[1]);
    if (k < 0) continue;
    const double len = std::hypot(s.x0[b] - s.x0[a], s.y0[b] - s.y0[a]);
    rings[k].joint_length += len;
    if (s.joint_broken[j]) rings[k].broken_length += len;
  }
  for (size_t t = 0; 3 * t + 2 < s.x0.size(); ++t) {  // node 3t + k is triangle t's corner k
    const double* x = &s.x0[3 * t];
    const double* y = &s.y0[3 * t];
    const long k = ring_of((x[0] + x[1] + x[2]) / 3 - center[0], (y[0] + y[1] + y[2]) / 3 - center[1]);
    if (k >= 0) rings[k].rock_area += triangle_area(s.x0, s.y0, t);
  }
  for (size_t k = 0; k < rings.size(); ++k)
    rings[k].inner_radius = hole_radius + k * ring_width, rings[k].outer_radius = hole_radius + (k + 1) * ring_width;
  z.center = center, z.hole_radius = hole_radius;
  z.crushed_radius = z.cracked_radius = hole_radius;
  bool crushed = true, cracked = true;
  for (size_t k = 0; k < rings.size() && (crushed || cracked); ++k) {
    if (rings[k].joint_length == 0) continue;  // a ring narrower than the joints' spacing may hold none
    crushed = crushed && rings[k].broken_length >= crushed_fraction * rings[k].joint_length;
    cracked = cracked && rings[k].broken_length > 0;
    if (crushed) z.crushed_radius = rings[k].outer_radius;
    if (cracked) z.cracked_radius = rings[k].outer_radius;
  }
  // Crack rose: broken length by the direction of the joint's middle from the centre, within the cracked zone.
  for (size_t j = 0; j < s.joint_nodes.size(); ++j) {
    if (!s.joint_broken[j]) continue;
    const int a = s.joint_nodes[j][0], b = s.joint_nodes[j][1];
    const double mx = 0.5 * (s.x0[a] + s.x0[b]) - center[0], my = 0.5 * (s.y0[a] + s.y0[b]) - center[1];
    const double r = std::hypot(mx, my);
    if (r < hole_radius || r > z.cracked_radius || mx * behind[0] + my * behind[1] < 0) continue;
    double angle = std::atan2(my, mx);
    if (angle < 0) angle += 2 * M_PI;
    const int k = std::min(kRoseSectors - 1, static_cast<int>(angle / (2 * M_PI / kRoseSectors)));
    z.crack_rose[k] += std::hypot(s.x0[b] - s.x0[a], s.y0[b] - s.y0[a]);
  }
  return z;
}

}  // namespace blastsim::fdem
