#include "units/pwp/segment_fit.h"

#include <cmath>
#include <functional>

#include "fit/fit.h"

namespace glint {

namespace {

// c += rise x the minimax polynomial of (f(t) - f(a)) / rise on [a, b], in x = (t - a) / (b - a),
// with both ends kept (0 and 1); `o` gives the degree and anything else of the fit.
void add_minimax(std::vector<double>& c, const std::function<double(double)>& f, double a, double b,
                 double fa, double rise, FitOptions o) {
  const double h = b - a;
  // The two-sided form makes both ends exact: x = 0 gives a, x = 1 gives b.
  const std::function<double(double)> normalised = [&](double x) {
    const double t = x <= 0.5 ? a + h * x : b - h * (1.0 - x);
    return (f(t) - fa) / rise;
  };
  o.method = FitMethod::kMinimax;
  o.constrain_zero = true;
  o.constrain_one = true;
  // A short piece of a smooth function: a coarse Remez grid, refined by golden-section search at
  // each extremum, finds the alternation set (the default grid is sized for all of [tau, 1]).
  o.remez_grid = 64;
  o.error_grid = 0;
  const FitResult r = fit_function(o, normalised);
  for (std::size_t j = 0; j < c.size() && j < r.coeffs.size(); ++j) c[j] += rise * r.coeffs[j];
}

}  // namespace

std::vector<double> fit_segment(double n, double a, double b, int degree) {
  const double fa = std::pow(a, n), fb = std::pow(b, n), rise = fb - fa;
  std::vector<double> c(static_cast<std::size_t>(degree) + 1, 0.0);
  c[0] = fa;
  // Flat in double precision (t^n underflows, or the segment is far below the lobe), or a line:
  // the chord is the fit.
  if (!(rise > 0.0) || degree == 1) {
    c[1] = rise > 0.0 ? rise : 0.0;
    return c;
  }
  FitOptions o;
  o.shininess = n;
  o.degree = degree;
  add_minimax(
      c, [n](double t) { return std::pow(t, n); }, a, b, fa, rise, o);
  return c;
}

std::vector<double> fit_segment_of(const std::function<double(double)>& f, double a, double b,
                                   int degree) {
  const double fa = f(a), fb = f(b), rise = fb - fa;
  std::vector<double> c(static_cast<std::size_t>(degree) + 1, 0.0);
  c[0] = fa;
  if (degree == 1) {
    c[1] = rise;
    return c;
  }
  FitOptions o;
  o.degree = degree;
  add_minimax(c, f, a, b, fa, rise, o);
  return c;
}

}  // namespace glint
