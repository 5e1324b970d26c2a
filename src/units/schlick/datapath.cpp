#include "units/schlick/datapath.h"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "reference/reference.h"
#include "units/keys.h"
#include "units/n_register.h"

namespace glint {

double schlick_n_prime(MatchMode match, double n) {
  if (!(n > 0) || !std::isfinite(n)) return n;  // refused by the constructor, naming n
  switch (match) {
    case MatchMode::kMinimax:
      return schlick_minimax_n(n);
    case MatchMode::kWidth:
      return schlick_width_n(n);
    case MatchMode::kNone:
      break;
  }
  return n;
}

SchlickUnit::SchlickUnit(const SchlickConfig& cfg, const MaterialParams& m, double n_prime)
    : cfg_(cfg) {
  check_format(cfg.in);
  check_format(cfg.out);
  check_format(cfg.n_format);
  if (cfg.in.frac_bits < 0 || cfg.out.frac_bits < 0 || cfg.n_format.frac_bits < 0 ||
      cfg.in.raw_one() == 0 || cfg.out.raw_one() == 0) {
    // not from a spec: read_common_keys refuses such formats, and a format has frac_bits >= 0
    throw std::invalid_argument("schlick: input and output formats must represent 1.0");
  }
  if (!(m.shininess > 0) || m.shininess > cfg.n_format.max_value()) {
    // refusal: schlick.n
    throw std::invalid_argument(fmt::format(
        "schlick: {}: shininess {} outside the n register (at most {:.6g})",
        key_values({{"n", cfg.n_format.name()}}), m.shininess, cfg.n_format.max_value()));
  }
  if (!(n_prime > 0) || n_prime > cfg.n_format.max_value()) {
    // refusal: schlick.n_prime
    throw std::invalid_argument(fmt::format(
        "schlick: {}: match={} gives n' = {:.6g} for shininess {}, outside the n register (at "
        "most {:.6g}; give a wider n format)",
        key_values({{"match", to_string(cfg.match)}, {"n", cfg.n_format.name()}}),
        to_string(cfg.match), n_prime, m.shininess, cfg.n_format.max_value()));
  }
  n_ = n_prime;
  material_n_ = m.shininess;
  n_raw_ = quantize_n(n_prime, cfg.n_format);
  one_in_ = cfg.in.raw_one();
  out_max_ = cfg.out.raw_one();
  n_frac_ = cfg.n_format.frac_bits;
  num_shift_ = cfg.n_format.frac_bits + cfg.out.frac_bits;
  // The double-estimate division needs num and den below 2^53.
  if (cfg.in.frac_bits + num_shift_ > 52 || cfg.n_format.width() + cfg.in.frac_bits + 1 > 52) {
    // refusal: schlick.divider
    throw std::invalid_argument(fmt::format(
        "schlick: {}: the divider's numerator ({} bits) or denominator ({} bits) would be wider "
        "than the 52 bits its exact model holds",
        key_values({{"in", cfg.in.name()}, {"out", cfg.out.name()}, {"n", cfg.n_format.name()}}),
        cfg.in.frac_bits + num_shift_, cfg.n_format.width() + cfg.in.frac_bits + 1));
  }
}

double SchlickUnit::shininess_q() const {
  return input_value(n_raw_, cfg_.n_format);
}

double SchlickUnit::model(std::int64_t t_raw) const {
  const std::int64_t t = t_raw > one_in_ ? one_in_ : (t_raw < 0 ? 0 : t_raw);
  return schlick(input_value(t, cfg_.in), shininess_q());
}

double SchlickUnit::float_model(double t) const {
  return schlick(t <= 0 ? 0.0 : (t > 1 ? 1.0 : t), n_);
}

}  // namespace glint
