// grtrace/tableau/stability.hpp
// Linear stability of a Runge-Kutta method, computed from its Butcher tableau.
//
// Applied to the test equation y' = lambda y, one step of size h of any Runge-Kutta method (A, b) is
// y_1 = R(z) y_0 with z = h lambda and the stability function (Hairer & Wanner II, sec. IV.2 and IV.3)
//     R(z) = 1 + z b^T (I - z A)^{-1} 1.
// The stability domain is S = { z in C : |R(z)| <= 1 }. For an explicit method A is strictly lower triangular,
// (I - zA) is unit lower triangular, and R is a polynomial of degree <= s,
//     R(z) = 1 + sum_{k>=1} (b^T A^{k-1} 1) z^k,
// whose first p + 1 coefficients are 1/k! for a method of order p (Hairer & Wanner II, IV.2); so every
// s-stage method of order s <= 4 has the same R, the Taylor polynomial of e^z. The domain of an explicit method
// is bounded; an implicit method such as Gauss-Legendre has a rational R (the (s,s) Pade approximant of e^z for
// Gauss), and is A-stable: S contains the whole left half-plane (Hairer & Wanner II, IV.3 and IV.5).
//
// What is here:
//   stability_function<T>(z)          R(z) through the resolvent with Eigen (complex), for any tableau (a, b, stages)
//   stability_polynomial<T>()         the coefficients of R for an explicit tableau (constexpr)
//   real_stability_interval<T>()      [x_min, 0]: the largest interval [x, 0] of the negative real axis inside S,
//                                     by scanning left from 0 and bisecting the first crossing of |R| = 1
//   stability_boundary<T>(box, ...)   the contour |R(z)| = 1 inside a rectangle of the complex plane, by marching
//                                     squares on a grid, each crossing refined by bisection along its grid edge,
//                                     joined into polylines (closed curves repeat their first point at the end)
// Assumes: T has static constexpr members stages, a (stages x stages) and b (stages); nothing else is read.
#pragma once

#include <Eigen/Dense>

#include <array>
#include <cmath>
#include <complex>
#include <concepts>
#include <cstddef>
#include <limits>
#include <vector>

