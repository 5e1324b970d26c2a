// Hardware of domain=log (L = 2d + 3, II 1): stage 1 the leading-one detector, the normalisation
// shifter that leaves the mantissa's index and offset, lg2's c_d; d - 1 multiply-adds (lg2's
// banks read beside each multiplier); the last lg2 stage forms acc x + c_0 exactly, rounds to fl
// bits and places -E above it (log2 t); the n multiplier, with the n table (per datapath group:
// the only per-material state) read in the stage before; the ex2 lookup (y's integer part split
// off, c_d); d - 1 multiply-adds; the last stage forms Ex exactly, shifts it right by -yi with
// the rounding half, clamps and muxes in 0 (t = 0) and 1.0 (t = 1). The lg2 and ex2 banks are
// ROMs of fixed contents for every material, also with tables=ram: only n is loadable.
#include "units/pwp/log_kind.h"

#include <fmt/format.h>

#include <algorithm>
#include <functional>
#include <string>

#include "cost/builder.h"
#include "hdl/verilog.h"

namespace glint {

PwpBank pwp_log_bank(const std::vector<std::int64_t>& table, std::size_t stride, int j) {
  PwpBank b;
  std::int64_t hi = 0;
  for (std::size_t k = static_cast<std::size_t>(j); k < table.size(); k += stride) {
    const std::int64_t c = table[k];
    b.is_signed = b.is_signed || c < 0;
    hi = std::max(hi, c < 0 ? -c : c);
    b.words.push_back(c);
  }
  b.width = hdl::value_bits(static_cast<std::uint64_t>(hi)) + (b.is_signed ? 1 : 0);
  return b;
}

PwpLogFormats pwp_log_formats(const PwpConfig& c, const PwpLogTables& t) {
  // |y| <= n_max fi: the n register's integer bits, the exponent's, and the sign.
  const int yint = c.n_format.int_bits + t.ebits + 1;
  return {uq(t.ebits, 0),
          uq(std::max(1, t.sl), 0),
          uq(std::max(1, t.rl), 0),
          sq(t.lg_acc_int, t.fl),
          sq(t.ebits + 1, t.fl),
          sq(yint, t.fy),
          sq(yint, 0),
          uq(std::max(1, t.se), 0),
          uq(std::max(1, t.re), 0),
          sq(t.ex_acc_int, t.fe)};
}

std::vector<Stage> pwp_log_stages(const PwpConfig& c, const std::vector<PwpUnit>& units) {
  const PwpLogTables& t = units.front().log_path()->tables();
  const PwpLogFormats f = pwp_log_formats(c, t);
  const int d = c.degree;
  std::vector<Stage> s{input_stage(),
                       {"lg_lookup",
                        1,
                        1,
                        {{"e", f.big_e}, {"index", f.lg_index}, {"x", f.lg_x}, {"acc", f.lg_acc}}}};
  for (int j = 1; j < d; ++j)
    s.push_back({"lg_mac" + std::to_string(j),
                 j + 1,
                 j + 1,
                 {{"e", f.big_e}, {"x", f.lg_x}, {"acc", f.lg_acc}}});
  s.push_back({"lg_last", d + 1, d + 1, {{"log2_t", f.log2t}}});
  s.push_back({"mul_n", d + 2, d + 2, {{"y", f.y}}});
  s.push_back({"ex_lookup",
               d + 3,
               d + 3,
               {{"y_int", f.y_int}, {"index", f.ex_index}, {"x", f.ex_x}, {"acc", f.ex_acc}}});
  for (int j = 1; j < d; ++j)
    s.push_back({"ex_mac" + std::to_string(j),
                 d + 3 + j,
                 d + 3 + j,
                 {{"y_int", f.y_int}, {"x", f.ex_x}, {"acc", f.ex_acc}}});
  s.push_back({"ex_last", 2 * d + 3, 2 * d + 3, {{"result", c.out}}});
  return s;
}

namespace {

// A bank of fixed contents as a ROM: its words as the stored bits.
Seg bank_rom(CostBuilder& b, const PwpBank& k, const std::string& where) {
  std::vector<std::int64_t> bits;
  const std::int64_t mask = (std::int64_t{1} << k.width) - 1;
  for (std::int64_t w : k.words) bits.push_back(w & mask);
  b.op("table_read");
  return b.rom(bits, k.width, where);
}

// One Horner evaluator's multiply-add stages after its lookup: d - 1 rounded to `frac` bits, the
// last exact (`last_width` wide). Returns the register widths of each stage's acc.
void horner_stages(CostBuilder& b, const std::string& fn, const std::vector<std::int64_t>& table,
                   std::size_t stride, int d, int acc_w, int xw, int first_stage, int carried_bits,
                   const std::function<std::vector<Seg>()>& last_extra, int last_reg,
                   const std::string& last_reg_what) {
  for (int m = 1; m <= d; ++m) {
    const int j = d - m, s = first_stage + m - 1;
    const bool last = m == d;
    const PwpBank cj = pwp_log_bank(table, stride, j);
    std::vector<Seg> p;
    const Seg rom =
        bank_rom(b, cj, fmt::format("stage {}: {} c_{} (ROM, every material)", s, fn, j));
    if (xw > 0) {
      // The first product reads the register loaded with c_d: its bank's width, not the acc's.
      const int aw = m == 1 ? pwp_log_bank(table, stride, d).width : acc_w;
      const Seg mul = b.multiplier(aw, xw, fmt::format("stage {}: {} acc x", s, fn), 1, true);
      b.op("mul");
      p.push_back(parallel(mul, rom));
    } else {
      p.push_back(rom);
    }
    p.push_back(b.adder(acc_w + (last ? xw : 0), fmt::format("stage {}: {} + c_{}", s, fn, j)));
    b.op("add");
    if (last) {
      const std::vector<Seg> extra = last_extra();  // placed in this stage
      p.insert(p.end(), extra.begin(), extra.end());
      b.reg(last_reg, fmt::format("stage {}: {}", s, last_reg_what));
    } else {
      b.reg(std::max(1, xw) + acc_w + carried_bits,
            fmt::format("stage {}: {} x, acc, carried", s, fn));
    }
    b.stage(fmt::format("stage {}", s), p);
  }
}

}  // namespace

void pwp_log_cost(CostBuilder& b, const LaneShape& L, const PwpConfig& c,
                  const std::vector<PwpUnit>& units) {
  const PwpLogTables& t = units.front().log_path()->tables();
  const PwpLogFormats f = pwp_log_formats(c, t);
  const int d = c.degree, wi = L.in.width(), wo = L.out.width();
  const int flags = 2 + L.group_bits;  // t = 0, t = 1, the group (its n read two stages on)

  // Stage 1: leading-one detector, normalisation, lg2's index and c_d.
  const Seg z = b.lzd(wi, "stage 1: leading-one detector");
  const Seg sh = b.shifter(wi, t.ebits, "stage 1: normalisation shifter");
  const PwpBank lgd = pwp_log_bank(t.lg, t.stride, d);
  const Seg cd = bank_rom(b, lgd, fmt::format("stage 1: lg2 c_{} (ROM, every material)", d));
  b.comparator(wi, "stage 1: t = 1");
  b.op("lzd");
  b.op("shift");
  b.reg(f.big_e.width() + f.lg_index.width() + f.lg_x.width() + lgd.width + flags,
        "stage 1: E, index, x, c_d, flags, group");
  b.stage("stage 1", {z, sh, cd});

  // lg2's multiply-adds; the last rounds to fl bits and places -E above (log2 t).
  const int lg_acc = f.lg_acc.width();
  const int wn_ram = L.tables_ram ? c.n_format.width() : [&] {
    // As a ROM the n table's constants fold to the bits the scene's values use.
    std::int64_t any = 0;
    for (const PwpUnit& u : units) any |= u.log_path()->n_raw();
    return std::max(1, hdl::value_bits(static_cast<std::uint64_t>(any)));
  }();
  const auto n_table = [&]() -> std::vector<Seg> {
    b.op("table_read");
    return {b.slot_table(L.groups, wn_ram, 1, true,
                         fmt::format("stage {}: n table (per datapath group)", d + 1))};
  };
  horner_stages(b, "lg2", t.lg, t.stride, d, lg_acc, t.rl, 2, f.big_e.width() + flags, n_table,
                f.log2t.width() + wn_ram + flags, "log2 t, n, flags");

  // y = n log2 t, rounded to fy bits in the tree.
  std::vector<std::int64_t> ns;
  for (const PwpUnit& u : units) ns.push_back(u.log_path()->n_raw());
  const bool known = !L.tables_ram && L.groups == static_cast<int>(units.size());
  const int sy = d + 2;
  const Seg my =
      known ? b.table_multiplier(f.log2t.width(), ns, fmt::format("stage {}: n log2 t", sy), true)
            : b.multiplier(wn_ram, f.log2t.width(), fmt::format("stage {}: n log2 t", sy), 1, true);
  b.op("mul");
  b.reg(f.y.width() + 2, fmt::format("stage {}: y, flags", sy));
  b.stage(fmt::format("stage {}", sy), {my});

  // ex2's lookup: yi and yf split (wiring), c_d.
  const int se = d + 3;
  const PwpBank exd = pwp_log_bank(t.ex, t.stride, d);
  const Seg ed = bank_rom(b, exd, fmt::format("stage {}: ex2 c_{} (ROM, every material)", se, d));
  b.reg(f.y_int.width() + f.ex_index.width() + f.ex_x.width() + exd.width + 2,
        fmt::format("stage {}: y_int, index, x, c_d, flags", se));
  b.stage(fmt::format("stage {}", se), {ed});

  // ex2's multiply-adds; the last shifts by -yi, rounds, clamps.
  const int ex_acc = f.ex_acc.width();
  const int vw = ex_acc + t.re;      // Ex exact: acc x + c_0
  const int levels = clog2(vw + 2);  // a larger shift leaves 0 (the range check)
  const int sl = 2 * d + 3;
  const auto tail = [&]() -> std::vector<Seg> {
    b.adder(f.y_int.width(), fmt::format("stage {}: shift amount", sl));
    b.comparator(f.y_int.width(), fmt::format("stage {}: shift range check", sl));
    b.op("shift");
    b.op("add");
    return {b.shifter(vw, levels, fmt::format("stage {}: shift by -yi", sl)),
            b.adder(wo + 1, fmt::format("stage {}: rounding incrementer", sl)),
            b.mux(wo, 4, fmt::format("stage {}: clamp to 1, t = 0, t = 1", sl))};
  };
  horner_stages(b, "ex2", t.ex, t.stride, d, ex_acc, t.re, d + 4, f.y_int.width() + 2, tail, wo,
                "result");
}

nlohmann::json pwp_log_describe(const PwpUnit& u) {
  const PwpLogPath& p = *u.log_path();
  const PwpLogTables& t = p.tables();
  return {{"domain", "log"},
          {"n", p.shininess_q()},
          {"lg2_segments", t.lg_segments()},
          {"ex2_segments", t.ex_segments()},
          {"lg2_offset_bits", t.rl},
          {"ex2_offset_bits", t.re},
          {"log_frac", t.fl},
          {"y_frac", t.fy},
          {"exp_frac", t.fe},
          {"monotone_extra_bits", t.extra},
          {"chord_segments", t.lg_chords + t.ex_chords},
          {"datapath_bound_ulps", p.datapath_bound_ulps()},
          {"per_slot",
           "n only: the lg2 and ex2 tables are ROMs shared by every material, also "
           "with tables=ram (only the n register is loadable)"}};
}

}  // namespace glint
