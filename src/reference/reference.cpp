#include "reference/reference.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace glint {

namespace {

constexpr double kPi = 3.14159265358979323846;

// NaN fails every comparison, so "!(x > 0)" rejects NaN along with non-positive values.
void require_positive(double x, const char* what, const char* func) {
  if (!(x > 0.0) || !std::isfinite(x)) {
    throw std::invalid_argument(
        fmt::format("{}: {} must be a finite value > 0, got {}", func, what, x));
  }
}

void check_threshold_inputs(double eps, double c_y, int lights, const char* func) {
  require_positive(eps, "eps", func);
  if (!(c_y >= 0.0) || !std::isfinite(c_y)) {
    throw std::invalid_argument(
        fmt::format("{}: c_y must be a finite value >= 0, got {}", func, c_y));
  }
  if (lights < 1) {
    throw std::invalid_argument(fmt::format("{}: lights must be >= 1, got {}", func, lights));
  }
}

}  // namespace

const char* to_string(Lobe lobe) {
  switch (lobe) {
    case Lobe::kPhong:
      return "phong";
    case Lobe::kBlinn:
      return "blinn";
    case Lobe::kGaussian:
      return "gaussian";
  }
  return "?";
}

std::optional<Lobe> try_parse_lobe(std::string_view text) {
  for (const Lobe lobe : {Lobe::kPhong, Lobe::kBlinn, Lobe::kGaussian}) {
    if (text == to_string(lobe)) return lobe;
  }
  return std::nullopt;
}

Lobe parse_lobe(std::string_view text) {
  if (const auto lobe = try_parse_lobe(text)) return *lobe;
  throw std::invalid_argument("unknown lobe '" + std::string(text) +
                              "': expected phong, blinn or gaussian");
}

double luminance(const Rgb& c) {
  return kLumaR * c.r + kLumaG * c.g + kLumaB * c.b;
}

double c_y(const Rgb& light, const Rgb& material) {
  return luminance(Rgb{light.r * material.r, light.g * material.g, light.b * material.b});
}

double c_y(const Rgb& material) {
  return luminance(material);
}

double glossy_scalar(double t, double n) {
  return t > 0.0 ? std::pow(t, n) : 0.0;
}

Rgb glossy_term(double t, double n, const Rgb& i, const Rgb& m) {
  const double s = glossy_scalar(t, n);
  return Rgb{s * i.r * m.r, s * i.g * m.g, s * i.b * m.b};
}

TauResult tau_power(double n, double eps, double c_y, int lights) {
  require_positive(n, "shininess n", "tau_power");
  check_threshold_inputs(eps, c_y, lights, "tau_power");
  TauResult res;
  res.c_y = c_y;
  res.eps = eps / lights;
  // The lobe's maximum is c_y at t = 1 (eq.2); if even that is below eps, eq.4 holds everywhere.
  // This also keeps c_y = 0 away from the division in eq.5.
  if (c_y <= res.eps) {
    res.tau = 1.0;
    res.always_skip = true;
    return res;
  }
  res.tau = std::pow(res.eps / c_y, 1.0 / n);
  return res;
}

double gaussian_lobe(double t, double omega) {
  require_positive(omega, "omega", "gaussian_lobe");
  const double phi = std::acos(std::clamp(t, -1.0, 1.0));
  const double a = phi / omega;
  return std::exp(-a * a);
}

TauResult tau_gaussian(double omega, double eps, double c_y, int lights) {
  require_positive(omega, "omega", "tau_gaussian");
  check_threshold_inputs(eps, c_y, lights, "tau_gaussian");
  TauResult res;
  res.c_y = c_y;
  res.eps = eps / lights;
  if (c_y <= res.eps) {  // ln(c_y/eps) <= 0: eq.8 has no real root, the lobe never reaches eps
    res.tau = 1.0;
    res.always_skip = true;
    return res;
  }
  const double phi = omega * std::sqrt(std::log(c_y / res.eps));  // eq.8
  // Eq.9 swaps "phi >= angle" for "cos(phi) <= cos(angle)", which needs cos to be decreasing
  // between the two, i.e. angle in [0, pi]. phi = acos(t) never exceeds pi, so an angle >= pi
  // means no direction satisfies eq.8: the lobe is above eps everywhere and cannot be skipped.
  // Taking cos(angle) anyway would wrap round and skip a visible lobe.
  if (phi >= kPi) {
    res.tau = -1.0;
    res.never_skip = true;
    return res;
  }
  res.tau = std::cos(phi);  // eq.9
  return res;
}

double gaussian_equivalent_shininess(double omega) {
  require_positive(omega, "omega", "gaussian_equivalent_shininess");
  return 2.0 / (omega * omega);
}

double schlick(double t, double n) {
  require_positive(n, "shininess n", "schlick");
  if (t <= 0.0) return 0.0;
  return t / (n - n * t + t);
}

namespace {

void check_hast(double tau, int d, const char* func) {
  if (!(tau < 1.0)) {
    throw std::invalid_argument(fmt::format("{}: tau must be < 1, got {}", func, tau));
  }
  if (d < 1) throw std::invalid_argument(fmt::format("{}: order d must be >= 1, got {}", func, d));
}

}  // namespace

double hast(double rho, double tau, int d) {
  check_hast(tau, d, "hast");
  if (rho <= tau) return 0.0;
  const double kappa = 1.0 / std::pow(1.0 - tau, d);
  return kappa * std::pow(rho - tau, d);
}

double hast_scaled(double rho, double tau, int d) {
  check_hast(tau, d, "hast_scaled");
  if (rho <= tau) return 0.0;
  return std::pow((rho - tau) / (1.0 - tau), d);
}

double horner(const double* coeffs, std::size_t count, double x) {
  double acc = 0.0;
  for (std::size_t k = count; k-- > 0;) acc = acc * x + coeffs[k];
  return acc;
}

}  // namespace glint
