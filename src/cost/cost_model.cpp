#include "cost/cost_model.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace glint {

const CostConstants& cost_constants() {
  static const CostConstants k;
  return k;
}

namespace {

// Smallest b with 2^b >= x (0 for x <= 1).
int clog2(long long x) {
  int b = 0;
  while ((1LL << b) < x) ++b;
  return b;
}

}  // namespace

double adder_delay(int width) {
  return 2.0 * clog2(std::max(width, 1)) + 2.0;
}

int multiplier_tree_levels(int rows) {
  int levels = 0;
  for (int d = 2; d < rows; d = d * 3 / 2) ++levels;  // Dadda: 2, 3, 4, 6, 9, 13, 19, 28, ...
  return levels;
}

double multiplier_delay(int width_a, int width_b) {
  const CostConstants& k = cost_constants();
  return k.and_delay + k.fa_level_delay * multiplier_tree_levels(std::min(width_a, width_b)) +
         adder_delay(width_a + width_b);
}

double divider_row_delay(int divisor_bits) {
  return adder_delay(divisor_bits + 1) + cost_constants().mux_delay;
}

double table_delay(int entries) {
  return clog2(std::max(entries, 1)) + 2.0;
}

// ---- JSON
// ----------------------------------------------------------------------------------------

nlohmann::json Primitive::to_json() const {
  return {{"kind", kind},   {"width_a", width_a}, {"width_b", width_b},
          {"count", count}, {"ge", ge},           {"where", where}};
}

Primitive Primitive::from_json(const nlohmann::json& j) {
  Primitive p;
  p.kind = j.at("kind").get<std::string>();
  p.width_a = j.at("width_a").get<int>();
  p.width_b = j.at("width_b").get<int>();
  p.count = j.at("count").get<int>();
  p.ge = j.at("ge").get<double>();
  p.where = j.at("where").get<std::string>();
  return p;
}

nlohmann::json UnitCost::to_json() const {
  nlohmann::json inv = nlohmann::json::array();
  for (const Primitive& p : inventory) inv.push_back(p.to_json());
  nlohmann::json st = nlohmann::json::array();
  for (const StageDelay& s : stages)
    st.push_back({{"stage", s.stage}, {"delay", s.delay}, {"path", s.path}});
  return {{"area_ge", area_ge},
          {"critical_path", critical_path},
          {"critical_stage", critical_stage},
          {"stages", std::move(st)},
          {"ops_per_computed", ops_per_computed},
          {"ops_per_request", ops_per_request},
          {"inventory", std::move(inv)}};
}

UnitCost UnitCost::from_json(const nlohmann::json& j) {
  UnitCost c;
  for (const auto& p : j.at("inventory")) c.inventory.push_back(Primitive::from_json(p));
  c.area_ge = j.at("area_ge").get<double>();
  c.critical_path = j.at("critical_path").get<double>();
  c.critical_stage = j.at("critical_stage").get<std::string>();
  for (const auto& s : j.at("stages"))
    c.stages.push_back({s.at("stage").get<std::string>(), s.at("delay").get<double>(),
                        s.at("path").get<std::string>()});
  c.ops_per_computed = j.at("ops_per_computed").get<std::map<std::string, double>>();
  c.ops_per_request = j.at("ops_per_request").get<std::map<std::string, double>>();
  return c;
}

namespace {

// One element on a stage's path.
struct Seg {
  std::string label;
  double delay = 0;
};

// Two things side by side: the stage waits for the slower.
Seg parallel(const Seg& a, const Seg& b) {
  return {"(" + a.label + " || " + b.label + ")", std::max(a.delay, b.delay)};
}

// Things one after the other, as one segment.
Seg series(const std::vector<Seg>& segs) {
  Seg out;
  for (const Seg& g : segs) {
    out.label += (out.label.empty() ? "" : " + ") + g.label;
    out.delay += g.delay;
  }
  return out;
}

// Collects the inventory, the stage paths and the operation counts of one lane.
class Builder {
 public:
  Builder() : k_(cost_constants()) {}

