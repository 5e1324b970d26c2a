// glint tau: the skip threshold of one material (Källberg & Larsson 2014).
#include <fmt/format.h>

#include <cmath>
#include <iostream>

#include "cli/cli.h"
#include "reference/reference.h"

namespace glint::cli {
namespace {

struct TauOptions {
  double shininess = 0;
  double eps = 0;
  std::string color = "1,1,1";
  std::string light = "1,1,1";
  int lights = 1;
  EpsMeasure eps_measure = EpsMeasure::kLuminance;
  std::string lobe = "phong";
  double roughness = 0;
  bool shininess_given = false, roughness_given = false;
  bool json = false;
};

int run_tau(const TauOptions& o) {
  const Lobe lobe = parse_lobe(o.lobe);
  require_finite_positive(o.eps, "--eps");
  const auto m = parse_rgb(o.color, "--color");
  const auto i = parse_rgb(o.light, "--light");
  // The weight eps is compared against: c_y (eq.3), or the largest channel of light x colour.
  const double cy = threshold_weight(o.eps_measure, Rgb{i[0], i[1], i[2]}, Rgb{m[0], m[1], m[2]});
  // Each component is finite, their product need not be (1e200 x 1e200).
  if (!std::isfinite(cy))
    throw std::invalid_argument(
        fmt::format("--color {} --light {}: c_y, the luminance of light x colour, overflows",
                    o.color, o.light));
  // The rules of a material in a vector file (traces/README.md): a shininess, when given, is
  // finite and > 0; only a Gaussian lobe has a roughness.
  if (o.shininess_given || lobe != Lobe::kGaussian)
    require_finite_positive(o.shininess, "--shininess");
  TauResult r;
  double n = o.shininess;
  if (lobe == Lobe::kGaussian) {
    if (!(o.roughness > 0 && o.roughness <= 1))
      throw std::invalid_argument("--roughness must be in (0, 1] for gaussian (Källberg eq.7)");
    r = tau_gaussian(o.roughness, o.eps, cy, o.lights);
    if (!o.shininess_given) n = gaussian_equivalent_shininess(o.roughness);
  } else {
    if (o.roughness_given)
      throw std::invalid_argument("--roughness: only --lobe gaussian has a roughness");
    r = tau_power(n, o.eps, cy, o.lights);
  }
  const char* verdict = r.always_skip ? "always" : (r.never_skip ? "never" : "t <= tau");
  if (o.json) {
    print_json({{"lobe", to_string(lobe)},
                {"shininess", n},
                {"roughness", o.roughness},
                {"eps", o.eps},
                {"lights", o.lights},
                {"eps_effective", r.eps},
                {"eps_measure", to_string(o.eps_measure)},
                {"c_y", c_y(Rgb{i[0], i[1], i[2]}, Rgb{m[0], m[1], m[2]})},
                {"weight", r.c_y},
                {"tau", r.tau},
                {"always_skip", r.always_skip},
                {"never_skip", r.never_skip}});
    return kExitOk;
  }
  std::cout << fmt::format("tau {:.6f}\n{} {:.6f}\neps {:.6g} (effective {:.6g} for {} light{})\n",
                           r.tau, o.eps_measure == EpsMeasure::kChannel ? "w_max" : "c_y", r.c_y,
                           o.eps, r.eps, o.lights, o.lights == 1 ? "" : "s")
            << fmt::format("skip {}\n", verdict);
  return kExitOk;
}

}  // namespace

void add_tau_command(CLI::App& app, int& status) {
  auto o = std::make_shared<TauOptions>();
  CLI::App* sub = app.add_subcommand(
      "tau", "Skip threshold tau = (eps/c_y)^(1/n) (Källberg eq.5; Gaussian lobes eq.9)");
  CLI::Option* shininess = sub->add_option(
      "--shininess", o->shininess, "Shininess exponent n (finite, > 0; gaussian: optional)");
  sub->add_option("--eps", o->eps, "Perceptibility threshold eps (finite, > 0)")->required();
  sub->add_option("--color", o->color,
                  "Specular colour r,g,b, each finite and >= 0 (c_y by Rec.709, eq.6)")
      ->capture_default_str();
  sub->add_option("--light", o->light,
                  "Light intensity r,g,b, each finite and >= 0 (per-light tau, eq.3)")
      ->capture_default_str();
  sub->add_option("--lights", o->lights, "Number of lights K, 1..1048576: eps/K (Källberg §2)")
      ->check(CLI::Range(1, 1 << 20))
      ->capture_default_str();
  sub->add_option("--lobe", o->lobe, "phong | blinn | gaussian")
      ->check(CLI::IsMember({"phong", "blinn", "gaussian"}))
      ->capture_default_str();
  CLI::Option* roughness =
      sub->add_option("--roughness", o->roughness, "Gaussian roughness omega in (0, 1]");
  add_eps_measure_option(sub, o->eps_measure);
  sub->add_flag("--json", o->json, "Print one JSON document on stdout");
  sub->callback([o, &status, shininess, roughness] {
    o->shininess_given = shininess->count() > 0;
    o->roughness_given = roughness->count() > 0;
    status = guarded([&] { return run_tau(*o); });
  });
}

}  // namespace glint::cli