namespace grtrace {

/// The part of a tableau that linear stability depends on: A and b (explicit or implicit).
template <class T>
concept RungeKuttaCoefficients = requires {
  { T::stages } -> std::convertible_to<std::size_t>;
  T::a[0][0];
  T::b[0];
};

/// True when A is strictly lower triangular (the method is explicit and R is a polynomial).
template <RungeKuttaCoefficients T>
constexpr bool has_explicit_coefficients() {
  for (std::size_t i = 0; i < T::stages; ++i)
    for (std::size_t j = i; j < T::stages; ++j)
      if (T::a[i][j] != 0.0) return false;
  return true;
}

/// R(z) = 1 + z b^T (I - zA)^{-1} 1 (Hairer & Wanner II, IV.2). Explicit tableaux use a unit-lower-triangular
/// solve; implicit ones an LU factorisation. Returns NaN when I - zA is singular (a pole of R).
template <RungeKuttaCoefficients T>
std::complex<double> stability_function(std::complex<double> z) {
  constexpr int S = static_cast<int>(T::stages);
  using Complex = std::complex<double>;
  using Matrix = Eigen::Matrix<Complex, S, S>;
  using Column = Eigen::Matrix<Complex, S, 1>;
  Matrix m = Matrix::Identity();
  Column b;
  for (int i = 0; i < S; ++i) {
    const auto ui = static_cast<std::size_t>(i);
    b(i) = Complex(T::b[ui], 0.0);
    for (int j = 0; j < S; ++j) m(i, j) -= z * T::a[ui][static_cast<std::size_t>(j)];
  }
  const Column ones = Column::Ones();
  Column u;
  if constexpr (has_explicit_coefficients<T>()) {
    u = m.template triangularView<Eigen::UnitLower>().solve(ones);
  } else {
    const Eigen::FullPivLU<Matrix> lu(m);
    if (!lu.isInvertible()) return {std::numeric_limits<double>::quiet_NaN(), 0.0};
    u = lu.solve(ones);
  }
  return Complex(1.0, 0.0) + z * b.cwiseProduct(u).sum();  // b^T u without the conjugation of dot()
}

/// |R(z)|.
template <RungeKuttaCoefficients T>
double stability_modulus(std::complex<double> z) {
  return std::abs(stability_function<T>(z));
}

/// Coefficients gamma_0..gamma_s of R(z) = sum_k gamma_k z^k for an explicit tableau:
/// gamma_0 = 1, gamma_k = b^T A^{k-1} 1 (expand (I - zA)^{-1} = sum_k z^k A^k, A nilpotent).
template <RungeKuttaCoefficients T>
requires(has_explicit_coefficients<T>()) constexpr std::array<double, T::stages + 1> stability_polynomial() {
  constexpr std::size_t S = T::stages;
  std::array<double, S + 1> gamma{};
  std::array<double, S> v{};  // A^{k-1} 1
  for (auto& x : v) x = 1.0;
  gamma[0] = 1.0;
  for (std::size_t k = 1; k <= S; ++k) {
    double s = 0.0;
    for (std::size_t i = 0; i < S; ++i) s += T::b[i] * v[i];
    gamma[k] = s;
    std::array<double, S> next{};
    for (std::size_t i = 0; i < S; ++i)
      for (std::size_t j = 0; j < S; ++j) next[i] += T::a[i][j] * v[j];
    v = next;
  }
  return gamma;
}

/// An interval [lower, upper] of the real axis.
struct RealInterval {
  double lower;
  double upper;
};

struct RealIntervalOptions {
  double scan_step = 1e-3;    ///< spacing of the scan along the negative real axis
  double scan_limit = 100.0;  ///< scan down to -scan_limit; beyond it the interval is reported as unbounded
  double tolerance = 1e-12;   ///< width of the final bisection bracket (the result is good to ~1e-10 or better)
};

/// The real stability interval [x_min, 0]: the largest interval [x, 0] on which |R| <= 1.
/// Scans left from 0 in steps of options.scan_step for the first point with |R| > 1, then bisects the bracket.
/// A gap in S narrower than the scan step could be missed; for the shipped tableaux the interval is found to
/// ~1e-12 (tests compare against the literature). x_min = -infinity when no exit is found down to -scan_limit
/// (A-stable implicit methods).
template <RungeKuttaCoefficients T>
RealInterval real_stability_interval(const RealIntervalOptions& options = {}) {
  auto outside = [](double x) { return !(stability_modulus<T>({x, 0.0}) <= 1.0); };
  const auto steps = static_cast<long>(std::ceil(options.scan_limit / options.scan_step));
  double inside_x = 0.0;
  for (long i = 1; i <= steps; ++i) {
    const double x = -static_cast<double>(i) * options.scan_step;
    if (!outside(x)) {
      inside_x = x;
      continue;
    }
    double lo = x, hi = inside_x;  // |R(lo)| > 1 >= |R(hi)|
    while (hi - lo > options.tolerance) {
      const double mid = 0.5 * (lo + hi);
      if (outside(mid)) lo = mid;
      else hi = mid;
    }
    return {hi, 0.0};
  }
  return {-std::numeric_limits<double>::infinity(), 0.0};
}

/// A rectangle of the complex plane.
struct ComplexBox {
  double re_min = -4.0, re_max = 1.0, im_min = -4.0, im_max = 4.0;
};

struct BoundaryOptions {
  int nx = 321;                ///< grid points along Re z (>= 2)
  int ny = 321;                ///< grid points along Im z (>= 2)
  int refine_iterations = 48;  ///< bisection steps along a grid edge for each contour point
};

using ComplexPolyline = std::vector<std::complex<double>>;

/// The contour |R(z)| = 1 inside `box`, as polylines (marching squares; saddle cells resolved by the value at
/// the cell centre). A curve that leaves the box ends on its edge; a closed curve ends with its first point
/// again. Points are accurate to round-off along the grid edge they lie on; between points the contour is
/// linear, so the grid spacing sets how well curvature is followed.
template <RungeKuttaCoefficients T>
std::vector<ComplexPolyline> stability_boundary(const ComplexBox& box, const BoundaryOptions& options = {}) {
  using Complex = std::complex<double>;
  const int nx = options.nx < 2 ? 2 : options.nx, ny = options.ny < 2 ? 2 : options.ny;
  const double dx = (box.re_max - box.re_min) / (nx - 1), dy = (box.im_max - box.im_min) / (ny - 1);
  auto node = [&](int i, int j) { return Complex(box.re_min + i * dx, box.im_min + j * dy); };
  auto level = [](Complex z) { return stability_modulus<T>(z) - 1.0; };
  auto index = [](int a, int b, int stride) {
    return static_cast<std::size_t>(a) * static_cast<std::size_t>(stride) + static_cast<std::size_t>(b);
  };

  std::vector<char> inside(static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny));
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) inside[index(j, i, nx)] = level(node(i, j)) <= 0.0 ? 1 : 0;
  auto in = [&](int i, int j) { return inside[index(j, i, nx)] != 0; };

  // Edge ids: horizontal edge (i,j)-(i+1,j) -> j*(nx-1)+i; vertical edge (i,j)-(i,j+1) -> H + j*nx+i.
  const std::size_t horizontal_count = static_cast<std::size_t>(nx - 1) * static_cast<std::size_t>(ny);
  const std::size_t edge_count = horizontal_count + static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny - 1);
  auto h_edge = [&](int i, int j) { return index(j, i, nx - 1); };
  auto v_edge = [&](int i, int j) { return horizontal_count + index(j, i, nx); };

  // Contour point on an edge whose ends straddle the level: bisection on |R| - 1 along the edge.
  std::vector<Complex> point(edge_count);
  std::vector<char> has_point(edge_count, 0);
  auto crossing = [&](Complex a, bool a_in, Complex b) {
    for (int k = 0; k < options.refine_iterations; ++k) {
      const Complex m = 0.5 * (a + b);
      if ((level(m) <= 0.0) == a_in) a = m;
      else b = m;
    }
    return 0.5 * (a + b);
  };
  auto edge_point = [&](std::size_t e, int i0, int j0, int i1, int j1) {
    if (!has_point[e]) {
      point[e] = crossing(node(i0, j0), in(i0, j0), node(i1, j1));
      has_point[e] = 1;
    }
    return e;
  };

  // Segments between edge ids; each edge point joins at most two segments.
  constexpr std::size_t none = std::numeric_limits<std::size_t>::max();
  std::vector<std::array<std::size_t, 2>> links(edge_count, {none, none});
  auto link = [&](std::size_t a, std::size_t b) {
    for (std::size_t e : {a, b}) {
      const std::size_t other = e == a ? b : a;
      auto& l = links[e];
      (l[0] == none ? l[0] : l[1]) = other;
    }
  };

  for (int j = 0; j + 1 < ny; ++j) {
    for (int i = 0; i + 1 < nx; ++i) {
      const std::array<bool, 4> corner = {in(i, j), in(i + 1, j), in(i + 1, j + 1), in(i, j + 1)};
      if (corner[0] == corner[1] && corner[1] == corner[2] && corner[2] == corner[3]) continue;
      // Edges between consecutive corners: bottom (0-1), right (1-2), top (2-3), left (3-0).
      auto edge = [&](int k) -> std::size_t {
        switch (k) {
          case 0:
            return edge_point(h_edge(i, j), i, j, i + 1, j);
          case 1:
            return edge_point(v_edge(i + 1, j), i + 1, j, i + 1, j + 1);
          case 2:
            return edge_point(h_edge(i, j + 1), i + 1, j + 1, i, j + 1);
          default:
            return edge_point(v_edge(i, j), i, j + 1, i, j);
        }
      };
      const int changes =
          (corner[0] != corner[1]) + (corner[1] != corner[2]) + (corner[2] != corner[3]) + (corner[3] != corner[0]);
      if (changes == 2) {
        std::array<std::size_t, 2> ends{};
        std::size_t n = 0;
        for (int k = 0; k < 4; ++k)
          if (corner[static_cast<std::size_t>(k)] != corner[static_cast<std::size_t>((k + 1) % 4)]) ends[n++] = edge(k);
        link(ends[0], ends[1]);
      } else {
        // Saddle: cut off each corner whose side differs from the cell centre's. Corner k lies between
        // edge k-1 and edge k.
        const bool centre = level(node(i, j) + Complex(0.5 * dx, 0.5 * dy)) <= 0.0;
        for (int k = 0; k < 4; ++k)
          if (corner[static_cast<std::size_t>(k)] != centre) link(edge((k + 3) % 4), edge(k));
      }
    }
  }

  // Walk the chains: open curves (ends of degree one, on the box edge) first, then closed loops.
  std::vector<ComplexPolyline> curves;
  std::vector<char> used(edge_count, 0);
  auto walk = [&](std::size_t start) {
    ComplexPolyline curve;
    std::size_t prev = none, cur = start;
    while (cur != none && !used[cur]) {
      used[cur] = 1;
      curve.push_back(point[cur]);
      const auto& l = links[cur];
      const std::size_t next = l[0] != prev && l[0] != none && !used[l[0]]
                                   ? l[0]
                                   : (l[1] != prev && l[1] != none && !used[l[1]] ? l[1] : none);
      if (next == none && (l[0] == start || l[1] == start) && curve.size() > 2) curve.push_back(point[start]);
      prev = cur;
      cur = next;
    }
    if (curve.size() >= 2) curves.push_back(std::move(curve));
  };
  for (std::size_t e = 0; e < edge_count; ++e)
    if (has_point[e] && !used[e] && links[e][0] != none && links[e][1] == none) walk(e);
  for (std::size_t e = 0; e < edge_count; ++e)
    if (has_point[e] && !used[e] && links[e][0] != none) walk(e);
  return curves;
}

}  // namespace grtrace
