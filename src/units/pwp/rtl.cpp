// pwp in Verilog: t0, the offset widths and every quantized coefficient are read from the built
// PwpUnits (PwpUnit::coeff, after the monotone repair), never refitted here.
#include "units/pwp/rtl.h"

#include <fmt/format.h>

#include <algorithm>

#include "hdl/verilog.h"
#include "units/stage_rtl.h"

namespace glint {

PwpBank pwp_bank(const std::vector<PwpUnit>& groups, int segments, int j) {
  PwpBank b;
  const std::size_t rows = std::size_t{1} << segments;
  std::int64_t hi = 0;
  for (const PwpUnit& u : groups) {
    for (std::size_t k = 0; k < rows; ++k) {
      const std::int64_t c = k < u.segment_count() ? u.coeff(k, j) : 0;
      b.is_signed = b.is_signed || c < 0;
      hi = std::max(hi, c < 0 ? -c : c);
      b.words.push_back(c);
    }
  }
  b.width = hdl::value_bits(static_cast<std::uint64_t>(hi)) + (b.is_signed ? 1 : 0);
  return b;
}

std::string pwp_rtl(const hdl::DatapathPorts& p, const PwpConfig& c,
                    const std::vector<PwpUnit>& groups, const StageLayout& layout) {
  using hdl::ext;
  using hdl::lit;
  using hdl::range;
  using hdl::slit;
  const int d = c.degree, wi = c.in.width(), fi = c.in.frac_bits, wo = c.out.width();
  const int fo = c.out.frac_bits, fa = fo + c.guard, cf = c.coef_frac, wg = p.group_bits;
  const int sw = std::max(1, c.segments);  // the index register
  const Stage& lookup = rtl_stage(layout, "lookup");
  const int xw = lookup.registers[1].format.width();  // x: max(1, R)
  const int aw = lookup.registers[2].format.width();  // acc, signed
  const int sb = hdl::value_bits(static_cast<std::uint64_t>(fi));
  int rmax = 0;
  for (const PwpUnit& u : groups) rmax = std::max(rmax, u.offset_bits());
  std::vector<std::int64_t> t0, rbits, align;
  for (const PwpUnit& u : groups) {
    t0.push_back(u.t0_raw());
    rbits.push_back(u.offset_bits());
    align.push_back(rmax - u.offset_bits());
  }
  // Every group's x is aligned to R = the widest offset, so that one rounding shift serves all
  // (the same value: (acc x 2^a + 2^(R-1)) >> R = (acc x + 2^(r-1)) >> r for a = R - r). The
  // aligned x is a register of its own only where the alignment differs between groups (with
  // tables=ram: whenever there are groups, since another material may be loaded).
  const bool align_varies = p.ram != nullptr
                                ? p.groups > 1 && rmax > 0
                                : std::any_of(align.begin(), align.end(),
                                              [&](std::int64_t a) { return a != align.front(); });
  const bool carry_group = groups.size() > 1 || p.ram != nullptr;

  std::string s = hdl::datapath_header(
      p, fmt::format("{}: pwp, a piecewise polynomial per material: 2^{} segments over [t0, 1], "
                     "degree {} in the offset x below the\n"
                     "segment index, by Horner's rule (PwpUnit::run in units/pwp/datapath.h): acc "
                     "= c_d; acc = round(acc x) + c_j, j = d-1..1,\n"
                     "rounding half up to {} fraction bits; the last stage forms acc x + c_0 "
                     "exactly, rounds once to the output's {}\n"
                     "fraction bits and clamps to [0, 1]; t <= t0 gives 0 and t = 1 gives 1.0. "
                     "{} datapath group(s), coefficients at {} fraction bits.",
                     p.module, c.segments, d, fa, fo, groups.size(), cf));
  s += hdl::datapath_input_stage(p);

  // ---- stage 1: t - t0, the index and x, c_d.
  s += rtl_stage_registers(lookup,
                           "v = t - t0 split into the segment index and the offset x below it; "
                           "acc = c_d");
  s += hdl::group_table(p, "t0", "in_group", wi, t0,
                        "t0 = 1 - 2^-span, the first input code of the span (PwpUnit::t0_raw)");
  s += hdl::group_table(p, "rbits", "in_group", sb, rbits,
                        "input bits below the segment index (PwpUnit::offset_bits)");
  s += fmt::format("  wire lookup_short = in_t <= t0;  // t <= t0: result 0\n");
  s += fmt::format("  wire lookup_top = in_t >= {};  // t = 1 (or above): result 1.0\n",
                   lit(wi, c.in.raw_one()));
  s += fmt::format("  wire {} lookup_v = in_t - t0;\n", range(wi));
  s += fmt::format("  wire {} lookup_k = lookup_v >> rbits;\n", range(wi));
  s += fmt::format("  wire {} lookup_idx = {};\n", range(sw), ext("lookup_k", wi, sw));
  if (wi > sw)
    s += fmt::format("  wire unused_k = ^lookup_k[{}:{}];  // < 2^segments\n", wi - 1, sw);
  s += fmt::format("  wire {} lookup_r = lookup_v & ~({{{}{{1'b1}}}} << rbits);  // v mod 2^r\n",
                   range(wi), wi);
  if (wi > xw) s += fmt::format("  wire unused_r = ^lookup_r[{}:{}];\n", wi - 1, xw);
  // A coefficient bank read at {group, index}: a case ROM of every group's rows, or a RAM.
  const auto bank = [&](int j, const std::string& name, const std::string& g,
                        const std::string& idx) {
    PwpBank b = pwp_bank(groups, c.segments, j);
    std::string t = fmt::format("  wire {} {}_addr = {{{}, {}}};\n", range(wg + sw), name, g, idx);
    const std::string what = fmt::format(
        "c_{} of every segment (PwpUnit::coeff), {} fraction bits, {} bits{}, at "
        "{{group, segment}}",
        j, cf, b.width, b.is_signed ? " signed" : "");
    if (p.ram != nullptr) {
      hdl::RamTable r;
      r.name = name;
      r.width = b.width;
      r.is_signed = b.is_signed;
      r.words = std::move(b.words);
      r.what = what;
      t += hdl::ram_table(*p.ram, std::move(r), name + "_addr", wg + sw);
    } else {
      hdl::Rom r;
      r.name = name;
      r.addr = name + "_addr";
      r.addr_bits = wg + sw;
      r.data_bits = b.width;
      r.is_signed = b.is_signed;
      r.words = std::move(b.words);
      r.comment = what;
      t += hdl::rom(r);
    }
    return std::make_pair(t, pwp_bank(groups, c.segments, j));
  };
  const auto [cd_text, cd] = bank(d, "lookup_c", "in_group", "lookup_idx");
  s += cd_text;
  // acc = c_j << (fa - cf): the coefficient at the accumulator's fraction bits, sign-extended.
  const auto aligned_coeff = [&](const std::string& name, const PwpBank& b, int to) {
    return fmt::format("({} <<< {})", ext(name, b.width, to, b.is_signed), fa - cf);
  };
  // Carried beside the layout's registers: the flags, the index, the group, the aligned x.
  const auto carried = [&](int m) {
    std::string t = fmt::format("  reg short{0}, top{0};\n  reg {1} idx{0};\n", m, range(sw));
    if (carry_group) t += fmt::format("  reg {} g{};\n", range(wg), m);
    if (align_varies) t += fmt::format("  reg {} xa{};\n", range(xw), m);
    return t;
  };
  s += carried(1);
  if (align_varies)
    s += hdl::group_table(p, "align", "in_group", sb, align,
                          fmt::format("R - r: the offset aligned to R = {} bits", rmax));
  s += "  always @(posedge clk) begin\n";
  s += "    short1 <= lookup_short;\n    top1 <= lookup_top;\n    idx1 <= lookup_idx;\n";
  if (carry_group) s += "    g1 <= in_group;\n";
  if (align_varies) s += fmt::format("    xa1 <= {} << align;\n", ext("lookup_r", wi, xw));
  s += fmt::format("    {} <= lookup_idx;\n", rtl_reg(lookup, 0));
  s += fmt::format("    {} <= {};\n", rtl_reg(lookup, 1), ext("lookup_r", wi, xw));
  s += fmt::format("    {} <= {};\n", rtl_reg(lookup, 2), aligned_coeff("lookup_c", cd, aw));
  s += "  end\n";

  // ---- the multiply-add stages
  std::string x_prev = rtl_reg(lookup, 1), acc_prev = rtl_reg(lookup, 2);
  for (int m = 1; m <= d; ++m) {
    const Stage& st = rtl_stage(layout, fmt::format("mac{}", m));
    const int j = d - m;  // the coefficient this stage adds
    const bool last = m == d;
    const std::string xa = align_varies ? fmt::format("xa{}", m) : x_prev;
    s += rtl_stage_registers(
        st, last ? "acc x + c_0 exact, rounded once to the output, clamped; t <= t0: 0, t = 1: 1.0"
                 : fmt::format("x carried, acc = round(acc x) + c_{}", j));
    const auto [cj_text, cj] =
        bank(j, st.name + "_c", carry_group ? fmt::format("g{}", m) : "in_group",
             fmt::format("idx{}", m));
    s += cj_text;
    // acc (signed) times the aligned x (unsigned, a zero sign bit), in pw bits.
    const int pw = aw + xw + 2;
    const std::string prod = st.name + "_p";
    s += fmt::format("  wire signed {} {} = {} * {};\n", range(pw), prod,
                     ext(acc_prev, aw, pw, true), ext(xa, xw, pw));
    if (!last) {
      s += carried(m + 1);
      const std::string sh = st.name + "_s";
      s += fmt::format("  wire signed {} {} = ({} + {}) >>> {};  // round half up\n", range(pw), sh,
                       prod, slit(pw, rmax > 0 ? std::int64_t{1} << (rmax - 1) : 0), rmax);
      s += fmt::format("  wire unused_{} = ^{}[{}:{}];  // |acc| < 2^{}: the layout's bound\n",
                       st.name, sh, pw - 1, aw, aw - 1);
      s += "  always @(posedge clk) begin\n";
      s += fmt::format("    short{0} <= short{1};\n    top{0} <= top{1};\n    idx{0} <= idx{1};\n",
                       m + 1, m);
      if (carry_group) s += fmt::format("    g{} <= g{};\n", m + 1, m);
      if (align_varies) s += fmt::format("    xa{} <= xa{};\n", m + 1, m);
      s += fmt::format("    {} <= {};\n", rtl_reg(st, 0), x_prev);
      s += fmt::format("    {} <= {} + {};\n", rtl_reg(st, 1), ext(sh, pw, aw),
                       aligned_coeff(st.name + "_c", cj, aw));
      s += "  end\n";
      x_prev = rtl_reg(st, 0);
      acc_prev = rtl_reg(st, 1);
      continue;
    }
    // Last: (acc x + c_0 2^(fa - cf + R) + half) >> (fa + R - fo), the clamp, the two ends.
    const int shift = fa + rmax - fo;
    const std::string y = st.name + "_y";
    s += fmt::format("  wire signed {} {}_c0 = {};\n", range(pw), st.name,
                     ext(st.name + "_c", cj.width, pw, cj.is_signed));
    s += fmt::format("  wire signed {} {} = ({} + ({}_c0 <<< {}) + {}) >>> {};\n", range(pw), y,
                     prod, st.name, fa - cf + rmax,
                     slit(pw, shift > 0 ? std::int64_t{1} << (shift - 1) : 0), shift);
    if (align_varies)
      s += fmt::format("  wire unused_x = ^{};  // the product reads the aligned x\n", x_prev);
    s += fmt::format("  wire unused_index = ^{};  // the register shows the segment read\n",
                     rtl_reg(lookup, 0));
    const std::int64_t one = c.out.raw_one();
    s += "  always @(posedge clk)\n";
    s +=
        fmt::format("    {} <= short{} ? {} : top{} ? {} : ({} < {}) ? {} : ({} > {}) ? {} : {};\n",
                    rtl_reg(st, 0), m, lit(wo, 0), m, lit(wo, one), y, slit(pw, 0), lit(wo, 0), y,
                    slit(pw, one), lit(wo, one), ext(y, pw, wo));
    s += fmt::format("  assign result = {};\n", rtl_reg(st, 0));
  }
  s += hdl::datapath_footer(p);
  return s;
}

}  // namespace glint