  // ---- primitives: each returns its path segment ----
  Seg adder(int w, const std::string& where) {
    add({"adder", w, 0, 1, w * k_.fa_ge, where});
    return {fmt::format("add {}", w), adder_delay(w)};
  }
  Seg multiplier(int a, int b, const std::string& where, int count = 1) {
    add({"multiplier", a, b, count, count * a * b * (k_.fa_ge + k_.and2_ge), where});
    return {fmt::format("mul {}x{}", a, b), multiplier_delay(a, b)};
  }
  // rows: quotient rows built in hardware (all quotient bits pipelined, 1 iterative).
  Seg divider(int rows, int divisor, const std::string& where) {
    add({"divider", rows, divisor, 1, rows * (divisor + 1) * (k_.fa_ge + k_.mux2_ge), where});
    return {fmt::format("div row {}", divisor + 1), divider_row_delay(divisor)};
  }
  Seg comparator(int w, const std::string& where) {
    add({"comparator", w, 0, 1, w * k_.cmp_bit_ge, where});
    return {fmt::format("cmp {}", w), adder_delay(w)};
  }
  Seg mux(int w, int inputs, const std::string& where) {
    add({"mux", w, inputs, 1, w * (inputs - 1) * k_.mux2_ge, where});
    return {fmt::format("mux{} {}", inputs, w), k_.mux_delay * clog2(inputs)};
  }
  Seg shifter(int w, int levels, const std::string& where) {
    add({"shifter", w, levels, 1, w * levels * k_.mux2_ge, where});
    return {fmt::format("shift {}x{}", w, levels), k_.mux_delay * levels};
  }
  Seg lzd(int w, const std::string& where) {
    add({"lzd", w, 0, 1, w * k_.lzd_bit_ge, where});
    return {fmt::format("lzd {}", w), 2.0 * clog2(w)};
  }
  Seg rom(int entries, int w, const std::string& where) {
    add({"table", entries, w, 1, static_cast<double>(entries) * w * k_.rom_bit_ge, where});
    return {fmt::format("rom {}x{}", entries, w), table_delay(entries)};
  }
  // Per-slot storage, `banks` of `entries` words. shared_port: the banks are one table addressed
  // by (bank, entry); otherwise every bank has its own read-mux tree.
  Seg slot_table(int entries, int w, int banks, bool shared_port, const std::string& where) {
    auto one = [&](double e) { return w * (e * k_.latch_ge + (e - 1) * k_.mux2_ge); };
    const double ge =
        shared_port ? one(static_cast<double>(entries) * banks) : banks * one(entries);
    add({"table", entries, w, banks, ge, where});
    const int e = shared_port ? entries * banks : entries;
    return {fmt::format("table {}x{}", e, w), table_delay(e)};
  }
  // A pipeline register written by every computed request (or every request).
  void reg(int w, const std::string& where, bool per_request = false, int count = 1) {
    add({"register", w, 0, count, count * w * k_.dff_ge, where});
    (per_request ? request_ : computed_)["reg_bits"] += w;
  }
  // State registers written `writes` times per computed request (iterative divider).
  void state_reg(int w, const std::string& where, double writes) {
    add({"register", w, 0, 1, w * k_.dff_ge, where});
    computed_["reg_bits"] += w * writes;
  }

  void op(const std::string& kind, double n = 1) { computed_[kind] += n; }
  void request_op(const std::string& kind, double n = 1) { request_[kind] += n; }

  // Closes a stage: its path in series plus the register overhead.
  void stage(const std::string& name, const std::vector<Seg>& path) {
    StageDelay s{name, k_.reg_delay, ""};
    for (const Seg& g : path) {
      s.delay += g.delay;
      s.path += g.label + " + ";
    }
    s.path += "reg";
    stages_.push_back(std::move(s));
  }

  UnitCost finish() {
    UnitCost c;
    c.inventory = std::move(inv_);
    for (const Primitive& p : c.inventory) c.area_ge += p.ge;
    c.stages = std::move(stages_);
    for (const StageDelay& s : c.stages) {
      if (s.delay > c.critical_path) {
        c.critical_path = s.delay;
        c.critical_stage = s.stage;
      }
    }
    for (auto& [kind, n] : computed_)
      if (n != 0) c.ops_per_computed[kind] = n;
    for (auto& [kind, n] : request_)
      if (n != 0) c.ops_per_request[kind] = n;
    return c;
  }

 private:
  void add(Primitive p) {
    if (p.ge <= 0) return;  // zero-width parts (e.g. no interpolation bits) are not built
    inv_.push_back(std::move(p));
  }

  const CostConstants& k_;
  std::vector<Primitive> inv_;
  std::vector<StageDelay> stages_;
  std::map<std::string, double> computed_, request_;
};

// What every lane shares, read from describe().
struct Lane {
  const nlohmann::json& d;
  const nlohmann::json& cfg;
  QFormat in, out;
  bool skip;
  int slots, slot_bits, latency, buffer;

