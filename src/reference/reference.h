// Double-precision reference models of the glossy highlight: the oracle every fixed-point unit is
// measured against. Pure functions over plain data; nothing here knows about bit widths.
//
// Papers:
//   Källberg & Larsson 2014, "Optimized Phong and Blinn-Phong Glossy Highlights" (threshold tau),
//   Schlick 1994, "A Fast Alternative to Phong's Specular Model" (rational t^n substitute),
//   Hast et al. 2003, "Fast Specular Highlights by modifying the Phong-Blinn Model"
//   (kappa(rho-tau)^d), Öztürk et al. 2006, "Polynomial Approximation of Blinn-Phong Model"
//   (polynomial fits, Horner).
//
// Throughout, t is the cosine that feeds the lobe: r.v for Phong, n.h for Blinn-Phong. The two
// lobes differ only in how t is formed upstream, so every function here takes t directly.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

namespace glint {

enum class Lobe : std::uint8_t { kPhong, kBlinn, kGaussian };

const char* to_string(Lobe lobe);  // "phong", "blinn", "gaussian"
// Parses "phong", "blinn" or "gaussian". Throws std::invalid_argument otherwise.
Lobe parse_lobe(std::string_view text);
// The same without throwing, for parsers that report a bad lobe in their own error format.
std::optional<Lobe> try_parse_lobe(std::string_view text);

struct Rgb {
  double r = 0.0;
  double g = 0.0;
  double b = 0.0;
};

// Rec.709 luminance weights, as used by Källberg eq.3 and eq.6. They sum to exactly 1 in real
// arithmetic, so white (1,1,1) has luminance 1 and eps is an absolute luminance level.
inline constexpr double kLumaR = 0.2126;
inline constexpr double kLumaG = 0.7152;
inline constexpr double kLumaB = 0.0722;

double luminance(const Rgb& c);
// Källberg eq.3: luminance of the per-channel product i*m, i.e. the peak glossy luminance for one
// light/material pair. Gives the tightest tau, at the cost of one tau per pair.
double c_y(const Rgb& light, const Rgb& material);
// Källberg eq.6: eq.3 with every light assumed white at 100%, so tau is per material only.
double c_y(const Rgb& material);

// max(0,t)^n [Källberg eq.1-2 without the colour factor]. Defined as 0 for t <= 0 (for n > 0
// pow(0,n) is 0 anyway; the explicit branch also keeps negative t away from pow, which would
// return NaN for non-integer n).
double glossy_scalar(double t, double n);
// Källberg eq.1: max(0,t)^n * i * m per channel.
Rgb glossy_term(double t, double n, const Rgb& i, const Rgb& m);

// A skip threshold: the comparator skips the lobe when t <= tau [Källberg eq.4-5].
struct TauResult {
  double tau = 0.0;
  // c_y <= eps: the lobe peaks at c_y (t = 1), so it never exceeds eps and can always be skipped.
  // tau is then 1.0, which still works as a plain comparator since t <= 1 always.
  bool always_skip = false;
  // The lobe exceeds eps at every angle (only possible for the Gaussian lobe): never skip. tau
  // is -1.0 then, but t = -1 would still compare as skipped, so callers must honour the flag.
  bool never_skip = false;
  double c_y = 0.0;
  double eps = 0.0;  // the effective eps after division by the light count

  // The comparator with both flags honoured.
  bool skip(double t) const { return always_skip || (!never_skip && t <= tau); }
};

// Källberg eq.5: tau = (eps/c_y)^(1/n), for `lights` overlapping lights with eps_K = eps/K
// (Källberg §2 end: K skipped lobes sum to at most K*eps_K = eps). Throws std::invalid_argument
// unless n > 0, eps > 0, c_y >= 0 and lights >= 1.
TauResult tau_power(double n, double eps, double c_y, int lights = 1);

// Källberg eq.7 without c_y: exp(-(acos(t)/omega)^2), t clamped to [-1, 1] so that a dot product
// that rounds slightly past 1 does not produce NaN. omega > 0 (the paper restricts omega to
// (0, 1]; larger values are accepted and simply give a wider lobe). Throws unless omega > 0.
double gaussian_lobe(double t, double omega);

// Källberg eq.8-9: tau = cos(omega * sqrt(ln(c_y/eps))), with the same flags and light handling
// as tau_power. Throws std::invalid_argument unless omega > 0, eps > 0, c_y >= 0, lights >= 1.
TauResult tau_gaussian(double omega, double eps, double c_y, int lights = 1);

// Shininess n for which cos^n(phi) matches the Gaussian lobe exp(-(phi/omega)^2) near phi = 0:
// ln cos(phi) = -phi^2/2 + O(phi^4), so cos^n(phi) ~ exp(-n phi^2 / 2) and n = 2/omega^2. This
// lets t^n units (polynomial, Schlick, Hast) stand in for Gaussian materials. The match is
// exact in curvature at the peak only; far from it the power lobe falls off faster. Throws unless
// omega > 0.
double gaussian_equivalent_shininess(double omega);

// Schlick 1994: S_n(t) = t / (n - n t + t), for t in [0, 1] and n > 0 (t <= 0 gives 0, as for
// the clamped cosine). For n >= 1 it never undershoots t^n on [0, 1]: with g(t) = t^(n-1)(n -
// (n-1)t), S >= t^n is g(t) <= 1, and g(1) = 1 with g'(t) = n(n-1)t^(n-2)(1-t) >= 0.
// Throws std::invalid_argument unless n > 0.
double schlick(double t, double n);

// Hast eq.2: f(rho) = kappa (rho - tau)^d with kappa = 1/(1 - tau)^d, so f(1) = 1 and every root
// sits at tau; 0 for rho <= tau (Hast §2: the whole term is skipped there). Throws unless tau < 1
// and d >= 1. kappa overflows once (1-tau)^d underflows (e.g. tau = 0.99, d = 200): use
// hast_scaled then.
double hast(double rho, double tau, int d);
// Hast eq.2 regrouped as ((rho - tau)/(1 - tau))^d: the same value, but the base stays in [0, 1]
// so nothing overflows. This is also the form a fixed-point datapath wants.
double hast_scaled(double rho, double tau, int d);

// Öztürk eq.12 (Horner's rule): beta_0 + x(beta_1 + x(beta_2 + ...)), coeffs[0] = beta_0 (the
// constant term). An empty polynomial is 0.
double horner(const double* coeffs, std::size_t count, double x);
inline double horner(const std::vector<double>& coeffs, double x) {
  return horner(coeffs.data(), coeffs.size(), x);
}

}  // namespace glint
