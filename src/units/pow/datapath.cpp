#include "units/pow/datapath.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "units/keys.h"
#include "units/n_register.h"
#include "units/unit_set.h"

namespace glint {
namespace {

// Table of f on [a, a + 1] at 2^bits + 1 nodes, rounded to nearest, plus one padding entry so the
// interpolation may read index + 1 at the last node (its slope is then multiplied by zero).
template <class F>
std::vector<std::int64_t> build_table(int bits, int frac, F f) {
  const std::size_t n = (std::size_t{1} << bits) + 1;
  std::vector<std::int64_t> t(n + 1);
  for (std::size_t i = 0; i < n; ++i) {
    t[i] = std::llround(std::ldexp(f(std::ldexp(static_cast<double>(i), -bits)), frac));
  }
  t[n] = t[n - 1];
  return t;
}

// Largest |f - chord| over the segments [x_i, x_i + h] of a function with monotone derivative:
// the maximum sits where f' equals the chord slope (df_inv maps a slope back to that point).
template <class F, class DInv>
double max_chord_error(int bits, F f, DInv df_inv) {
  const double h = std::ldexp(1.0, -bits);
  double worst = 0;
  for (int i = 0; i < (1 << bits); ++i) {
    const double a = i * h, b = a + h;
    const double s = (f(b) - f(a)) / h;
    const double x = std::clamp(df_inv(s), a, b);
    worst = std::max(worst, std::fabs(f(a) + s * (x - a) - f(x)));
  }
  return worst;
}

}  // namespace

PowTables::PowTables(const PowConfig& cfg)
    : log_bits(cfg.log_bits),
      log_frac(cfg.log_frac),
      exp_bits(cfg.exp_bits),
      exp_frac(cfg.exp_frac) {
  log_table = build_table(cfg.log_bits, cfg.log_frac, [](double x) { return std::log2(1 + x); });
  exp_table = build_table(cfg.exp_bits, cfg.exp_frac, [](double x) { return std::exp2(x); });
  // Interpolation with fewer remainder bits than the table resolution (pad) is exact at the
  // nodes, so the chord terms still bound it.
  const double ln2 = std::log(2.0);
  eps_log = max_chord_error(
                cfg.log_bits, [](double x) { return std::log2(1 + x); },
                [ln2](double s) { return 1.0 / (s * ln2) - 1.0; }) +
            std::ldexp(1.0, -cfg.log_frac);  // table ½ ulp + interpolation ½ ulp
  eps_exp = max_chord_error(
                cfg.exp_bits, [](double x) { return std::exp2(x); },
                [ln2](double s) { return std::log2(s / ln2); }) +
            std::ldexp(1.0, -cfg.exp_frac);
}

PowUnit::PowUnit(const PowConfig& cfg, const MaterialParams& m,
                 std::shared_ptr<const PowTables> tables)
    : cfg_(cfg), tables_(std::move(tables)) {
  check_format(cfg.in);
  check_format(cfg.out);
  check_format(cfg.n_format);
  if (cfg.in.raw_one() == 0 || cfg.out.raw_one() == 0 || cfg.in.frac_bits < 1)
    // not from a spec: read_common_keys refuses such formats
    throw std::invalid_argument("pow: input and output formats must represent 1.0");
  if (cfg.log_bits < 1 || cfg.log_bits > 16)
    // not from a spec: the key reader takes log_bits in 1..16 only
    throw std::invalid_argument(fmt::format("pow: log_bits {}: must be in 1..16", cfg.log_bits));
  if (cfg.exp_bits < 1 || cfg.exp_bits > 16)
    // not from a spec: the key reader takes exp_bits in 1..16 only
    throw std::invalid_argument(fmt::format("pow: exp_bits {}: must be in 1..16", cfg.exp_bits));
  if (cfg.log_frac < 4 || cfg.log_frac > 30)
    // not from a spec: the key reader takes log_frac in 4..30 only
    throw std::invalid_argument(fmt::format("pow: log_frac {}: must be in 4..30", cfg.log_frac));
  if (cfg.y_frac < 4 || cfg.y_frac > 30)
    // not from a spec: the key reader takes y_frac in 4..30 only
    throw std::invalid_argument(fmt::format("pow: y_frac {}: must be in 4..30", cfg.y_frac));
  if (cfg.exp_frac < cfg.out.frac_bits || cfg.exp_frac > 30)
    // refusal: pow.exp_frac
    throw std::invalid_argument(fmt::format(
        "pow: {}: exp_frac must be in {}..30 (at least the output's fraction bits)",
        key_values({{"exp_frac", std::to_string(cfg.exp_frac)}, {"out", cfg.out.name()}}),
        cfg.out.frac_bits));
  if (!(m.shininess > 0) || m.shininess > cfg.n_format.max_value())
    // refusal: pow.n
    throw std::invalid_argument(fmt::format(
        "pow: {}: shininess {} outside the n register (at most {:.6g})",
        key_values({{"n", cfg.n_format.name()}}), m.shininess, cfg.n_format.max_value()));
  n_ = m.shininess;
  n_raw_ = quantize_n(n_, cfg.n_format);
  fi_ = cfg.in.frac_bits;
  one_in_ = cfg.in.raw_one();
  one_out_ = cfg.out.raw_one();

  // Mantissa fraction has fi bits: the top log_bits address the table (padded when fi is
  // smaller), the rest interpolate.
  log_r_bits_ = std::max(0, fi_ - cfg.log_bits);
  log_pad_ = std::max(0, cfg.log_bits - fi_);
  log_r_mask_ = (std::int64_t{1} << log_r_bits_) - 1;
  exp_r_bits_ = std::max(0, cfg.y_frac - cfg.exp_bits);
  exp_pad_ = std::max(0, cfg.exp_bits - cfg.y_frac);
  exp_r_mask_ = (std::int64_t{1} << exp_r_bits_) - 1;
  y_shift_ = cfg.n_format.frac_bits + cfg.log_frac - cfg.y_frac;
  out_shift_ = cfg.exp_frac - cfg.out.frac_bits;
  if (y_shift_ < 0)
    // refusal: pow.y_frac
    throw std::invalid_argument(fmt::format(
        "pow: {}: y_frac exceeds the {} fraction bits of the product n log2 t (n's and log_frac's)",
        key_values({{"y_frac", std::to_string(cfg.y_frac)},
                    {"n", cfg.n_format.name()},
                    {"log_frac", std::to_string(cfg.log_frac)}}),
        cfg.n_format.frac_bits + cfg.log_frac));
  // The interpolations multiply a node difference (entry bits + sign) by the remainder bits:
  // wide inputs leave many remainder bits below the table address (in.frac_bits - log_bits).
  if (cfg.log_frac + 2 + log_r_bits_ > 62)
    // refusal: pow.log_interpolation
    throw std::invalid_argument(fmt::format(
        "pow: log2 interpolation: {}: {} remainder bits (the input's fraction bits below the "
        "log_bits table index) by entries of log_frac fraction bits would be {} bits wide, more "
        "than 62",
        key_values({{"in", cfg.in.name()},
                    {"log_bits", std::to_string(cfg.log_bits)},
                    {"log_frac", std::to_string(cfg.log_frac)}}),
        log_r_bits_, cfg.log_frac + 2 + log_r_bits_));
  if (cfg.exp_frac + 3 + exp_r_bits_ > 62)
    // not from a spec: exp_frac + 3 + y_frac - exp_bits <= 30 + 3 + 29 under the keys' ranges
    throw std::invalid_argument(fmt::format(
        "pow: {}: the exp2 interpolation of {} remainder bits (y_frac below the exp_bits table "
        "index) by entries of exp_frac fraction bits would be {} bits wide, more than 62",
        key_values({{"y_frac", std::to_string(cfg.y_frac)},
                    {"exp_bits", std::to_string(cfg.exp_bits)},
                    {"exp_frac", std::to_string(cfg.exp_frac)}}),
        exp_r_bits_, cfg.exp_frac + 3 + exp_r_bits_));
  // n_raw * log2t must fit: |log2 t| <= fi, so it needs n width + log2(fi) + log_frac + 1 bits.
  if (cfg.n_format.width() + 6 + cfg.log_frac > 62)
    // refusal: pow.n_log
    throw std::invalid_argument(fmt::format(
        "pow: {}: the product n log2 t would be {} bits wide, more than 62",
        key_values({{"n", cfg.n_format.name()}, {"log_frac", std::to_string(cfg.log_frac)}}),
        cfg.n_format.width() + 6 + cfg.log_frac));

  if (tables_ == nullptr) {
    tables_ = std::make_shared<const PowTables>(cfg);
  } else if (!tables_->fits(cfg)) {
    // not from a spec: the build shares tables built from the same keys
    throw std::invalid_argument("pow: shared tables built for other table keys");
  }
  log_table_ = tables_->log_table.data();
  exp_table_ = tables_->exp_table.data();

  // Error bound, the terms named in the header comment; only dy depends on the material.
  const double nq = shininess_q();
  const double dy = nq * tables_->eps_log + std::ldexp(0.5, -cfg.y_frac);
  bound_ = (std::exp2(dy) * (1 + tables_->eps_exp) - 1) + std::ldexp(0.5, -cfg.out.frac_bits);
}

std::vector<PowUnit> build_pow_units(const PowConfig& cfg,
                                     const std::vector<MaterialParams>& slots) {
  std::vector<PowUnit> units;
  units.reserve(slots.size());
  // The first slot builds the tables (and checks the config, so a refusal reads as before: from
  // within a slot, naming it); every later slot shares them.
  std::shared_ptr<const PowTables> shared;
  for (const auto& m : slots) {
    for_slot(m, [&] { units.emplace_back(cfg, m, shared); });
    shared = units.back().tables();
  }
  return units;
}

double PowUnit::shininess_q() const {
  return input_value(n_raw_, cfg_.n_format);
}

double PowUnit::model(std::int64_t t_raw) const {
  const std::int64_t t = t_raw > one_in_ ? one_in_ : (t_raw < 0 ? 0 : t_raw);
  return std::pow(input_value(t, cfg_.in), shininess_q());
}

double PowUnit::float_model(double t) const {
  return t <= 0 ? 0.0 : std::pow(std::min(t, 1.0), n_);
}

std::size_t PowUnit::table_bits() const {
  // log2 entries reach 1.0 (log_frac + 1 bits), exp2 entries reach 2.0 (exp_frac + 2 bits).
  return ((std::size_t{1} << cfg_.log_bits) + 1) * static_cast<std::size_t>(cfg_.log_frac + 1) +
         ((std::size_t{1} << cfg_.exp_bits) + 1) * static_cast<std::size_t>(cfg_.exp_frac + 2);
}

}  // namespace glint
