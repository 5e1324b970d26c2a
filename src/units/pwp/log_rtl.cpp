// pwp's domain=log in Verilog: the lg2 and ex2 coefficients are the built PwpLogTables' (one ROM
// per coefficient, the same for every material, also with tables=ram), each group's n its
// PwpLogPath::n_raw (a group table: loadable with tables=ram); the shifts and roundings are
// PwpLogPath::run's.
#include <fmt/format.h>

#include <algorithm>

#include "hdl/verilog.h"
#include "units/pwp/log_kind.h"
#include "units/pwp/rtl.h"
#include "units/stage_rtl.h"

namespace glint {
namespace {

using hdl::ext;
using hdl::lit;
using hdl::range;
using hdl::slit;

// Coefficient j of a shared table as a case ROM read at `addr` (`bits` wide, at least 1).
std::string coeff_rom(const std::string& name, const std::vector<std::int64_t>& table,
                      std::size_t stride, int j, const std::string& addr, int bits,
                      const std::string& what, PwpBank& bank) {
  bank = pwp_log_bank(table, stride, j);
  hdl::Rom r;
  r.name = name;
  r.addr = addr;
  r.addr_bits = bits;
  r.data_bits = bank.width;
  r.is_signed = bank.is_signed;
  r.words = bank.words;
  r.comment = fmt::format("{} c_{} of every segment, {} bits{} (PwpLogTables; every material)",
                          what, j, bank.width, bank.is_signed ? " signed" : "");
  return hdl::rom(r);
}

}  // namespace

std::string pwp_log_rtl(const hdl::DatapathPorts& p, const PwpConfig& c,
                        const std::vector<PwpUnit>& groups, const StageLayout& layout) {
  const PwpLogTables& T = groups.front().log_path()->tables();
  const PwpLogFormats f = pwp_log_formats(c, T);
  const int d = c.degree, wi = c.in.width(), fi = c.in.frac_bits, wo = c.out.width();
  const int wg = p.group_bits, eb = f.big_e.width(), liw = f.lg_index.width();
  const int lxw = f.lg_x.width(), law = f.lg_acc.width(), tw = f.log2t.width();
  const int yw = f.y.width(), yiw = f.y_int.width(), eiw = f.ex_index.width();
  const int exw = f.ex_x.width(), eaw = f.ex_acc.width(), nw = c.n_format.width();
  const int y_shift = groups.front().log_path()->y_shift();
  std::vector<std::int64_t> ns;
  for (const PwpUnit& u : groups) ns.push_back(u.log_path()->n_raw());

  std::string s = hdl::datapath_header(
      p, fmt::format("{}: pwp domain=log, t^n = ex2(n lg2 t) (PwpLogPath::run in "
                     "units/pwp/log_datapath.h): a leading-one\n"
                     "detector, lg2 of the mantissa by 2^{} segments of degree {} (Horner, {} "
                     "fraction bits), y = n log2 t rounded\n"
                     "to {} bits, ex2 of y's fraction by 2^{} segments (Horner, {} fraction bits), "
                     "the shift by floor(y) and\n"
                     "one rounding half up to {} bits, clamped; t = 0 gives 0 and t = 1 gives 1.0. "
                     "The coefficient ROMs are the\n"
                     "same for every material; only n is per datapath group ({} group(s)).",
                     p.module, T.sl, d, T.fl, T.fy, T.se, T.fe, c.out.frac_bits, groups.size()));
  s += hdl::datapath_input_stage(p);

  // Carried beside the layout's registers from position m on: t = 0, t = 1, the group (until
  // its n is read), the segment index.
  const auto carried = [&](int m, bool group, int idx_w) {
    std::string t = fmt::format("  reg zc{0}, tp{0};\n", m);
    if (group) t += fmt::format("  reg {} g{};\n", range(wg), m);
    if (idx_w > 0) t += fmt::format("  reg {} ix{};\n", range(idx_w), m);
    return t;
  };

  // ---- position 1: the leading one, the mantissa's index and offset, lg2's c_d.
  const Stage& s1 = rtl_stage(layout, "lg_lookup");
  s += rtl_stage_registers(s1,
                           "t = 2^-e (1 + mf 2^-F): e, mf's segment index and offset x, "
                           "acc = c_d");
  std::string lzd = lit(eb, 0);
  for (int b = 0; b <= fi; ++b)
    lzd = fmt::format("in_t[{}] ? {} : {}", b, lit(eb, fi - b),
                      b == 0 ? lit(eb, 0) : "(" + lzd + ")");
  s += fmt::format("  wire {} ll_e = {};  // leading-one detector\n", range(eb), lzd);
  s += fmt::format("  wire {} ll_m = in_t << ll_e;  // 1.mf, the leading one at bit {}\n",
                   range(wi), fi);
  s += fmt::format("  wire unused_ll = ^ll_m[{}:{}];\n", wi - 1, fi);
  const std::string lidx =
      T.sl > 0 ? fmt::format("ll_m[{}:{}]", fi - 1, T.rl) : std::string("1'b0");
  const std::string lx = T.rl > 0 ? fmt::format("ll_m[{}:0]", T.rl - 1) : std::string("1'b0");
  s +=
      fmt::format("  wire {} ll_k = {};\n  wire {} ll_x = {};\n", range(liw), lidx, range(lxw), lx);
  PwpBank bank;
  s += coeff_rom("ll_c", T.lg, T.stride, d, "ll_k", liw, "lg2", bank);
  s += carried(1, true, liw);
  s += "  always @(posedge clk) begin\n";
  s += fmt::format("    zc1 <= in_t == {};\n    tp1 <= in_t >= {};\n", lit(wi, 0),
                   lit(wi, c.in.raw_one()));
  s += "    g1 <= in_group;\n    ix1 <= ll_k;\n";
  s += fmt::format("    {} <= ll_e;\n    {} <= ll_k;\n    {} <= ll_x;\n", rtl_reg(s1, 0),
                   rtl_reg(s1, 1), rtl_reg(s1, 2));
  s += fmt::format("    {} <= {};\n  end\n", rtl_reg(s1, 3),
                   ext("ll_c", bank.width, law, bank.is_signed));
  s += fmt::format("  wire unused_lk = ^{};  // the register shows the segment read\n",
                   rtl_reg(s1, 1));

  // One multiply-add of a Horner evaluator: `acc x` (signed by unsigned) in pw bits.
  const auto product = [&](const std::string& name, const std::string& acc, int aw,
                           const std::string& x, int xw) {
    const int pw = aw + xw + 2;
    return std::make_pair(fmt::format("  wire signed {} {} = {} * {};\n", range(pw), name,
                                      ext(acc, aw, pw, true), ext(x, xw, pw)),
                          pw);
  };

  // ---- positions 2..d: lg2's multiply-adds, rounded half up to fl bits.
  std::string e_prev = rtl_reg(s1, 0), x_prev = rtl_reg(s1, 2), acc_prev = rtl_reg(s1, 3);
  for (int m = 1; m < d; ++m) {
    const Stage& st = rtl_stage(layout, fmt::format("lg_mac{}", m));
    const int j = d - m, pos = m + 1;
    s += rtl_stage_registers(st, fmt::format("e, x carried; acc = round(acc x) + c_{}", j));
    const std::string c_name = fmt::format("lm{}_c", m);
    s += coeff_rom(c_name, T.lg, T.stride, j, fmt::format("ix{}", pos - 1), liw, "lg2", bank);
    const auto [pt, pw] = product(fmt::format("lm{}_p", m), acc_prev, law, x_prev, lxw);
    s += pt;
    s += fmt::format("  wire signed {} lm{}_s = (lm{}_p + {}) >>> {};\n", range(pw), m, m,
                     slit(pw, T.lg_half), T.rl);
    s += fmt::format("  wire unused_lm{0} = ^lm{0}_s[{1}:{2}];\n", m, pw - 1, law);
    s += carried(pos, true, liw);
    s += "  always @(posedge clk) begin\n";
    s += fmt::format(
        "    zc{0} <= zc{1};\n    tp{0} <= tp{1};\n    g{0} <= g{1};\n"
        "    ix{0} <= ix{1};\n",
        pos, pos - 1);
    s += fmt::format("    {} <= {};\n    {} <= {};\n", rtl_reg(st, 0), e_prev, rtl_reg(st, 1),
                     x_prev);
    s += fmt::format("    {} <= {} + {};\n  end\n", rtl_reg(st, 2),
                     ext(fmt::format("lm{}_s", m), pw, law),
                     ext(c_name, bank.width, law, bank.is_signed));
    e_prev = rtl_reg(st, 0);
    x_prev = rtl_reg(st, 1);
    acc_prev = rtl_reg(st, 2);
  }

  // ---- position d + 1: acc x + c_0 exact, rounded to fl bits; log2 t = Lg - e; n read.
  const Stage& sl = rtl_stage(layout, "lg_last");
  s += rtl_stage_registers(sl, "log2 t = round(acc x + c_0) - e; the group's n read beside it");
  s += coeff_rom("lz_c", T.lg, T.stride, 0, fmt::format("ix{}", d), liw, "lg2", bank);
  {
    const auto [pt, pw] = product("lz_p", acc_prev, law, x_prev, lxw);
    s += pt;
    s += fmt::format("  wire signed {} lz_v = (lz_p + ({} <<< {}) + {}) >>> {};\n", range(pw),
                     ext("lz_c", bank.width, pw, bank.is_signed), T.rl, slit(pw, T.lg_half), T.rl);
    if (pw > tw) s += fmt::format("  wire unused_lz = ^lz_v[{}:{}];  // Lg <= 1.0\n", pw - 1, tw);
    s += hdl::group_table(p, "n", fmt::format("g{}", d), nw, ns,
                          fmt::format("n, {} (PwpLogPath::n_raw)", c.n_format.name()));
    if (p.ram == nullptr &&
        std::all_of(ns.begin(), ns.end(), [&](std::int64_t v) { return v == ns.front(); }))
      s += fmt::format("  wire unused_g = ^g{};  // one n for every group: not read\n", d);
    s += carried(d + 1, false, 0);
    s += fmt::format("  reg {} nv{};\n", range(nw), d + 1);
    s += "  always @(posedge clk) begin\n";
    s += fmt::format("    zc{0} <= zc{1};\n    tp{0} <= tp{1};\n    nv{0} <= n;\n", d + 1, d);
    s += fmt::format("    {} <= {} - ({} <<< {});\n  end\n", rtl_reg(sl, 0), ext("lz_v", pw, tw),
                     ext(e_prev, eb, tw), T.fl);
  }

  // ---- position d + 2: y = n log2 t, rounded half up.
  const Stage& sy = rtl_stage(layout, "mul_n");
  s += rtl_stage_registers(sy, fmt::format("y = n log2 t rounded half up to {} fraction bits "
                                           "(<= 0)",
                                           T.fy));
  {
    const int mw = nw + tw + 2;
    s += fmt::format("  wire signed {} mn_p = {} * {};\n", range(mw),
                     ext(fmt::format("nv{}", d + 1), nw, mw), ext(rtl_reg(sl, 0), tw, mw, true));
    s += fmt::format("  wire signed {} mn_y = {};\n", range(mw),
                     y_shift > 0 ? fmt::format("(mn_p + {}) >>> {}",
                                               slit(mw, std::int64_t{1} << (y_shift - 1)), y_shift)
                                 : std::string("mn_p"));
    if (mw > yw) s += fmt::format("  wire unused_mn = ^mn_y[{}:{}];\n", mw - 1, yw);
    s += carried(d + 2, false, 0);
    s += "  always @(posedge clk) begin\n";
    s += fmt::format("    zc{0} <= zc{1};\n    tp{0} <= tp{1};\n", d + 2, d + 1);
    s += fmt::format("    {} <= {};\n  end\n", rtl_reg(sy, 0), ext("mn_y", mw, yw));
  }

  // ---- position d + 3: y = yi + yf; yf's index and offset; ex2's c_d.
  const Stage& sx = rtl_stage(layout, "ex_lookup");
  s += rtl_stage_registers(sx,
                           "floor(y); y's fraction split into the segment index and the "
                           "offset x; acc = c_d");
  {
    const std::string y = rtl_reg(sy, 0);
    s += fmt::format("  wire signed {} xl_yi = {} >>> {};  // floor(y)\n", range(yw), y, T.fy);
    if (yw > yiw) s += fmt::format("  wire unused_xl = ^xl_yi[{}:{}];\n", yw - 1, yiw);
    const std::string kidx =
        T.se > 0 ? fmt::format("{}[{}:{}]", y, T.fy - 1, T.re) : std::string("1'b0");
    const std::string kx = T.re > 0 ? fmt::format("{}[{}:0]", y, T.re - 1) : std::string("1'b0");
    s += fmt::format("  wire {} xl_k = {};\n  wire {} xl_x = {};\n", range(eiw), kidx, range(exw),
                     kx);
    s += coeff_rom("xl_c", T.ex, T.stride, d, "xl_k", eiw, "ex2", bank);
    s += carried(d + 3, false, eiw);
    s += "  always @(posedge clk) begin\n";
    s +=
        fmt::format("    zc{0} <= zc{1};\n    tp{0} <= tp{1};\n    ix{0} <= xl_k;\n", d + 3, d + 2);
    s += fmt::format("    {} <= {};\n    {} <= xl_k;\n    {} <= xl_x;\n", rtl_reg(sx, 0),
                     ext("xl_yi", yw, yiw, true), rtl_reg(sx, 1), rtl_reg(sx, 2));
    s += fmt::format("    {} <= {};\n  end\n", rtl_reg(sx, 3),
                     ext("xl_c", bank.width, eaw, bank.is_signed));
    s += fmt::format("  wire unused_xk = ^{};  // the register shows the segment read\n",
                     rtl_reg(sx, 1));
  }

  // ---- positions d + 4 .. 2d + 2: ex2's multiply-adds.
  std::string yi_prev = rtl_reg(sx, 0);
  x_prev = rtl_reg(sx, 2);
  acc_prev = rtl_reg(sx, 3);
  for (int m = 1; m < d; ++m) {
    const Stage& st = rtl_stage(layout, fmt::format("ex_mac{}", m));
    const int j = d - m, pos = d + 3 + m;
    s += rtl_stage_registers(st, fmt::format("floor(y), x carried; acc = round(acc x) + c_{}", j));
    const std::string c_name = fmt::format("xm{}_c", m);
    s += coeff_rom(c_name, T.ex, T.stride, j, fmt::format("ix{}", pos - 1), eiw, "ex2", bank);
    const auto [pt, pw] = product(fmt::format("xm{}_p", m), acc_prev, eaw, x_prev, exw);
    s += pt;
    s += fmt::format("  wire signed {} xm{}_s = (xm{}_p + {}) >>> {};\n", range(pw), m, m,
                     slit(pw, T.ex_half), T.re);
    s += fmt::format("  wire unused_xm{0} = ^xm{0}_s[{1}:{2}];\n", m, pw - 1, eaw);
    s += carried(pos, false, eiw);
    s += "  always @(posedge clk) begin\n";
    s += fmt::format("    zc{0} <= zc{1};\n    tp{0} <= tp{1};\n    ix{0} <= ix{1};\n", pos,
                     pos - 1);
    s += fmt::format("    {} <= {};\n    {} <= {};\n", rtl_reg(st, 0), yi_prev, rtl_reg(st, 1),
                     x_prev);
    s += fmt::format("    {} <= {} + {};\n  end\n", rtl_reg(st, 2),
                     ext(fmt::format("xm{}_s", m), pw, eaw),
                     ext(c_name, bank.width, eaw, bank.is_signed));
    yi_prev = rtl_reg(st, 0);
    x_prev = rtl_reg(st, 1);
    acc_prev = rtl_reg(st, 2);
  }

  // ---- position 2d + 3: Ex = acc x + c_0 exact, shifted right by fe + re - fo - yi, rounded
  // half up, clamped; t = 0: 0, t = 1: 1.0.
  const Stage& sr = rtl_stage(layout, "ex_last");
  s += rtl_stage_registers(sr, "Ex exact, shifted by floor(-y), rounded half up, clamped to 1.0");
  s += coeff_rom("xz_c", T.ex, T.stride, 0, fmt::format("ix{}", 2 * d + 2), eiw, "ex2", bank);
  {
    const auto [pt, pw] = product("xz_p", acc_prev, eaw, x_prev, exw);
    s += pt;
    s += fmt::format("  wire signed {} xz_v = xz_p + ({} <<< {});  // > 0\n", range(pw),
                     ext("xz_c", bank.width, pw, bank.is_signed), T.re);
    const int shw = std::max(yiw, 8) + 2;
    s += fmt::format("  wire signed {} xz_shift = {} - {};\n", range(shw),
                     slit(shw, T.fe + T.re - T.fo), ext(yi_prev, yiw, shw, true));
    s += fmt::format("  wire [63:0] xz_w = {};\n", ext("xz_v", pw, 64));
    s += "  wire [5:0] xz_k = xz_shift[5:0];\n";
    s += "  wire [63:0] xz_r = (xz_w + ((64'd1 << xz_k) >> 1)) >> xz_k;  // round half up\n";
    s += fmt::format("  wire [63:0] xz_q = (xz_shift >= {}) ? 64'd0 : xz_r;\n", slit(shw, 62));
    const std::int64_t one = c.out.raw_one();
    s += "  always @(posedge clk)\n";
    s += fmt::format("    {} <= zc{} ? {} : tp{} ? {} : (xz_q > {}) ? {} : {};\n", rtl_reg(sr, 0),
                     2 * d + 2, lit(wo, 0), 2 * d + 2, lit(wo, one), lit(64, one), lit(wo, one),
                     ext("xz_q", 64, wo));
  }
  s += fmt::format("  assign result = {};\n", rtl_reg(sr, 0));
  s += hdl::datapath_footer(p);
  return s;
}

}  // namespace glint
