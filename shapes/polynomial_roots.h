#pragma once
// Real roots of low-degree polynomials, for analytic shapes (shapes/torus.cpp). Coefficients
// are c[0] + c[1] x + ... + c[n] x^n, in double. docs/shapes.md compares the two families.

namespace tray {

/// p(x) by Horner's rule.
double polyEval(const double* c, int n, double x);

/// Every root of the degree-n polynomial (1 <= n <= 4) in [lo, hi] at which it changes sign,
/// ascending; returns how many (at most n). Roots are isolated through the derivatives: the
/// sign-changing roots of p' cut [lo, hi] into pieces on which p is monotone, so each piece
/// holds at most one root, found by Newton steps safeguarded by bisection (a bracket that
/// always shrinks). Nothing is lost to a closed form's cancellation or to a threshold on the
/// discriminant: a root is missed only where p does not change sign in double arithmetic
/// (a tangent touch, of measure zero). A value of exactly 0 counts as positive.
int polyRootsIsolated(const double* c, int n, double lo, double hi, double* roots);

/// The classic closed forms of J. Schwarze, "Cubic and Quartic Roots", Graphics Gems I (1990):
/// Cardano for the cubic, Ferrari (through the resolvent cubic) for the quartic, with the
/// original absolute zero threshold 1e-9. Roots unsorted; returns how many. Kept as the
/// baseline the stability suite measures (tests/stability/torus_solver_test.cpp).
int solveQuadraticClosedForm(const double c[3], double s[2]);
int solveCubicClosedForm(const double c[4], double s[3]);
int solveQuarticClosedForm(const double c[5], double s[4]);

}  // namespace tray
