// lut in Verilog: every constant is read from the built LutUnit of each datapath group (t0, the
// span's shifts, the table's entries through LutUnit::entry), never recomputed here.
#include "units/lut/rtl.h"

#include <fmt/format.h>

#include <algorithm>

#include "hdl/verilog.h"
#include "units/stage_rtl.h"

namespace glint {
namespace {

// The t^n tables as two banks, the even nodes and the odd ones, each group's 2^bits + 2 entries
// (j = 0..2^bits + 1) at group (2^(bits-1) + 1) + j / 2 (registers, tables=ram) or at {group,
// j / 2} (a case ROM a bank). The two nodes j and j + 1 a request reads are one even and one odd,
// so each bank is read once: as ROMs, two half tables in place of the whole one read at two
// addresses; as registers, the two read muxes together are no larger than one over the whole
// table (the cost model's tables).
std::string lut_banked_tables(const hdl::DatapathPorts& p, const std::vector<LutUnit>& groups,
                              int bits, int tw, int iw, const std::string& what) {
  using hdl::ext;
  using hdl::range;
  const int wg = p.group_bits;
  const int half = (1 << (bits - 1)) + 1;  // entries a group in each bank
  const std::size_t stride = std::size_t{1} << (iw - 1);
  std::vector<std::int64_t> even, odd;
  for (const LutUnit& u : groups) {
    if (p.ram == nullptr) {  // {group, h}: each group's bank padded to a power of two
      even.resize(even.size() == 0 ? 0 : (even.size() + stride - 1) / stride * stride, 0);
      odd.resize(even.size(), 0);
    }
    for (int h = 0; h < half; ++h) {
      even.push_back(u.entry(2 * h));
      odd.push_back(u.entry(2 * h + 1));
    }
  }
  const std::string even_what = what + "\nthe even entries j = 2h";
  const std::string odd_what = what + "\nthe odd entries j = 2h + 1";
  // node j = i in one bank, j = i + 1 in the other: the even bank is read at (i + 1) / 2, the
  // odd one at i / 2, and i's low bit says which holds node_lo.
  std::string s;
  s += fmt::format("  wire {} lookup_ih = lookup_i[{}:1];\n", range(iw - 1), iw - 1);
  s += fmt::format("  wire {} lookup_i1h = lookup_i1[{}:1];\n", range(iw - 1), iw - 1);
  if (p.ram != nullptr) {
    hdl::RamTable e{}, o{};
    e.name = "tn_even";
    o.name = "tn_odd";
    e.width = o.width = tw;
    e.words = std::move(even);
    o.words = std::move(odd);
    e.what = even_what + ", at group (2^(bits-1) + 1) + h";
    o.what = odd_what + ", at group (2^(bits-1) + 1) + h";
    const int ab = hdl::index_bits(e.words.size());
    s += hdl::ram_array(*p.ram, std::move(e));
    s += hdl::ram_array(*p.ram, std::move(o));
    const auto addr = [&](const std::string& h) {
      const std::string hi = ext(h, iw - 1, ab);
      if (groups.size() == 1) return hi;
      return fmt::format("{} * {} + {}", ext("in_group", wg, ab), hdl::lit(ab, half), hi);
    };
    s += fmt::format("  wire {} lookup_even = tn_even_mem[{}];\n", range(tw), addr("lookup_i1h"));
    s += fmt::format("  wire {} lookup_odd = tn_odd_mem[{}];\n", range(tw), addr("lookup_ih"));
  } else {
    hdl::Rom e, o;
    e.name = "lookup_even";
    o.name = "lookup_odd";
    e.addr = "{in_group, lookup_i1h}";
    o.addr = "{in_group, lookup_ih}";
    e.addr_bits = o.addr_bits = wg + iw - 1;
    e.data_bits = o.data_bits = tw;
    e.words = std::move(even);
    o.words = std::move(odd);
    e.comment = even_what + ", at {group, h}";
    o.comment = odd_what + ", at {group, h}";
    s += hdl::rom(e);
    s += hdl::rom(o);
  }
  s += fmt::format("  wire {} lookup_lo = lookup_i[0] ? lookup_odd : lookup_even;\n", range(tw));
  s += fmt::format("  wire {} lookup_hi = lookup_i[0] ? lookup_even : lookup_odd;\n", range(tw));
  s += "  wire unused_i1 = lookup_i1[0];  // (i + 1)'s bank is the other one\n";
  return s;
}

}  // namespace

std::string lut_rtl(const hdl::DatapathPorts& p, const LutConfig& c,
                    const std::vector<LutUnit>& groups, const StageLayout& layout) {
  using hdl::ext;
  using hdl::lit;
  using hdl::range;
  const int wi = c.in.width(), fi = c.in.frac_bits, wo = c.out.width();
  const int tf = c.table_frac, tw = tf + 1, bits = c.bits, wg = p.group_bits;
  const Stage& lookup = rtl_stage(layout, "lookup");
  const Stage& interp = rtl_stage(layout, "interp");
  const int iw = lookup.registers[0].format.width();  // index: bits + 1
  const int fw = lookup.registers[1].format.width();  // remainder: max(1, R)

  // Per group: t0, the remainder bits r (index = (t - t0) >> r) and the padding (index << pad:
  // inputs finer than the table's step do not exist, datapath.h), and R - r, which aligns every
  // group's remainder to the widest R so that stage 2 rounds at one shift for all of them.
  std::vector<std::int64_t> t0, rbits, pad, align;
  int rmax = 0;
  for (const LutUnit& u : groups) rmax = std::max(rmax, u.remainder_bits());
  for (const LutUnit& u : groups) {
    t0.push_back(u.t0_raw());
    rbits.push_back(u.remainder_bits());
    pad.push_back(std::max(0, bits - (fi - u.span_log2())));
    align.push_back(rmax - u.remainder_bits());
  }
  // The group is carried to stage 2 for its alignment when that differs between groups (with
  // tables=ram: whenever there are groups, since another material may be loaded).
  const bool align_varies = p.ram != nullptr
                                ? p.groups > 1 && rmax > 0
                                : std::any_of(align.begin(), align.end(),
                                              [&](std::int64_t a) { return a != align.front(); });
  const int kw = std::max(wi, iw);  // the index before its padding shift
  const int sb = hdl::value_bits(static_cast<std::uint64_t>(std::max(fi, bits)));

  std::string s = hdl::datapath_header(
      p, fmt::format("{}: lut, a table of t^n per material + linear interpolation (the baseline "
                     "Schlick 1994 names).\n"
                     "Stages (lut.cpp, LutUnit::run in units/lut/datapath.h): lookup (index, "
                     "remainder, both nodes), interp.\n"
                     "{} datapath group(s), 2^{} + 1 entries each of {} bits (t^n rounded to {} "
                     "fraction bits).",
                     p.module, groups.size(), bits, tw, tf));
  s += hdl::datapath_input_stage(p);

  // ---- stage 1
  s += rtl_stage_registers(lookup,
                           "t - t0 split into the table index and the remainder below it; the "
                           "two nodes around t");
  s += "  reg lookup_short;  // t <= t0: below the table's span, result 0 (carried)\n";
  if (align_varies) s += fmt::format("  reg {} lookup_group;  // carried to stage 2\n", range(wg));
  s += hdl::group_table(p, "t0", "in_group", wi, t0,
                        "t0 = 1 - 2^-span, the table's first node (LutUnit::t0_raw)");
  s += hdl::group_table(p, "rbits", "in_group", sb, rbits,
                        "input bits below the index (LutUnit::remainder_bits)");
  s += hdl::group_table(p, "pad", "in_group", sb, pad,
                        "index padding: the span holds fewer codes than the table has segments");
  s += fmt::format("  wire {} lookup_tc = (in_t > {}) ? {} : in_t;  // t clamped to 1.0\n",
                   range(wi), lit(wi, c.in.raw_one()), lit(wi, c.in.raw_one()));
  s += fmt::format("  wire {} lookup_v = lookup_tc - t0;  // v = t - t0\n", range(wi));
  s += fmt::format("  wire {} lookup_vw = {};\n", range(kw), ext("lookup_v", wi, kw));
  s += fmt::format("  wire {} lookup_k = (lookup_vw >> rbits) << pad;  // i = (v >> r) << pad\n",
                   range(kw));
  s += fmt::format("  wire {} lookup_i = {};\n", range(iw), ext("lookup_k", kw, iw));
  // v < 2^(Fi - span): the bits above the index and the remainder are 0 by construction.
  if (kw > iw) s += fmt::format("  wire unused_k = ^lookup_k[{}:{}];\n", kw - 1, iw);
  s += fmt::format("  wire {} lookup_i1 = lookup_i + {};\n", range(iw), lit(iw, 1));
  s += fmt::format("  wire {} lookup_rem = lookup_v & ~({{{}{{1'b1}}}} << rbits);  // v mod 2^r\n",
                   range(wi), wi);
  if (wi > fw) s += fmt::format("  wire unused_rem = ^lookup_rem[{}:{}];\n", wi - 1, fw);
  // The t^n table of every group: entries 0..2^bits and the padding entry 2^bits + 1 (the last
  // node again, read as node_hi at t = 1), in an even and an odd bank.
  s += lut_banked_tables(
      p, groups, bits, tw, iw,
      fmt::format("t^n at the nodes t0 + j (1 - t0) 2^-{} of each group, rounded to {} fraction "
                  "bits (LutUnit::entry), j = 0..2^{} + 1 (the last entry repeats 1.0 for node_hi "
                  "at t = 1)",
                  bits, tf, bits));
  const std::string node_lo = "lookup_lo", node_hi = "lookup_hi";
  s += "  always @(posedge clk) begin\n";
  s += "    lookup_short <= in_t <= t0;\n";
  if (align_varies) s += "    lookup_group <= in_group;\n";
  s += fmt::format("    {} <= lookup_i;\n", rtl_reg(lookup, 0));
  s += fmt::format("    {} <= {};\n", rtl_reg(lookup, 1), ext("lookup_rem", wi, fw));
  s += fmt::format("    {} <= {};\n", rtl_reg(lookup, 2), node_lo);
  s += fmt::format("    {} <= {};\n", rtl_reg(lookup, 3), node_hi);
  s += "  end\n";

  // ---- stage 2: y = (a << r) + (b - a) rem, exact, then one rounding (half up) and the clamp.
  s += rtl_stage_registers(interp,
                           "(a << r) + (b - a) r formed exactly, rounded once to the "
                           "output (round half up), clamped to 1.0");
  const int shift = rmax + tf - c.out.frac_bits;  // the same for every group once aligned
  const int dw = tw + 1;                          // b - a, signed
  const int yw = tw + rmax + 3;                   // y, signed, with room for the rounding half
  s += fmt::format(
      "  wire signed {} interp_lo = {};\n", range(yw),
      rmax > 0 ? fmt::format("{{{}'d0, {}, {}'d0}}", yw - tw - rmax, rtl_reg(lookup, 2), rmax)
               : ext(rtl_reg(lookup, 2), tw, yw));
  if (rmax > 0) {
    s += hdl::group_table(p, "align", "lookup_group", sb, align,
                          fmt::format("R - r: the remainder aligned to R = {} bits", rmax));
    s += fmt::format("  wire {} interp_rem = {} << align;\n", range(fw), rtl_reg(lookup, 1));
    s += fmt::format("  wire signed {} interp_diff = {} - {};  // b - a\n", range(dw),
                     ext(rtl_reg(lookup, 3), tw, dw), ext(rtl_reg(lookup, 2), tw, dw));
    const int pw = dw + fw + 1;
    s += fmt::format("  wire signed {} interp_prod = {} * $signed({});\n", range(pw),
                     ext("interp_diff", dw, pw, true), ext("interp_rem", fw, pw));
    s += fmt::format("  wire signed {} interp_y = interp_lo + {};\n", range(yw),
                     ext("interp_prod", pw, yw, true));
  } else {
    s += fmt::format("  wire unused_interp = ^{{{}, {}}};  // no input bits below the index\n",
                     rtl_reg(lookup, 1), rtl_reg(lookup, 3));
    s += fmt::format("  wire signed {} interp_y = interp_lo;\n", range(yw));
  }
  s += fmt::format("  wire unused_index = ^{};  // the index register shows the address read\n",
                   rtl_reg(lookup, 0));
  s += fmt::format("  wire signed {} interp_q = (interp_y + {}) >>> {};  // round_nearest\n",
                   range(yw), hdl::slit(yw, shift > 0 ? std::int64_t{1} << (shift - 1) : 0), shift);
  const std::int64_t one = c.out.raw_one();
  s += "  always @(posedge clk)\n";
  s += fmt::format("    {} <= lookup_short ? {} : (interp_q > {}) ? {} : {};\n", rtl_reg(interp, 0),
                   lit(wo, 0), hdl::slit(yw, one), lit(wo, one), ext("interp_q", yw, wo));
  s += fmt::format("  assign result = {};\n", rtl_reg(interp, 0));
  s += hdl::datapath_footer(p);
  return s;
}

}  // namespace glint
