#include "shapes/polynomial_roots.h"

#include <cmath>
#include <limits>

namespace tray {

double polyEval(const double* c, int n, double x) {
  double p = c[n];
  for (int i = n - 1; i >= 0; --i) p = p * x + c[i];
  return p;
}

namespace {

/// The root of p in the bracket [a, b], where p(a) > 0 differs from p(b) > 0 (posA says
/// which). Newton from the midpoint; a step that leaves the bracket or does not halve it
/// falls back to bisection, so the bracket shrinks at least geometrically.
double refineRoot(const double* c, int n, double a, double b, bool posA) {
  double x = 0.5 * (a + b), lastWidth = b - a;
  for (int iter = 0; iter < 200; ++iter) {
    // p and p' together (Horner).
    double p = c[n], dp = 0.0;
    for (int i = n - 1; i >= 0; --i) dp = dp * x + p, p = p * x + c[i];
    if (p == 0.0) return x;
    if ((p > 0.0) == posA)
      a = x;
    else
      b = x;
    const double width = b - a;
    if (!(width >
          4.0 * std::numeric_limits<double>::epsilon() * std::fmax(std::fabs(a), std::fabs(b))))
      return 0.5 * (a + b);
    const double newton = dp != 0.0 ? x - p / dp : a - 1.0;
    if (newton > a && newton < b && std::fabs(newton - x) < 0.5 * lastWidth) {
      if (std::fabs(newton - x) <= 2.0 * std::numeric_limits<double>::epsilon() * std::fabs(x))
        return newton;
      lastWidth = std::fabs(newton - x);
      x = newton;
    } else {
      lastWidth = width;
      x = 0.5 * (a + b);
    }
  }
  return x;
}

}  // namespace

int polyRootsIsolated(const double* c, int n, double lo, double hi, double* roots) {
  if (n < 1 || !(lo <= hi)) return 0;
  if (c[n] == 0.0) return polyRootsIsolated(c, n - 1, lo, hi, roots);
  if (n == 1) {
    const double x = -c[0] / c[1];
    if (!(x >= lo && x <= hi)) return 0;
    roots[0] = x;
    return 1;
  }
  // Monotone pieces between the sign changes of p'.
  double d[4] = {0, 0, 0, 0}, cut[6] = {0, 0, 0, 0, 0, 0};
  for (int i = 0; i < n; ++i) d[i] = double(i + 1) * c[i + 1];
  cut[0] = lo;
  const int k = polyRootsIsolated(d, n - 1, lo, hi, cut + 1);
  cut[k + 1] = hi;
  int count = 0;
  bool posA = polyEval(c, n, lo) > 0.0;
  for (int i = 0; i <= k; ++i) {
    const double a = cut[i], b = cut[i + 1];
    const bool posB = polyEval(c, n, b) > 0.0;
    if (posA != posB && b > a) roots[count++] = refineRoot(c, n, a, b, posA);
    posA = posB;
  }
  return count;
}

// --- Schwarze's closed forms, as published (Graphics Gems I, "Roots3And4.c") ------------------

namespace {
constexpr double kEqnEps = 1e-9;
bool isZero(double x) {
  return x > -kEqnEps && x < kEqnEps;
}
}  // namespace

int solveQuadraticClosedForm(const double c[3], double s[2]) {
  const double p = c[1] / (2 * c[2]), q = c[0] / c[2], D = p * p - q;
  if (isZero(D)) {
    s[0] = -p;
    return 1;
  }
  if (D < 0) return 0;
  const double sqrtD = std::sqrt(D);
  s[0] = sqrtD - p;
  s[1] = -sqrtD - p;
  return 2;
}

int solveCubicClosedForm(const double c[4], double s[3]) {
  // x^3 + A x^2 + B x + C = 0; x = y - A/3 gives y^3 + 3p y + 2q = 0.
  const double A = c[2] / c[3], B = c[1] / c[3], C = c[0] / c[3];
  const double sqA = A * A;
  const double p = 1.0 / 3 * (-1.0 / 3 * sqA + B);
  const double q = 1.0 / 2 * (2.0 / 27 * A * sqA - 1.0 / 3 * A * B + C);
  const double cbp = p * p * p, D = q * q + cbp;
  int num;
  if (isZero(D)) {
    if (isZero(q)) {
      s[0] = 0;
      num = 1;
    } else {
      const double u = std::cbrt(-q);
      s[0] = 2 * u;
      s[1] = -u;
      num = 2;
    }
  } else if (D < 0) {  // casus irreducibilis: three real roots
    const double phi = 1.0 / 3 * std::acos(-q / std::sqrt(-cbp)), t = 2 * std::sqrt(-p);
    s[0] = t * std::cos(phi);
    s[1] = -t * std::cos(phi + M_PI / 3);
    s[2] = -t * std::cos(phi - M_PI / 3);
    num = 3;
  } else {
    const double sqrtD = std::sqrt(D);
    s[0] = std::cbrt(sqrtD - q) - std::cbrt(sqrtD + q);
    num = 1;
  }
  const double sub = 1.0 / 3 * A;
  for (int i = 0; i < num; ++i) s[i] -= sub;
  return num;
}

int solveQuarticClosedForm(const double c[5], double s[4]) {
  // x^4 + A x^3 + B x^2 + C x + D = 0; x = y - A/4 gives y^4 + p y^2 + q y + r = 0.
  const double A = c[3] / c[4], B = c[2] / c[4], C = c[1] / c[4], D = c[0] / c[4];
  const double sqA = A * A;
  const double p = -3.0 / 8 * sqA + B;
  const double q = 1.0 / 8 * sqA * A - 1.0 / 2 * A * B + C;
  const double r = -3.0 / 256 * sqA * sqA + 1.0 / 16 * sqA * B - 1.0 / 4 * A * C + D;
  int num;
  if (isZero(r)) {  // y (y^3 + p y + q) = 0
    const double k[4] = {q, p, 0, 1};
    num = solveCubicClosedForm(k, s);
    s[num++] = 0;
  } else {
    // Ferrari: one real root z of the resolvent cubic splits the quartic into two quadratics.
    const double k[4] = {1.0 / 2 * r * p - 1.0 / 8 * q * q, -r, -1.0 / 2 * p, 1};
    solveCubicClosedForm(k, s);
    const double z = s[0];
    double u = z * z - r, v = 2 * z - p;
    if (isZero(u))
      u = 0;
    else if (u > 0)
      u = std::sqrt(u);
    else
      return 0;
    if (isZero(v))
      v = 0;
    else if (v > 0)
      v = std::sqrt(v);
    else
      return 0;
    const double k1[3] = {z - u, q < 0 ? -v : v, 1};
    num = solveQuadraticClosedForm(k1, s);
    const double k2[3] = {z + u, q < 0 ? v : -v, 1};
    num += solveQuadraticClosedForm(k2, s + num);
  }
  const double sub = 1.0 / 4 * A;
  for (int i = 0; i < num; ++i) s[i] -= sub;
  return num;
}

}  // namespace tray