  explicit Lane(const nlohmann::json& desc)
      : d(desc),
        cfg(desc.at("config")),
        in(parse_q_format(cfg.at("in").get<std::string>())),
        out(parse_q_format(cfg.at("out").get<std::string>())),
        skip(cfg.at("skip").get<std::string>() == "on"),
        slots(static_cast<int>(desc.at("slots").size())),
        slot_bits(clog2(std::max(slots, 1))),
        latency(desc.at("timing").at("latency").get<int>()),
        buffer(desc.at("timing").at("buffer_depth").get<int>()) {}

  const nlohmann::json& slot_list() const { return d.at("slots"); }
  int max_slot_int(const char* key) const {
    int m = 0;
    for (const auto& s : slot_list()) m = std::max(m, s.at(key).get<int>());
    return m;
  }
  void expect_latency(int expected, const std::string& unit) const {
    if (latency != expected)
      throw std::logic_error(fmt::format(
          "cost model: {} has latency {} but its datapath model has {} stages (units.cpp timing "
          "and cost_model.cpp disagree)",
          unit, latency, expected));
  }
};

// Comparator stage: tau (or hast/horner's root) per slot, the compare, and the register that
// carries t, the skip flag, the slot id and (carry_root) the root to the u scaler.
void comparator_stage(Builder& b, const Lane& L, bool carry_root) {
  const int wi = L.in.width();
  std::vector<Seg> path;
  if (L.skip || carry_root) {
    path.push_back(b.slot_table(L.slots, wi, 1, true,
                                carry_root ? "tau/root table (per slot)" : "tau table (per slot)"));
    b.request_op("table_read");
  }
  if (L.skip) {
    path.push_back(b.comparator(wi, "tau comparator"));
    b.request_op("compare");
  }
  b.reg(wi + (L.skip ? 1 : 0) + L.slot_bits + (carry_root ? wi : 0), "comparator register", true);
  b.stage("comparator", path);
}

// u = (t - root) k clamped to [0, 1] at fh fraction bits (u_scaler.h): returns the stage path.
std::vector<Seg> u_scaler(Builder& b, const Lane& L, int k_width, int fh) {
  const int wi = L.in.width();
  const Seg k = b.slot_table(L.slots, k_width, 1, true, "u scaler: k table (per slot)");
  const Seg sub = b.adder(wi, "u scaler: t - tau");
  const Seg mul = b.multiplier(wi, k_width, "u scaler: (t - tau) k");
  const Seg clamp = b.mux(fh + 1, 2, "u scaler: clamp to 1");
  b.op("table_read");
  b.op("add");
  b.op("mul");
  return {parallel(k, sub), mul, clamp};
}

// ---- units
// ---------------------------------------------------------------------------------------

void schlick_cost(Builder& b, const Lane& L) {
  const QFormat nf = parse_q_format(L.cfg.at("n").get<std::string>());
  const bool iterative = L.cfg.at("divider").get<std::string>() == "iterative";
  const int wi = L.in.width(), fi = L.in.frac_bits, wo = L.out.width();
  const int wn = nf.width();
  // D = n (1 - t) + t < max(n, 1) in units of 2^-(Fn + Fi): D needs max(Wn, Fn + 1) + Fi bits.
  const int wd = std::max(wn, nf.frac_bits + 1) + fi;
  const int q = L.out.frac_bits + 2;  // integer bit, Fo fraction bits, the rounding bit
  L.expect_latency(q + 2, "schlick");
  comparator_stage(b, L, false);

  // Stage 1: D = n (1 - t) + t. 1 - t is the complement of t plus one: the +n correction is one
  // more row of the multiplier's tree.
  const Seg n = b.slot_table(L.slots, wn, 1, true, "stage 1: n table (per slot)");
  const Seg mul = b.multiplier(wn, fi + 1, "stage 1: n (1 - t)");
  const Seg add = b.adder(wd, "stage 1: + t");
  b.reg(wd + wi, "stage 1: D and t");
  b.op("table_read");
  b.op("mul");
  b.op("add");
  b.stage("stage 1", {n, mul, add});

  // Restoring division, q quotient bits; the last decides the rounding.
  b.op("div_step", q);
  const std::string span = fmt::format("stages 2-{}", q + 1);
  if (!iterative) {
    const Seg row = b.divider(q, wd, span + ": divider (pipelined, one row per stage)");
    for (int r = 1; r <= q; ++r) {
      // Partial remainder, divisor and the quotient bits so far; the last row passes only Q.
      const int carried = r < q ? (wd + 1) + wd + r : q;
      b.reg(carried, fmt::format("stage {}: divider row {}", r + 1, r));
      b.stage(fmt::format("stage {}", r + 1), {row});
    }
  } else {
    const Seg row = b.divider(1, wd, span + ": divider (iterative, one row reused)");
    const int counter = clog2(q + 1);
    const Seg load = b.mux(wd + 1, 2, span + ": divider load/iterate mux");
    b.state_reg(wd + 1, span + ": divider partial remainder", q);
    b.state_reg(wd, span + ": divider divisor", 1);
    b.state_reg(q, span + ": divider quotient shift register", q);
    b.state_reg(counter, span + ": divider step counter", q);
    b.stage(span + " (divider loop)", {row, load});
  }

  // Last stage: round (Q + 1) >> 1 and clamp to 1.0.
  const Seg rnd = b.adder(q, fmt::format("stage {}: rounding incrementer", q + 2));
  const Seg clamp = b.mux(wo, 2, fmt::format("stage {}: clamp to 1", q + 2));
  b.reg(wo, fmt::format("stage {}: result", q + 2));
  b.op("add");
  b.stage(fmt::format("stage {}", q + 2), {rnd, clamp});
}

void hast_cost(Builder& b, const Lane& L) {
  const int d = L.cfg.at("d").get<int>();
  const int fh = L.out.frac_bits + L.cfg.at("guard").get<int>();
  const int wo = L.out.width();
  int wk = 0;
  for (const auto& s : L.slot_list())
    wk = std::max(wk, s.at("k_int_bits").get<int>() + s.at("k_frac_bits").get<int>());
  L.expect_latency(d, "hast");
  comparator_stage(b, L, true);

  std::vector<Seg> path = u_scaler(b, L, wk, fh);
  if (d == 1) {
    path.push_back(b.adder(wo + 1, "stage 1: rounding incrementer"));
    b.op("add");
    b.reg(wo, "stage 1: result");
  } else {
    b.reg(fh + 1, "stage 1: u");
  }
  b.stage("stage 1", path);
  for (int s = 2; s <= d; ++s) {
    // u^(s-1) * u, rounded in the tree (to fh bits, the last one to the output format).
    const Seg mul = b.multiplier(fh + 1, fh + 1, fmt::format("stage {}: chain multiplier", s));
    b.op("mul");
    if (s < d)
      b.reg(2 * (fh + 1), fmt::format("stage {}: u and u^{}", s, s));
    else
      b.reg(wo, fmt::format("stage {}: result", s));
    b.stage(fmt::format("stage {}", s), {mul});
  }
}

void horner_cost(Builder& b, const Lane& L) {
  const int p = L.cfg.at("degree").get<int>();
  const int fh = L.out.frac_bits + L.cfg.at("guard").get<int>();
  const bool tau_domain = L.cfg.at("domain").get<std::string>() == "tau";
  const int wo = L.out.width();
  int cw = 0, wk = 0;
  for (const auto& s : L.slot_list()) {
    cw = std::max(cw, parse_q_format(s.at("coefficient_format").get<std::string>()).width());
    // describe() has k's value but not its widths: derived as UScaler does (k < 2^k_int,
    // fk = fh + 2).
    int k_int = 1;
    while (std::ldexp(1.0, k_int) <= s.at("k").get<double>()) ++k_int;
    wk = std::max(wk, k_int + fh + 2);
  }
  const int wacc = L.max_slot_int("acc_int_bits") + fh;  // signed accumulator
  L.expect_latency(p + 1, "horner");
  comparator_stage(b, L, tau_domain);

  // One coefficient bank per stage, every bank holding all slots.
  const Seg coef =
      b.slot_table(L.slots, cw, p + 1, false, "coefficient tables (per slot, one bank per stage)");
  b.op("table_read", p + 1);
  // Stage 1: the u scaler (tau domain; on the full domain u = t is wiring), c_p read beside it.
  const Seg first = tau_domain ? parallel(coef, series(u_scaler(b, L, wk, fh))) : coef;
  b.reg((fh + 1) + cw + L.slot_bits, "stage 1: u, c_p, slot id");
  b.stage("stage 1", {first});
  for (int s = 2; s <= p + 1; ++s) {
    const bool last = s == p + 1;
    const Seg mul = b.multiplier(wacc, fh + 1, fmt::format("stage {}: acc u", s));
    const Seg add = b.adder(wacc, fmt::format("stage {}: + c_{}", s, p + 1 - s));
    b.op("mul");
    b.op("add");
    std::vector<Seg> sp{parallel(mul, coef), add};
    if (last) {
      sp.push_back(b.mux(wo, 3, fmt::format("stage {}: clamp to [0, 1]", s)));
      b.reg(wo, fmt::format("stage {}: result", s));
    } else {
      b.reg((fh + 1) + wacc + L.slot_bits, fmt::format("stage {}: u, acc, slot id", s));
    }
    b.stage(fmt::format("stage {}", s), sp);
  }
}

void pow_cost(Builder& b, const Lane& L) {
  const QFormat nf = parse_q_format(L.cfg.at("n").get<std::string>());
  const int lb = L.cfg.at("log_bits").get<int>(), lf = L.cfg.at("log_frac").get<int>();
  const int yf = L.cfg.at("y_frac").get<int>();
  const int eb = L.cfg.at("exp_bits").get<int>(), xf = L.cfg.at("exp_frac").get<int>();
  const int wi = L.in.width(), fi = L.in.frac_bits, wo = L.out.width(), wn = nf.width();
  const int ebits = clog2(fi + 1);                   // exponent of t / normalisation shift
  const int lw = lf + 1;                             // log2(1 + x) in [0, 1]: 1.0 at the last node
  const int log_r = std::max(0, fi - lb);            // interpolation bits of the mantissa
  const int log2t_w = lf + ebits + 1;                // signed log2 t
  const int yint = (wn - nf.frac_bits) + ebits + 1;  // |y| <= n_max fi, signed
  const int xw = xf + 2;                             // 2^x in [1, 2]: 2.0 at the last node
  const int exp_r = std::max(0, yf - eb);
  L.expect_latency(5, "pow");
  comparator_stage(b, L, false);

  // Stage 1: normalise t, read log2 at the segment's two ends.
  const Seg z = b.lzd(wi, "stage 1: leading-one detector");
  const Seg sh = b.shifter(wi, ebits, "stage 1: normalisation shifter");
  const Seg lt = b.rom((1 << lb) + 1, lw, "stage 1: log2 table (ROM)");
  b.op("lzd");
  b.op("shift");
  b.op("table_read", 2);
  b.reg(2 * lw + log_r + ebits + L.slot_bits, "stage 1: log2 nodes, remainder, exponent, slot");
  b.stage("stage 1", {z, sh, lt});

  // Stage 2: log2 interpolation; the n register read beside it.
  std::vector<Seg> p2;
  if (log_r > 0) {
    p2.push_back(b.adder(lw + 1, "stage 2: log2 node difference"));
    p2.push_back(b.multiplier(lw + 1, log_r, "stage 2: log2 interpolation"));
    b.op("add");
    b.op("mul");
  }
  p2.push_back(b.adder(lw, "stage 2: + log2 node"));
  b.op("add");
  const Seg n = b.slot_table(L.slots, wn, 1, true, "stage 2: n table (per slot)");
  b.op("table_read");
  p2.front() = parallel(p2.front(), n);
  b.reg(log2t_w + wn, "stage 2: log2 t, n");
  b.stage("stage 2", p2);

  // Stage 3: y = n log2 t, rounded to y_frac in the tree.
  const Seg my = b.multiplier(wn, log2t_w, "stage 3: n log2 t");
  b.op("mul");
  b.reg(yint + yf, "stage 3: y");
  b.stage("stage 3", {my});

  // Stage 4: exp2 nodes of the fraction of y.
  const Seg et = b.rom((1 << eb) + 1, xw, "stage 4: exp2 table (ROM)");
  b.op("table_read", 2);
  b.reg(2 * xw + exp_r + yint, "stage 4: exp2 nodes, remainder, integer part of y");
  b.stage("stage 4", {et});

  // Stage 5: exp2 interpolation, shift by the integer part, round, clamp.
  std::vector<Seg> p5;
  if (exp_r > 0) {
    p5.push_back(b.adder(xw + 1, "stage 5: exp2 node difference"));
    p5.push_back(b.multiplier(xw + 1, exp_r, "stage 5: exp2 interpolation"));
    b.op("add");
    b.op("mul");
  }
  p5.push_back(b.adder(xw, "stage 5: + exp2 node"));
  p5.push_back(b.shifter(xw, clog2(xw + 1), "stage 5: output shifter"));
  p5.push_back(b.adder(wo + 1, "stage 5: rounding incrementer"));
  p5.push_back(b.mux(wo, 2, "stage 5: clamp to 1"));
  b.op("add", 2);
  b.op("shift");
  b.reg(wo, "stage 5: result");
  b.stage("stage 5", p5);
}

void lut_cost(Builder& b, const Lane& L) {
  const int bits = L.cfg.at("bits").get<int>(), tf = L.cfg.at("table_frac").get<int>();
  const int wi = L.in.width(), fi = L.in.frac_bits, wo = L.out.width();
  const int entries = (1 << bits) + 1;
  const int tw = tf + 1;  // t^n in [0, 1]: 1.0 at the last node
  const int sbits = clog2(fi + 1);
  int r_max = 0;  // interpolation bits: fi - span - bits, widest over slots
  for (const auto& s : L.slot_list())
    r_max = std::max(r_max, fi - s.at("span_log2").get<int>() - bits);
  L.expect_latency(2, "lut");
  comparator_stage(b, L, false);

  // Stage 1: t - t0 (t0 = 1 - 2^-span), the index field at the slot's span, the two nodes.
  const Seg sp = b.slot_table(L.slots, sbits, 1, true, "stage 1: span table (per slot)");
  const Seg sub = b.adder(wi, "stage 1: t - t0");
  const Seg sh = b.shifter(wi, sbits, "stage 1: index shifter");
  const Seg tab = b.slot_table(entries, tw, L.slots, true, "stage 1: t^n table (per slot)");
  b.op("table_read", 3);
  b.op("add");
  b.op("shift");
  b.reg(2 * tw + r_max, "stage 1: nodes, remainder");
  b.stage("stage 1", {sp, sub, sh, tab});

  // Stage 2: interpolation (rounding folded into the adder), clamp.
  std::vector<Seg> p2;
  if (r_max > 0) {
    p2.push_back(b.adder(tw + 1, "stage 2: node difference"));
    p2.push_back(b.multiplier(tw + 1, r_max, "stage 2: interpolation"));
    p2.push_back(b.adder(tw + r_max, "stage 2: + node"));
    b.op("add", 2);
    b.op("mul");
  } else {
    p2.push_back(b.adder(wo + 1, "stage 2: rounding incrementer"));
    b.op("add");
  }
  p2.push_back(b.mux(wo, 2, "stage 2: clamp to 1"));
  b.reg(wo, "stage 2: result");
  b.stage("stage 2", p2);
}

// The in-order merge buffer (its entries carry the slot id when the colour stage follows).
void merge_buffer(Builder& b, const Lane& L, bool colour) {
  const int w = L.out.width() + (colour ? L.slot_bits : 0);
  b.reg(w, "merge buffer", true, L.buffer);
  if (L.buffer > 1) b.mux(w, L.buffer, "merge buffer read mux");
}

void colour_stage(Builder& b, const Lane& L) {
  const int wo = L.out.width();
  const Seg tab = b.slot_table(L.slots, 3 * wo, 1, true, "colour: RGB table (per slot)");
  const Seg mul = b.multiplier(wo, wo, "colour: highlight x R, G, B", 3);
  b.op("table_read");
  b.op("mul", 3);
  b.reg(3 * wo, "colour: RGB result", true);
  b.stage("colour", {tab, mul});
}

}  // namespace

UnitCost unit_cost(const SpecularUnit& unit, bool colour_multiply) {
  const nlohmann::json d = unit.describe();
  const Lane lane(d);
  Builder b;
  const std::string& name = unit.name();
  if (name == "schlick") {
    schlick_cost(b, lane);
  } else if (name == "hast") {
    hast_cost(b, lane);
  } else if (name == "horner") {
    horner_cost(b, lane);
  } else if (name == "pow") {
    pow_cost(b, lane);
  } else if (name == "lut") {
    lut_cost(b, lane);
  } else {
    throw std::invalid_argument(fmt::format("cost model: unknown unit '{}'", name));
  }
  merge_buffer(b, lane, colour_multiply);
  if (colour_multiply) colour_stage(b, lane);
  return b.finish();
}

}  // namespace glint
