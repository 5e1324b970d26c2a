// Each clocked module alone, driven cycle by cycle by a testbench process: the source's handshake,
// the compute unit's latency and initiation interval, the comparator's bypass, credits and II
// gating, the merge buffer's ordering, flow-through and backpressure, the sink's ready pattern.
// One SystemC elaboration per TEST (each test case runs in its own process under ctest).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <systemc>
#include <vector>

#include "eval/evaluate.h"
#include "rtl_model/compute_pipeline.h"
#include "rtl_model/result_merge.h"
#include "rtl_model/row_stream.h"
#include "rtl_model/rtl_common.h"
#include "rtl_model/scoreboard.h"
#include "rtl_model/sim_control.h"
#include "rtl_model/tau_comparator.h"
#include "rtl_model/vector_source.h"
#include "units/catalogue.h"
#include "units/common.h"

namespace glint::rtl {
namespace {

// The clock's process of a test: at every rising edge c, calls `on_edge(c)`, which reads what the
// modules present at c and writes the inputs they will see at c + 1, and ticks the modules under
// test (ClockedStage), as the lane's clock does.
class Driver : public sc_core::sc_module {
 public:
  sc_core::sc_in<bool> clk;
  SC_HAS_PROCESS(Driver);
  Driver(sc_core::sc_module_name name, std::function<void(std::uint64_t)> on_edge)
      : sc_core::sc_module(name), clk("clk"), on_edge_(std::move(on_edge)) {
    SC_METHOD(tick);
    sensitive << clk.pos();
    dont_initialize();
  }

  void ticks(ClockedStage& stage) { stages_.push_back(&stage); }

