#include "units/u_scaler_rtl.h"

#include <fmt/format.h>

#include <algorithm>

#include "hdl/verilog.h"

namespace glint {

std::string u_scaler_rtl(const hdl::DatapathPorts& p, const std::vector<const UScaler*>& groups,
                         const QFormat& in, int fh, bool loaded) {
  using hdl::ext;
  using hdl::lit;
  using hdl::range;
  const int wi = in.width(), fi = in.frac_bits;
  const int fk = fh + 2;  // UScaler: k two bits finer than u
  int kw = 1;
  std::vector<std::int64_t> root, k;
  for (const UScaler* s : groups) {
    kw = std::max(kw, s->k_int_bits() + s->k_frac());
    root.push_back(s->root_raw());
    k.push_back(s->k_raw());
  }
  const int shift = fi + fk - fh;  // UScaler's k_shift: (t - root) k has Fi + Fk fraction bits
  const int pw = wi + kw + 1;      // the product and its rounding half
  std::string s = hdl::comment(fmt::format(
      "u scaler (units/u_scaler.h, Hast et al. 2003 eq.2 as u = (t - tau) / (1 - tau)): "
      "u = (min(t, 1) - root) k,\n"
      "k = 1/(1 - root) rounded up to {} fraction bits, rounded half up to {} fraction bits, "
      "clamped to 1.0; 0 at t <= root",
      fk, fh));
  hdl::DatapathPorts tables = p;
  if (!loaded) tables.ram = nullptr;  // the same for every material: constants
  s += hdl::group_table(tables, "root", "in_group", wi, root,
                        "root: the comparator's threshold code (UScaler::root_raw)");
  s += hdl::group_table(tables, "k", "in_group", kw, k,
                        fmt::format("k = 1/(1 - root), uq{}.{} (UScaler::k_raw)", kw - fk, fk));
  s += fmt::format("  wire {} scaler_tc = (in_t > {}) ? {} : in_t;  // t clamped to 1.0\n",
                   range(wi), lit(wi, in.raw_one()), lit(wi, in.raw_one()));
  s += fmt::format("  wire {} scaler_diff = scaler_tc - root;\n", range(wi));
  s += fmt::format("  wire {} scaler_prod = {} * {};\n", range(pw), ext("scaler_diff", wi, pw),
                   ext("k", kw, pw));
  s += fmt::format("  wire {} scaler_q = (scaler_prod + {}) >> {};  // round half up\n", range(pw),
                   lit(pw, std::int64_t{1} << (shift - 1)), shift);
  const std::int64_t one_h = std::int64_t{1} << fh;
  s += fmt::format("  wire {} scaler_u = (in_t <= root) ? {} : (scaler_q > {}) ? {} : {};\n",
                   range(fh + 1), lit(fh + 1, 0), lit(pw, one_h), lit(fh + 1, one_h),
                   ext("scaler_q", pw, fh + 1));
  return s;
}

}  // namespace glint
