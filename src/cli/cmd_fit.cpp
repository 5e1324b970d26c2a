// glint fit: polynomial fits of t^n (Öztürk et al. 2006, and our fits on [tau, 1]).
#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <iostream>

#include "cli/cli.h"
#include "fit/fit.h"
#include "reference/reference.h"

namespace glint::cli {
namespace {

struct FitCliOptions {
  double shininess = 0;
  int degree = 4;
  int samples = FitOptions{}.samples;
  std::string method = "ls";
  std::string domain = "full";
  double eps = 1e-3;
  std::string color = "1,1,1";
  EpsMeasure eps_measure = EpsMeasure::kLuminance;
  bool constrain = false;
  bool json = false;
  bool samples_given = false;
};

int run_fit(const FitCliOptions& o) {
  require_finite_positive(o.shininess, "--shininess");
  require_finite_positive(o.eps, "--eps");
  FitOptions f;
  f.shininess = o.shininess;
  f.degree = o.degree;
  f.method = parse_fit_method(o.method);
  f.domain = parse_fit_domain(o.domain);
  // Only the sampled methods read --samples; minimax fits t^n itself on a dense grid.
  if (o.samples_given && f.method == FitMethod::kMinimax)
    throw std::invalid_argument(fmt::format(
        "--samples {}: method minimax fits t^n itself, not samples (use ls or robust)", o.samples));
  if (f.method != FitMethod::kMinimax && o.samples < o.degree + 1)
    throw std::invalid_argument(
        fmt::format("--samples {}: a degree-{} fit needs at least {} samples", o.samples, o.degree,
                    o.degree + 1));
  f.samples = o.samples;
  const auto m = parse_rgb(o.color, "--color");
  if (!std::isfinite(c_y(Rgb{m[0], m[1], m[2]})))
    throw std::invalid_argument(
        fmt::format("--color {}: c_y, the colour's luminance, overflows", o.color));
  // Under a white light; the weight is c_y or, with --eps-measure channel, the largest channel.
  const TauResult tau = tau_power(
      o.shininess, o.eps, threshold_weight(o.eps_measure, Rgb{1, 1, 1}, Rgb{m[0], m[1], m[2]}));
  if (f.domain == FitDomain::kTau) {
    if (tau.always_skip)
      throw std::invalid_argument(
          fmt::format("{} <= eps: the lobe is never visible, nothing to fit",
                      o.eps_measure == EpsMeasure::kChannel ? "the largest channel" : "c_y"));
    f.tau = tau.tau;
  }
  f.constrain_one = o.constrain;
  f.constrain_zero = o.constrain && f.domain == FitDomain::kTau;
  const FitResult r = fit_power(f);
  if (robust_rejects_samples(r))
    std::fprintf(stderr,
                 "glint: warning: fit --method robust: largest error %.4g on its %d samples "
                 "against %.4g for ls: on noise-free t^n the bisquare weights reject its "
                 "steepest part (the highlight, or t near 0 for n < 1) as outliers; use ls or "
                 "minimax (robust is for noisy, measured data)\n",
                 r.sample_max_error, f.samples, r.ls_sample_max_error);
  const char* var = r.variable == FitVariable::kU ? "u = (t - tau)/(1 - tau)" : "t";
  if (o.json) {
    print_json({{"shininess", o.shininess},
                {"degree", o.degree},
                {"method", to_string(f.method)},
                {"domain", to_string(f.domain)},
                // The points ls and robust fit; minimax fits t^n itself.
                {"samples", f.method == FitMethod::kMinimax ? nlohmann::json(nullptr)
                                                            : nlohmann::json(f.samples)},
                {"tau", r.tau},
                {"eps_measure", to_string(o.eps_measure)},
                {"variable", to_string(r.variable)},
                {"constrain_one", f.constrain_one},
                {"constrain_zero", f.constrain_zero},
                {"coefficients", r.coeffs},
                {"max_abs_error", r.max_abs_error},
                {"rms_error", r.rms_error},
                {"t_at_max_error", r.t_at_max_error},
                {"skipped_error_bound", r.skipped_error_bound},
                {"monotone", r.monotone},
                {"iterations", r.iterations},
                {"converged", r.converged}});
    return kExitOk;
  }
  std::cout << fmt::format(
      "fit of t^{} by a degree-{} polynomial, method {}, domain {}{}{}\n", o.shininess, o.degree,
      to_string(f.method), to_string(f.domain),
      f.method == FitMethod::kMinimax ? "" : fmt::format(", {} samples", f.samples),
      o.constrain ? " (constrained)" : "");
  if (f.domain == FitDomain::kTau)
    std::cout << fmt::format("tau {:.6f} (eps on {})\n", r.tau, to_string(o.eps_measure));
  std::cout << fmt::format("variable {}\ncoefficients (c0 first):\n", var);
  for (std::size_t k = 0; k < r.coeffs.size(); ++k)
    std::cout << fmt::format("  c{:<2} {: .17g}\n", k, r.coeffs[k]);
  std::cout << fmt::format("max abs error {:.6e} at t = {:.6f}\nrms error     {:.6e}\n",
                           r.max_abs_error, r.t_at_max_error, r.rms_error)
            << fmt::format("monotone      {}\n", r.monotone ? "yes" : "no");
  if (f.domain == FitDomain::kTau)
    std::cout << fmt::format("skipped t <= tau contributes at most {:.3e}\n",
                             r.skipped_error_bound);
  return kExitOk;
}

}  // namespace

void add_fit_command(CLI::App& app, int& status) {
  auto o = std::make_shared<FitCliOptions>();
  CLI::App* sub = app.add_subcommand("fit", "Fit a polynomial to t^n and report its error");
  sub->add_option("--shininess", o->shininess, "Shininess exponent n (finite, > 0)")->required();
  sub->add_option("--degree", o->degree, "Polynomial degree p, 1..10")
      ->check(CLI::Range(1, 10))
      ->capture_default_str();
  CLI::Option* samples =
      sub->add_option("--samples", o->samples,
                      "Uniform samples of ls and robust, 2..1000000 (domain full: x = i/N, i = "
                      "1..N, as Öztürk et al. sample 0 < x < 1; tau: u = i/(N-1), i = 0..N-1); "
                      "at least degree + 1, not with minimax")
          ->check(CLI::Range(2, 1000000))
          ->capture_default_str();
  sub->add_option("--method", o->method,
                  "ls: least squares on the samples | robust: bisquare weights (Öztürk's, for "
                  "noisy measured data; on t^n itself they can reject the highlight, and glint "
                  "warns) | minimax: the smallest largest error")
      ->check(CLI::IsMember({"ls", "robust", "minimax"}))
      ->capture_default_str();
  sub->add_option("--domain", o->domain, "full: x in (0, 1] | tau: [tau, 1] in u")
      ->check(CLI::IsMember({"full", "tau"}))
      ->capture_default_str();
  sub->add_option("--eps", o->eps, "eps for tau (domain tau; finite, > 0)")->capture_default_str();
  add_eps_measure_option(sub, o->eps_measure);
  sub->add_option("--color", o->color, "Specular colour r,g,b for c_y (each finite, >= 0)")
      ->capture_default_str();
  sub->add_flag("--constrain", o->constrain, "Force f(1) = 1 (and f(tau) = 0 on domain tau)");
  sub->add_flag("--json", o->json, "Print one JSON document on stdout");
  sub->callback([o, samples, &status] {
    o->samples_given = samples->count() > 0;
    status = guarded([&] { return run_fit(*o); });
  });
}

}  // namespace glint::cli