 private:
  void tick() {
    on_edge_(cycle_++);
    for (ClockedStage* s : stages_) s->tick();
  }
  std::function<void(std::uint64_t)> on_edge_;
  std::vector<ClockedStage*> stages_;
  std::uint64_t cycle_ = 0;
};

// Runs edges 0 .. cycles - 1.
void run_cycles(std::uint64_t cycles) {
  sc_core::sc_start(clock_first_edge() + clock_period() * static_cast<double>(cycles - 1) +
                    clock_period() / 2);
}

VectorHeader two_materials() {
  VectorHeader h;
  h.eps = 1e-3;
  h.lights = 1;
  VectorMaterial m;
  m.name = "gold";
  m.specular = {1, 0.766, 0.336};
  m.shininess = 64;
  m.lobe = Lobe::kBlinn;
  h.materials.push_back(m);
  m.name = "plastic";
  m.specular = {0.5, 0.5, 0.5};
  m.shininess = 8;
  h.materials.push_back(m);
  return h;
}

std::vector<VectorRow> rows_of(const std::vector<double>& ts) {
  std::vector<VectorRow> rows;
  for (std::size_t i = 0; i < ts.size(); ++i) {
    VectorRow r;
    r.t = ts[i];
    r.material = static_cast<std::uint32_t>(i % 2);
    r.line = i + 1;
    rows.push_back(r);
  }
  return rows;
}

TEST(RtlModules, VectorSourceAdvancesOnlyOnHandshake) {
  const SlotMap slots = make_slots(two_materials());
  const auto unit = make_unit(parse_unit_spec("hast"), slots);
  const std::vector<VectorRow> rows = rows_of({0.5, -0.3, 0.99, 1.0005, 0.75});
  MemoryRowStream stream(rows);
  RowRing ring(8);
  SimControl control;
  sc_core::sc_clock clk("clk", clock_period(), 0.5, clock_first_edge(), true);
  sc_core::sc_signal<bool> ready("ready", false);
  VectorSource source("source", stream, *unit, slots, ring, control, false);
  // Ready pattern for edges 0..: handshakes where ready && valid.
  const std::vector<bool> pattern = {false, true,  false, false, true,
                                     true,  false, true,  true,  true};
  ready.write(pattern[0]);
  struct Seen {
    bool valid, ready;
    Request request;
  };
  std::vector<Seen> seen;
  Driver driver("driver", [&](std::uint64_t c) {
    seen.push_back({source.valid.read(), ready.read(), source.request.read()});
    ready.write(c + 1 < pattern.size() ? pattern[c + 1] : true);
  });
  driver.ticks(source);
  driver.clk(clk);
  source.ready(ready);
  run_cycles(14);

  ASSERT_EQ(seen.size(), 14u);
  std::uint64_t expect_seq = 0;
  for (std::size_t c = 0; c < seen.size(); ++c) {
    SCOPED_TRACE("edge " + std::to_string(c));
    if (expect_seq < rows.size()) {
      ASSERT_TRUE(seen[c].valid);
      const Request& r = seen[c].request;
      EXPECT_EQ(r.seq, expect_seq);
      EXPECT_EQ(r.t_raw, quantize_input(rows[expect_seq].t, unit->in_format()));
      EXPECT_EQ(r.slot, slots.slot(rows[expect_seq]));
      EXPECT_EQ(r.last, expect_seq + 1 == rows.size());
      EXPECT_EQ(ring.at(expect_seq).line, rows[expect_seq].line);
      if (seen[c].ready) ++expect_seq;
    } else {
      EXPECT_FALSE(seen[c].valid);
    }
  }
  EXPECT_EQ(expect_seq, rows.size());
  EXPECT_EQ(source.presented(), rows.size());
}

// Latency: a request started at edge a is in the output register from edge a + L, visible to the
// merge at a + L + 1. II: the registered ready is low at edges a + 1 .. a + II - 1.
void check_pipeline(const std::string& spec, const std::vector<std::uint64_t>& starts,
                    std::uint64_t cycles) {
  const SlotMap slots = make_slots(two_materials());
  const auto unit = make_unit(parse_unit_spec(spec), slots);
  const int L = unit->timing().latency, II = unit->timing().ii;
  sc_core::sc_clock clk("clk", clock_period(), 0.5, clock_first_edge(), true);
  sc_core::sc_signal<bool> in_valid("in_valid", false);
  sc_core::sc_signal<Request> in_request("in_request");
  auto pipe = std::make_unique<ComputePipeline>("pipe", *unit, true);
  auto request_for = [&](std::uint64_t a) {
    Request r;
    r.seq = a;
    r.t_raw = 20000 + static_cast<std::int64_t>(a * 997 % 40000);
    r.slot = static_cast<std::uint32_t>(a % 2);
    return r;
  };
  auto starts_at = [&](std::uint64_t c) {
    return std::find(starts.begin(), starts.end(), c) != starts.end();
  };
  if (starts_at(0)) {
    in_valid.write(true);
    in_request.write(request_for(0));
  }
  std::vector<bool> ready_seen;
  std::vector<Result> out_seen;
  Driver driver("driver", [&](std::uint64_t c) {
    ready_seen.push_back(pipe->ready.read());
    out_seen.push_back(pipe->out.read());
    in_valid.write(starts_at(c + 1));
    if (starts_at(c + 1)) in_request.write(request_for(c + 1));
  });
  driver.ticks(*pipe);
  driver.clk(clk);
  pipe->in_valid(in_valid);
  pipe->in_request(in_request);
  run_cycles(cycles);

  EXPECT_EQ(pipe->violations(), 0u);
  EXPECT_EQ(pipe->started(), starts.size());
  for (std::uint64_t c = 0; c < cycles; ++c) {
    SCOPED_TRACE(spec + " edge " + std::to_string(c));
    bool busy = false;
    for (std::uint64_t a : starts) busy = busy || (a < c && c < a + static_cast<std::uint64_t>(II));
    EXPECT_EQ(ready_seen[c], !busy);
    const bool expect_out =
        c >= static_cast<std::uint64_t>(L) + 1 && starts_at(c - static_cast<std::uint64_t>(L) - 1);
    ASSERT_EQ(out_seen[c].valid, expect_out);
    if (expect_out) {
      const std::uint64_t a = c - static_cast<std::uint64_t>(L) - 1;
      const Request r = request_for(a);
      EXPECT_EQ(out_seen[c].seq, a);
      EXPECT_EQ(out_seen[c].issue, a);
      EXPECT_FALSE(out_seen[c].skipped);
      EXPECT_EQ(out_seen[c].value, unit->eval(r.slot, r.t_raw));
    }
  }
}

TEST(RtlModules, HastChainLatencyAndFullThroughput) {
  check_pipeline("hast:d=5", {0, 1, 2, 3, 7, 9, 10}, 24);
}

TEST(RtlModules, IterativeDividerInitiationInterval) {
  // schlick, out uq1.15: q = 17 quotient bits, latency 19, II 17.
  check_pipeline("schlick:divider=iterative", {1, 18, 35, 60}, 90);
}

TEST(RtlModules, StageLayoutsNameEveryRegister) {
  const SlotMap slots = make_slots(two_materials());
  sc_core::sc_clock clk("clk", clock_period(), 0.5, clock_first_edge(), true);
  struct Case {
    const char* spec;
    std::vector<std::string> names;
  };
  const std::vector<Case> cases = {
      {"hast:d=3", {"in", "scale", "mul1", "mul2"}},
      {"horner:degree=3", {"in", "scale", "mac1", "mac2", "mac3"}},
      {"pow", {"in", "log_table", "log_interp", "mul_n", "exp_table", "exp_interp"}},
      {"lut", {"in", "lookup", "interp"}},
      {"schlick:out=uq1.3,divider=iterative", {"in", "mac", "div", "round"}},
      {"schlick:out=uq1.3,divider=pipelined", {"in", "mac", "q0", "q1", "q2", "q3", "q4", "round"}},
  };
  std::vector<std::unique_ptr<SpecularUnit>> units;
  std::vector<std::unique_ptr<ComputePipeline>> pipes;
  int k = 0;
  for (const Case& c : cases) {
    units.push_back(make_unit(parse_unit_spec(c.spec), slots));
    pipes.push_back(std::make_unique<ComputePipeline>(("p" + std::to_string(k++)).c_str(),
                                                      *units.back(), false));
    std::vector<std::string> names;
    for (const Stage& s : pipes.back()->layout().stages()) names.push_back(s.name);
    EXPECT_EQ(names, c.names) << c.spec;
    EXPECT_EQ(pipes.back()->layout().latency(), pipes.back()->latency());
  }
  // The divider kind must agree with the unit's II: an iterative divider stage (one request for q
  // cycles) in a unit whose II is 1 is refused.
  const auto pipelined = make_unit(parse_unit_spec("schlick"), slots);
  std::vector<Stage> iterative = {{"in", 0, 0, {}},
                                  {"mac", 1, 1, {}},
                                  {"div", 2, 18, {}},
                                  {"round", 19, 19, {{"result", pipelined->out_format()}}}};
  EXPECT_THROW(StageLayout(iterative, pipelined->timing().ii, pipelined->out_format()),
               std::invalid_argument);
  EXPECT_NO_THROW(StageLayout(iterative, 17, pipelined->out_format()));
}

// Comparator: skips go to the bypass register (done at a + 1), computed requests to the unit when
// it is ready, a credit per issue, a returned credit usable at the next edge.
TEST(RtlModules, TauComparatorBypassCreditsAndIIGate) {
  const SlotMap slots = make_slots(two_materials());
  const auto unit = make_unit(parse_unit_spec("hast:buffer=2"), slots);
  const std::int64_t tau0 = unit->tau_raw(0);
  ASSERT_GT(tau0, 100);
  sc_core::sc_clock clk("clk", clock_period(), 0.5, clock_first_edge(), true);
  sc_core::sc_signal<bool> src_valid("src_valid", true), unit_ready("unit_ready", true),
      credit_return("credit_return", false);
  sc_core::sc_signal<Request> src_request("src_request");
  TauComparator cmp("cmp", *unit, 2, false);
  EXPECT_EQ(cmp.tau_table()[0], tau0);
  EXPECT_EQ(cmp.tau_table()[1], unit->tau_raw(1));

  // Requests, all slot 0: skip, compute, skip, compute, compute.
  const std::vector<std::int64_t> ts = {tau0, tau0 + 1, 0, 40000, 32768};
  auto request = [&](std::uint64_t i) {
    Request r;
    r.seq = i;
    r.t_raw = ts[i];
    r.slot = 0;
    r.last = i + 1 == ts.size();
    return r;
  };
  src_request.write(request(0));
  // Testbench: credit returns at edges 4 and 9 (visible at 5 and 10); unit not ready at edges
  // 10..12.
  std::uint64_t next = 0;
  std::vector<std::uint64_t> issue_cycle(ts.size(), 0);
  std::vector<Result> bypass_seen;
  std::vector<bool> compute_seen;
  Driver driver("driver", [&](std::uint64_t c) {
    bypass_seen.push_back(cmp.bypass.read());
    compute_seen.push_back(cmp.compute_valid.read());
    if (next < ts.size() && src_valid.read() && cmp.src_ready.read()) {
      issue_cycle[next] = c;
      ++next;
      if (next < ts.size()) {
        src_request.write(request(next));
      } else {
        src_valid.write(false);
      }
    }
    credit_return.write(c == 4 || c == 9);
    unit_ready.write(!(c + 1 >= 10 && c + 1 <= 12));
  });
  driver.ticks(cmp);
  driver.clk(clk);
  cmp.src_valid(src_valid);
  cmp.src_request(src_request);
  cmp.unit_ready(unit_ready);
  cmp.credit_return(credit_return);
  run_cycles(20);

  ASSERT_EQ(next, 4u);  // request 4 never gets a credit
  // 0 (skip) at 0, 1 (compute) at 1; no credit until the return at edge 4 is usable at 5;
  // 2 (skip) at 5; the return at 9 is usable at 10 but the unit is busy at 10..12: 3 at 13.
  // No credit left for 4 until ... never returned: check it waits.
  EXPECT_EQ(issue_cycle[0], 0u);
  EXPECT_EQ(issue_cycle[1], 1u);
  EXPECT_EQ(issue_cycle[2], 5u);
  EXPECT_EQ(issue_cycle[3], 13u);
  EXPECT_EQ(cmp.issued(), 4u);
  EXPECT_EQ(cmp.stall_credit(), 3u);  // request 2: edges 2, 3, 4
  EXPECT_EQ(cmp.stall_unit(), 7u);    // request 3: edges 6..9 credit, 10..12 unit -> unit binds
  // Bypass register: valid at a + 1 for the skipped requests only.
  for (std::uint64_t c = 0; c < bypass_seen.size(); ++c) {
    const bool expect = c == issue_cycle[0] + 1 || c == issue_cycle[2] + 1;
    EXPECT_EQ(bypass_seen[c].valid, expect) << "edge " << c;
    if (expect) {
      EXPECT_TRUE(bypass_seen[c].skipped);
      EXPECT_EQ(bypass_seen[c].value, 0);
      EXPECT_EQ(bypass_seen[c].issue, c - 1);
    }
    EXPECT_EQ(compute_seen[c], c == issue_cycle[1] || c == issue_cycle[3]) << "edge " << c;
  }
}

// Merge: out-of-order arrivals retire in stream order; a result can retire at its arrival edge
// (flow-through); a low sink ready holds the head; a credit returns one edge after each retire.
TEST(RtlModules, ResultMergeOrderFlowThroughBackpressure) {
  sc_core::sc_clock clk("clk", clock_period(), 0.5, clock_first_edge(), true);
  sc_core::sc_signal<Result> bypass("bypass"), compute("compute");
  sc_core::sc_signal<bool> sink_ready("sink_ready", true);
  ResultMerge merge("merge", 4, 16, false, true);
  auto result = [](std::uint64_t seq, bool skipped) {
    Result r;
    r.valid = true;
    r.skipped = skipped;
    r.seq = seq;
    r.value = skipped ? 0 : 1000 + static_cast<std::int64_t>(seq);
    return r;
  };
  // Arrivals (edge at which the merge samples them): seq 1 (bypass) at 2, seq 0 (compute) at 4,
  // seq 2 (bypass) and seq 3 (compute) together at 5. Sink not ready at edge 6.
  std::vector<std::pair<std::uint64_t, Result>> bypass_at = {{2, result(1, true)},
                                                             {5, result(2, true)}};
  std::vector<std::pair<std::uint64_t, Result>> compute_at = {{4, result(0, false)},
                                                              {5, result(3, false)}};
  auto drive = [](sc_core::sc_signal<Result>& sig,
                  const std::vector<std::pair<std::uint64_t, Result>>& at, std::uint64_t edge) {
    Result r;
    for (const auto& [e, x] : at)
      if (e == edge) r = x;
    sig.write(r);
  };
  std::vector<std::pair<std::uint64_t, Result>> retired;
  std::vector<bool> credit_seen;
  Driver driver("driver", [&](std::uint64_t c) {
    credit_seen.push_back(merge.credit_return.read());
    if (merge.head_valid.read() && sink_ready.read()) retired.push_back({c, merge.head.read()});
    drive(bypass, bypass_at, c + 1);
    drive(compute, compute_at, c + 1);
    sink_ready.write(c + 1 != 6);
  });
  driver.ticks(merge);
  driver.clk(clk);
  merge.bypass_in(bypass);
  merge.compute_in(compute);
  merge.sink_ready(sink_ready);
  run_cycles(12);

  ASSERT_EQ(retired.size(), 4u);
  const std::uint64_t expect_cycle[] = {4, 5, 7, 8};
  const std::uint64_t expect_done[] = {4, 2, 5, 5};
  for (std::uint64_t i = 0; i < 4; ++i) {
    EXPECT_EQ(retired[i].second.seq, i);
    EXPECT_EQ(retired[i].first, expect_cycle[i]) << "seq " << i;
    EXPECT_EQ(retired[i].second.done, expect_done[i]) << "seq " << i;
  }
  for (std::uint64_t c = 0; c < credit_seen.size(); ++c) {
    const bool expect = c == 5 || c == 6 || c == 8 || c == 9;
    EXPECT_EQ(credit_seen[c], expect) << "edge " << c;
  }
  EXPECT_EQ(merge.max_occupancy(), 3u);  // seq 1, 2, 3 stored at edge 5 (seq 0 retired at 4)
  EXPECT_EQ(merge.overflows(), 0u);
}

// Sink: ready at edge c is SinkReady::ready(c); a valid head waits while it is low.
TEST(RtlModules, ScoreboardHonoursSinkReady) {
  const SlotMap slots = make_slots(two_materials());
  const auto unit = make_unit(parse_unit_spec("lut"), slots);
  const SinkReady sink{0.4, 11};
  RowRing ring(4);
  SimControl control;
  control.set_lanes(1);
  sc_core::sc_clock clk("clk", clock_period(), 0.5, clock_first_edge(), true);
  sc_core::sc_signal<bool> head_valid("head_valid", false);
  sc_core::sc_signal<Result> head("head");
  std::vector<ResultTiming> timings;
  Scoreboard sb(
      "sink", *unit, sink, ring, control,
      [&](const VectorRow&, const Result&, const ResultTiming& t) { timings.push_back(t); }, false,
      false);
  auto result = [&](std::uint64_t seq) {
    Result r;
    r.valid = true;
    r.seq = seq;
    r.slot = 0;
    r.t_raw = 60000 + static_cast<std::int64_t>(seq);
    r.value = unit->eval_with_skip(0, r.t_raw);
    r.skipped = unit->skip(0, r.t_raw);
    r.issue = seq;
    r.done = seq + 1;
    r.last = seq == 9;
    return r;
  };
  std::uint64_t seq = 0;
  std::vector<bool> ready_seen;
  std::uint64_t waits = 0;
  head_valid.write(true);
  head.write(result(0));
  Driver driver("driver", [&](std::uint64_t) {
    ready_seen.push_back(sb.ready.read());
    if (head_valid.read()) {
      if (sb.ready.read()) {
        ++seq;
        head_valid.write(seq < 10);
        if (seq < 10) head.write(result(seq));
      } else {
        ++waits;
      }
    }
  });
  driver.ticks(sb);
  driver.clk(clk);
  sb.head_valid(head_valid);
  sb.head(head);
  run_cycles(60);

  for (std::uint64_t c = 0; c < ready_seen.size(); ++c) EXPECT_EQ(ready_seen[c], sink.ready(c));
  ASSERT_EQ(timings.size(), 10u);
  EXPECT_TRUE(sb.done());
  EXPECT_EQ(sb.mismatches(), 0u);
  EXPECT_EQ(sb.stats().results, 10u);
  EXPECT_EQ(sb.stats().sink_wait, waits);
  EXPECT_EQ(sb.stats().cycles, timings.back().retire + 1);
  for (const ResultTiming& t : timings) EXPECT_TRUE(sink.ready(t.retire));
}

// Settled by the clock (a lane), the comparator's combinational part reads its inputs' new values
// after the edge's ticks: only a Register has them, so plain signals are refused at elaboration.
TEST(RtlModules, CombinationalSettledByTheClockNeedsRegisterInputs) {
  const SlotMap slots = make_slots(two_materials());
  const auto unit = make_unit(parse_unit_spec("hast"), slots);
  sc_core::sc_signal<bool> src_valid("src_valid", true), credit_return("credit_return", false);
  Register<bool> unit_ready("unit_ready", true);
  sc_core::sc_signal<Request> src_request("src_request");
  TauComparator cmp("cmp", *unit, 2, false, CombMode::kSettledByClock);
  cmp.src_valid(src_valid);
  cmp.src_request(src_request);
  cmp.unit_ready(unit_ready);
  cmp.credit_return(credit_return);
  try {
    sc_core::sc_start(clock_period());
    ADD_FAILURE() << "elaborated with plain signals";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("every input must be a Register"), std::string::npos)
        << e.what();
  }
  EXPECT_TRUE(cmp.unit_ready.bound_to_register());
  EXPECT_FALSE(cmp.src_valid.bound_to_register());
}

}  // namespace
}  // namespace glint::rtl
