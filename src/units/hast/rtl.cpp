// hast in Verilog: the u scaler's root and k and each group's order d are read from the built
// HastUnits; the chain's widths and roundings are HastUnit::run's.
#include "units/hast/rtl.h"

#include <fmt/format.h>

#include "hdl/verilog.h"
#include "units/stage_rtl.h"
#include "units/u_scaler_rtl.h"

namespace glint {
namespace {

// (a * b + half) >> shift as a wire `name` of the product's width (2 (fh + 1) bits): round half
// up, UScaler's and round_nearest's rounding. shift 0: the exact product.
std::string rounded_product(const std::string& name, const std::string& a, const std::string& b,
                            int w, int shift) {
  const int pw = 2 * w;
  if (shift == 0)
    return fmt::format("  wire {} {} = {} * {};\n", hdl::range(pw), name, hdl::ext(a, w, pw),
                       hdl::ext(b, w, pw));
  return fmt::format("  wire {} {} = ({} * {} + {}) >> {};\n", hdl::range(pw), name,
                     hdl::ext(a, w, pw), hdl::ext(b, w, pw),
                     hdl::lit(pw, std::int64_t{1} << (shift - 1)), shift);
}

}  // namespace

std::string hast_rtl(const hdl::DatapathPorts& p, const HastConfig& c,
                     const std::vector<HastUnit>& groups, const StageLayout& layout) {
  using hdl::ext;
  using hdl::lit;
  using hdl::range;
  const int d = c.d, wo = c.out.width(), fo = c.out.frac_bits;
  const int fh = fo + c.guard, w = fh + 1;
  const int pw = 2 * w;
  std::vector<const UScaler*> scalers;
  std::vector<std::int64_t> order;
  for (const HastUnit& u : groups) {
    scalers.push_back(&u.scaler());
    order.push_back(u.order());
  }
  std::string s = hdl::datapath_header(
      p, fmt::format("{}: hast, Hast et al. 2003 eq.2 f = kappa (t - tau)^d in the overflow-free "
                     "form u^d,\n"
                     "u = (t - tau) k, k = 1/(1 - tau) (HastUnit::run in units/hast/datapath.h): "
                     "the u scaler, then d - 1 = {}\n"
                     "multipliers of {} x {} bits, each rounding half up to {} fraction bits, the "
                     "last to the output's {}.{}",
                     p.module, d - 1, w, w, fh, fo,
                     c.per_slot_d ? "\nd=auto: each group's own order d_s <= d; stages past d_s "
                                    "multiply by 1.0 (an operand mux)."
                                  : ""));
  s += hdl::datapath_input_stage(p);
  const Stage& scale = rtl_stage(layout, "scale");
  s += rtl_stage_registers(scale, d == 1 ? "u, rounded to the output" : "u");
  s += u_scaler_rtl(p, scalers, c.in, fh);
  const int db = hdl::value_bits(static_cast<std::uint64_t>(d));
  if (c.per_slot_d && d > 1) {
    s += hdl::group_table(p, "order", "in_group", db, order,
                          "the group's order d_s (d=auto: HastUnit::order)");
    for (int k = 1; k < d; ++k)
      s += fmt::format("  reg {} d{};  // d_s carried beside position {}\n", range(db), k, k);
  }
  if (d == 1) {
    const int shift = fh - fo;
    const std::string q =
        shift == 0 ? "scaler_u"
                   : fmt::format("(scaler_u + {}) >> {}", lit(w, 1 << (shift - 1)), shift);
    s += fmt::format("  wire {} scale_r = {};\n", range(w), q);
    if (w > wo) s += fmt::format("  wire unused_r = ^scale_r[{}:{}];  // <= 1.0\n", w - 1, wo);
    s += fmt::format("  always @(posedge clk) {} <= {};\n", rtl_reg(scale, 0),
                     ext("scale_r", w, wo));
    s += fmt::format("  assign result = {};\n", rtl_reg(scale, 0));
    s += hdl::datapath_footer(p);
    return s;
  }
  s += "  always @(posedge clk) begin\n";
  s += fmt::format("    {} <= scaler_u;\n", rtl_reg(scale, 0));
  if (c.per_slot_d) s += "    d1 <= order;\n";  // d > 1 here
  s += "  end\n";

  std::string u_prev = rtl_reg(scale, 0), power_prev = rtl_reg(scale, 0);
  for (int k = 2; k <= d; ++k) {
    const Stage& st = rtl_stage(layout, fmt::format("mul{}", k - 1));
    const bool last = k == d;
    s += rtl_stage_registers(st, last ? fmt::format("u^{} rounded to the output", d)
                                      : fmt::format("u carried, u^{} = u^{} u rounded", k, k - 1));
    std::string operand = u_prev;
    if (c.per_slot_d) {
      // Stage k multiplies by u while k <= d_s, else by 1.0 (HastUnit::run's shorter orders).
      operand = st.name + "_operand";
      s += fmt::format("  wire {} {} = (d{} >= {}) ? {} : {};\n", range(w), operand, k - 1,
                       lit(db, k), u_prev, lit(w, std::int64_t{1} << fh));
    }
    const std::string prod = st.name + "_q";
    const int shift = last ? 2 * fh - fo : fh;
    s += rounded_product(prod, power_prev, operand, w, shift);
    const int keep = last ? wo : w;
    s += fmt::format("  wire unused_{} = ^{}[{}:{}];  // the product rounded is <= 1.0\n", st.name,
                     prod, pw - 1, keep);
    s += "  always @(posedge clk) begin\n";
    if (last) {
      s += fmt::format("    {} <= {};\n", rtl_reg(st, 0), ext(prod, pw, wo));
    } else {
      s += fmt::format("    {} <= {};\n", rtl_reg(st, 0), u_prev);
      s += fmt::format("    {} <= {};\n", rtl_reg(st, 1), ext(prod, pw, w));
      if (c.per_slot_d) s += fmt::format("    d{} <= d{};\n", k, k - 1);
    }
    s += "  end\n";
    if (!last) {
      u_prev = rtl_reg(st, 0);
      power_prev = rtl_reg(st, 1);
    } else {
      s += fmt::format("  assign result = {};\n", rtl_reg(st, 0));
    }
  }
  s += hdl::datapath_footer(p);
  return s;
}

}  // namespace glint
