// sfu in Verilog: the SFU's tables are tesla_sfu's, each group's n is its SfuUnit::n_fp32, and
// every step is tesla_sfu.cpp's on the inputs the lane lets through. What it assumes (and the C++
// datapath guarantees): t in (0, 1] after the clamp (t = 0 is carried as a flag to a result of 0),
// so lg2 sees a normal positive fp32 and gives +0 (t = 1) or a negative normal; n is a positive
// normal below 2^24, so the product neither overflows nor underflows and is never NaN or
// infinite; RRO's and ex2's special codes are kept all the same (|x| >= 128 gives ex2 0), and
// ex2's result is at most 1.0, which to_fixed rounds to nearest even.
#include "units/sfu/rtl.h"

#include <fmt/format.h>

#include <cstdlib>

#include "hdl/verilog.h"
#include "units/stage_rtl.h"

namespace glint {
namespace {

// The top-most set bit of `v` (bits lo..hi) as a `width`-bit index, a ternary chain (no loop
// variable widths for the linter).
std::string leading_one(const std::string& v, int lo, int hi, int width) {
  std::string chain = hdl::lit(width, 0);
  for (int b = lo; b <= hi; ++b)
    chain = fmt::format("{}[{}] ? {} : ({})", v, b, hdl::lit(width, b), chain);
  return chain;
}

// One interpolator of Oberman & Siu, wires prefixed `p`: the table entry of `frac`'s top 6 bits
// (three case ROMs: A, B and C; lg2's C is stored as its magnitude and subtracted), r = its low 17
// bits and the truncated square of r (tesla_sfu.cpp, truncated_square).
std::string interpolator(const std::string& p, const tesla_sfu::Table& table, bool c_negative,
                         const std::string& frac, const std::string& what) {
  hdl::Rom a, b, c;
  a.name = p + "_a";
  b.name = p + "_b";
  c.name = p + "_c";
  a.addr = b.addr = c.addr = p + "_idx";
  a.addr_bits = b.addr_bits = c.addr_bits = 6;
  a.data_bits = 26;
  b.data_bits = 16;
  c.data_bits = 10;
  for (const auto& k : table) {
    a.words.push_back(k.a);
    b.words.push_back(k.b);
    c.words.push_back(std::abs(k.c));
  }
  a.comment = what + ": A of the 64 segments (tesla_tables.cpp)";
  b.comment = what + ": B";
  c.comment = what + (c_negative ? ": |C| (C < 0: subtracted)" : ": C");
  std::string s;
  s += fmt::format("  wire [5:0] {}_idx = {}[22:17];\n", p, frac);
  s += fmt::format("  wire [16:0] {}_r = {}[16:0];\n", p, frac);
  s += hdl::rom(a) + hdl::rom(b) + hdl::rom(c);
  // Row i of the squarer is r 2^i truncated to its bits of weight 2^18 and up: r >> (18 - i);
  // rows 0 and 1 are empty.
  std::string rows;
  for (int i = 2; i < tesla_sfu::kOffsetBits; ++i)
    rows +=
        fmt::format("{}({}_r[{}] ? ({}_r >> {}) : 17'd0)", i == 2 ? "" : " + ", p, i, p, 18 - i);
  s += fmt::format("  wire [16:0] {}_rows = {};  // the truncated squarer's rows\n", p, rows);
  s += fmt::format("  wire [15:0] {}_r2 = {}_rows[16:1];\n", p, p);
  s += fmt::format("  wire unused_{}_rows = {}_rows[0];\n", p, p);
  return s;
}

}  // namespace

std::string sfu_rtl(const hdl::DatapathPorts& p, const std::vector<SfuUnit>& groups,
                    const StageLayout& layout) {
  using hdl::ext;
  using hdl::lit;
  using hdl::range;
  const SfuConfig& c = groups.front().config();
  const int wi = c.in.width(), fi = c.in.frac_bits, wo = c.out.width(), g = c.out.frac_bits;
  const Stage& s1 = rtl_stage(layout, "lg2");
  const Stage& s2 = rtl_stage(layout, "fmul");
  const Stage& s3 = rtl_stage(layout, "pre");
  const Stage& s4 = rtl_stage(layout, "ex2");
  const Stage& s5 = rtl_stage(layout, "to_fixed");

  std::string s = hdl::datapath_header(
      p, fmt::format("{}: sfu, t^n = ex2(n lg2 t) bit for bit as an NVIDIA Tesla-class GPU "
                     "computes it (SfuUnit::run in\n"
                     "units/sfu/datapath.h, tesla_sfu.cpp): t to fp32, MUFU.LG2, FMUL by n, "
                     "RRO.EX2, MUFU.EX2, the fp32\n"
                     "result to {} rounded to nearest even. Assumes t in (0, 1] or t = 0 (a "
                     "flag), n a positive normal fp32:\n"
                     "lg2 then sees normal positive inputs and the product never overflows.",
                     p.module, c.out.name()));
  s += hdl::datapath_input_stage(p);

  // ---- stage 1: t to fp32 (2^-shift 1.f), lg2 of it.
  s += rtl_stage_registers(s1, "lg2 t as fp32: +0 at t = 1, else negative (one's complement)");
  s += "  reg z1, z2, z3, z4;  // t = 0: the result is 0 (carried)\n";
  s += fmt::format("  reg {} g1;  // the group carried to its n\n", range(p.group_bits));
  if (p.groups <= 1) s += "  wire unused_g1 = ^g1;  // (one n for every group: not read)\n";
  s += fmt::format("  wire {} lg_tc = (in_t > {}) ? {} : in_t;  // t clamped to 1.0\n", range(wi),
                   lit(wi, c.in.raw_one()), lit(wi, c.in.raw_one()));
  s += fmt::format("  wire [4:0] lg_e = {};  // leading one\n", leading_one("lg_tc", 0, fi, 5));
  s += fmt::format("  wire [4:0] lg_shift = {} - lg_e;  // t = 2^-shift 1.f\n", lit(5, fi));
  s += fmt::format("  wire {} lg_m = lg_tc << lg_shift;  // the leading one at bit {}\n", range(wi),
                   fi);
  if (wi > fi) s += fmt::format("  wire unused_lg_m = ^lg_m[{}:{}];\n", wi - 1, fi);
  s += fmt::format(
      "  wire [22:0] lg_f = {};  // the fp32 fraction\n",
      fi == 23 ? std::string("lg_m[22:0]") : fmt::format("{{lg_m[{}:0], {}'d0}}", fi - 1, 23 - fi));
  s += interpolator("lg", tesla_sfu::kLg2Table, true, "lg_f", "lg2");
  // The significand's log2 in 36 fraction bits: (A 2^12 + B r - 2 |C| r^2 + 0x3345) / 4, never
  // negative (every entry and r: checked in the C++ as the sum of its terms).
  s += "  wire [39:0] lg_sum = (" + ext("lg_a", 26, 40) + " << 12) + " + ext("lg_b", 16, 40) +
       " * " + ext("lg_r", 17, 40) + " - ((" + ext("lg_c", 10, 40) + " * " + ext("lg_r2", 16, 40) +
       ") << 1) + 40'h3345;\n";
  s += "  wire unused_lg_sum = ^{lg_sum[39:38], lg_sum[1:0]};\n";
  // fixed = frac - shift 2^36 < 0 for t < 1: its one's complement, shift 2^36 - frac - 1.
  s += "  wire [41:0] lg_mag = {1'b0, lg_shift, 36'd0} - {6'd0, lg_sum[37:2]} - 42'd1;\n";
  s += "  wire unused_lg_mag = lg_mag[41];  // below 24 2^36\n";
  s += fmt::format("  wire [5:0] lg_lead = {};\n", leading_one("lg_mag", 0, 40, 6));
  s += "  wire [40:0] lg_norm = lg_mag[40:0] << (6'd40 - lg_lead);  // truncated to 24 bits\n";
  s += "  wire unused_lg_norm = ^{lg_norm[40], lg_norm[16:0]};  // the leading one, the rest\n";
  s += "  wire [7:0] lg_exp = 8'd91 + {2'd0, lg_lead};\n";
  s += "  always @(posedge clk) begin\n";
  s += "    z1 <= in_t == " + lit(wi, 0) + ";\n";
  s += "    g1 <= in_group;\n";
  s += fmt::format(
      "    {} <= (lg_shift == 5'd0) ? 32'd0 : (lg_mag == 42'd0) ? 32'h80000000 : "
      "{{1'b1, lg_exp, lg_norm[39:17]}};\n",
      rtl_reg(s1, 0));
  s += "  end\n";

  // ---- stage 2: FMUL by n (round to nearest even).
  s += rtl_stage_registers(s2, "n (fp32) and the product lg2 t * n, rounded to nearest even");
  std::vector<std::int64_t> n;
  for (const SfuUnit& u : groups) n.push_back(u.n_fp32());
  s += hdl::group_table(p, "n", "g1", 31, n, "n as fp32 without its sign bit (SfuUnit::n_fp32)");
  const std::string x = rtl_reg(s1, 0);
  s += fmt::format("  wire [47:0] fm_p = {{24'd0, 1'b1, {}[22:0]}} * {{24'd0, 1'b1, n[22:0]}};\n",
                   x);
  s += fmt::format("  wire [9:0] fm_e0 = {{2'd0, {}[30:23]}} + {{2'd0, n[30:23]}} - 10'd126;\n", x);
  s += "  wire [23:0] fm_kept = fm_p[47] ? fm_p[47:24] : fm_p[46:23];\n";
  s += "  wire [23:0] fm_rest = fm_p[47] ? fm_p[23:0] : {fm_p[22:0], 1'b0};\n";
  s += "  wire [9:0] fm_e = fm_p[47] ? fm_e0 : fm_e0 - 10'd1;\n";
  s += "  wire fm_up = (fm_rest > 24'h800000) || (fm_rest == 24'h800000 && fm_kept[0]);\n";
  s += "  wire [24:0] fm_round = {1'b0, fm_kept} + {24'd0, fm_up};\n";
  s += "  wire [9:0] fm_exp = fm_round[24] ? fm_e + 10'd1 : fm_e;\n";
  s += "  wire [22:0] fm_frac = fm_round[24] ? 23'd0 : fm_round[22:0];\n";
  s += "  wire unused_fm = ^{fm_exp[9:8], fm_round[23]};  // normal products; the hidden one\n";
  s += "  always @(posedge clk) begin\n    z2 <= z1;\n";
  s += fmt::format("    {} <= {{1'b0, n}};\n", rtl_reg(s2, 0));
  s += fmt::format(
      "    {} <= ({}[30:23] == 8'd0) ? {{{}[31], 31'd0}} : {{{}[31], fm_exp[7:0], "
      "fm_frac}};\n",
      rtl_reg(s2, 1), x, x, x);
  s += "  end\n";
  s += fmt::format("  wire unused_fmul_n = ^{};  // shown beside the product\n", rtl_reg(s2, 0));

  // ---- stage 3: RRO.EX2: the sign and 7.23 fixed point, truncated.
  s += rtl_stage_registers(s3, "RRO.EX2: sign, |x| in 7.23 fixed point (0x40800000: |x| >= 128)");
  const std::string y = rtl_reg(s2, 1);
  s += fmt::format("  wire [7:0] rr_k = 8'd159 - {}[30:23];  // 32 - (exponent - 127)\n", y);
  s += fmt::format("  wire [55:0] rr_w = {{1'b1, {}[22:0], 32'd0}} >> rr_k;\n", y);
  s += "  wire unused_rr = ^rr_w[55:30];\n";
  s += "  always @(posedge clk) begin\n    z3 <= z2;\n";
  s += fmt::format(
      "    {} <= ({}[30:23] == 8'd0) ? {{{}[31], 31'd0}} : ({}[30:23] >= 8'd134) ? "
      "{{{}[31], 31'h40800000}} : {{{}[31], 1'b0, rr_w[29:0]}};\n",
      rtl_reg(s3, 0), y, y, y, y, y);
  s += "  end\n";

  // ---- stage 4: MUFU.EX2: 2^-(i + f) = 2^-(i + 1) 2^(1 - f), 1 - f as f's complement.
  s += rtl_stage_registers(s4, "ex2 as fp32");
  const std::string q = rtl_reg(s3, 0);
  s += fmt::format("  wire ex_neg = {}[31];\n", q);
  s += fmt::format("  wire [7:0] ex_i = {}[30:23];\n", q);
  s += fmt::format("  wire [22:0] ex_f0 = {}[22:0];\n", q);
  s += "  wire ex_fz = ex_f0 == 23'd0;\n";
  s += "  wire [22:0] ex_f = (ex_neg && !ex_fz) ? ~ex_f0 : ex_f0;\n";
  s += "  wire [9:0] ex_int = !ex_neg ? {2'd0, ex_i} : ex_fz ? 10'd0 - {2'd0, ex_i} : "
       "10'd0 - {2'd0, ex_i} - 10'd1;\n";
  s += interpolator("ex", tesla_sfu::kEx2Table, false, "ex_f", "ex2");
  s += "  wire [39:0] ex_sum = (" + ext("ex_a", 26, 40) + " << 13) + " + ext("ex_b", 16, 40) +
       " * " + ext("ex_r", 17, 40) + " + " + ext("ex_c", 10, 40) + " * " + ext("ex_r2", 16, 40) +
       " + 40'h77e2;\n";
  s += "  wire unused_ex_sum = ^{ex_sum[39:38], ex_sum[14:0]};  // 2^23 <= sum >> 15 < 2^24\n";
  s += "  wire [9:0] ex_exp = ex_int + 10'd127;\n";
  s += "  always @(posedge clk) begin\n    z4 <= z3;\n";
  s += fmt::format(
      "    {} <= ex_i[7] ? (!ex_i[0] ? 32'h7fffffff : ex_neg ? 32'd0 : 32'h7f800000) : "
      "(ex_exp[9] || ex_exp == 10'd0) ? 32'd0 : {{1'b0, ex_exp[7:0], ex_sum[37:15]}};\n",
      rtl_reg(s4, 0));
  s += "  end\n";

  // ---- stage 5: fp32 to the output format, rounded to nearest even, clamped to 1.0.
  s += rtl_stage_registers(s5, fmt::format("the result, {}", c.out.name()));
  const std::string e = rtl_reg(s4, 0);
  s += fmt::format("  wire [63:0] tf_x = {{40'd0, 1'b1, {}[22:0]}};\n", e);
  s += fmt::format("  wire [9:0] tf_s = 10'd{} - {{2'd0, {}[30:23]}};  // right shift\n", 150 - g,
                   e);
  s += "  wire [9:0] tf_ls = 10'd0 - tf_s;\n";
  s += "  wire [63:0] tf_l = tf_x << tf_ls[5:0];\n";
  s += "  wire [63:0] tf_q = tf_x >> tf_s[4:0];\n";
  s += "  wire [63:0] tf_rem = tf_x & ((64'd1 << tf_s[4:0]) - 64'd1);\n";
  s += "  wire [63:0] tf_half = (64'd1 << tf_s[4:0]) >> 1;\n";
  s += "  wire tf_up = (tf_rem > tf_half) || (tf_rem == tf_half && tf_q[0]);\n";
  s += "  wire [63:0] tf_r = tf_s[9] || tf_s == 10'd0 ? tf_l : "
       "(tf_s > 10'd30) ? 64'd0 : tf_q + {63'd0, tf_up};\n";
  s += fmt::format("  wire unused_tf = ^{{tf_ls[9:6], {}[31]}};\n", e);
  const std::int64_t one = c.out.raw_one();
  s += "  always @(posedge clk) begin\n";
  s += fmt::format("    {} <= (z4 || {}[30:23] == 8'd0) ? {} : (tf_r > {}) ? {} : {};\n",
                   rtl_reg(s5, 0), e, lit(wo, 0), lit(64, one), lit(wo, one), ext("tf_r", 64, wo));
  s += "  end\n";
  s += fmt::format("  assign result = {};\n", rtl_reg(s5, 0));
  s += hdl::datapath_footer(p);
  return s;
}

}  // namespace glint
