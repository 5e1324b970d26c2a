#include "units/n_register.h"

#include <algorithm>
#include <cmath>

namespace glint {

std::int64_t quantize_n(double n, const QFormat& format) {
  return std::max<std::int64_t>(
      1, Fixed::from_double(n, format, Quant::kRndConv, Overflow::kSat).raw());
}

NRegister elaborate_n_register(const QFormat& format, const std::vector<std::int64_t>& raw,
                               const std::vector<double>& target, bool fixed) {
  NRegister n;
  n.format = format;
  n.built = format;
  n.fixed = fixed;
  std::int64_t max_raw = 0;
  int low_zeros = 63;  // trailing zero bits every stored value has
  for (std::size_t g = 0; g < raw.size(); ++g) {
    max_raw = std::max(max_raw, raw[g]);
    if (raw[g] > 0)
      low_zeros = std::min(low_zeros, __builtin_ctzll(static_cast<unsigned long long>(raw[g])));
    const double err = std::fabs(input_value(raw[g], format) - target[g]);
    if (err > n.max_error) {
      n.max_error = err;
      n.worst = g;
    }
  }
  n.exact = n.max_error == 0;
  if (fixed || raw.empty() || max_raw <= 0 || format.frac_bits < 0) return n;
  // The value bits between the highest one and the lowest one any group stores: fraction bits
  // below the lowest one are zero in every value, integer bits above the highest one too.
  const int top = 64 - __builtin_clzll(static_cast<unsigned long long>(max_raw));
  const int frac = std::max(0, format.frac_bits - low_zeros);
  const int ints = std::max(0, top - format.frac_bits);
  n.built = uq(ints, frac);
  return n;
}

nlohmann::json n_register_json(const NRegister& n, const std::vector<MaterialParams>& groups) {
  nlohmann::json j{{"format", n.format.name()},
                   {"built", n.built.name()},
                   {"width", n.built.width()},
                   {"sized_to", n.fixed ? "format" : "scene"},
                   {"exact", n.exact}};
  if (!n.exact) {
    j["max_abs_error"] = n.max_error;
    j["at"] = n.worst < groups.size() ? groups[n.worst].name : std::string();
  }
  return j;
}

}  // namespace glint
