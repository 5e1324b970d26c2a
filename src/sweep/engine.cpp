#include "sweep/engine.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <stdexcept>

#include "eval/energy.h"
#include "eval/parallel.h"
#include "sweep/measures.h"
#include "sweep/memory.h"
#include "units/catalogue.h"
#include "units/common.h"
#include "units/lane_cost.h"

namespace glint {
namespace {
using Clock = std::chrono::steady_clock;
}  // namespace

struct SweepEngine::Block {
  std::vector<std::size_t> members;       // the configurations it evaluates (engine order)
  std::unique_ptr<Evaluator> ev;          // their units, in that order
  std::vector<TimingEngine> timing;       // one per unit of ev
  std::vector<ActivityCounter> activity;  // one per unit of ev, with node
};

SweepEngine::SweepEngine(const VectorHeader& header, std::vector<SweepConfig> configs,
                         const SweepSettings& settings)
    : configs_(std::move(configs)),
      settings_(settings),
      slots_(make_slots(header, settings.chip)),
      refused_(configs_.size()) {
  check_sweep_memory(configs_,
                     settings_.chip.slots > 0 ? settings_.chip.slots : slots_.params.size());
  settings_.block = std::max<std::size_t>(1, settings_.block);
  settings_.chunk_rows = std::max<std::size_t>(1, settings_.chunk_rows);
  const std::size_t n_blocks = (configs_.size() + settings_.block - 1) / settings_.block;
  std::vector<std::unique_ptr<Block>> blocks(n_blocks);
  // Blocks are built on the threads too (fits and tables take a while for thousands of
  // configurations); each writes only its own block and its own configurations' refusals.
  parallel_for(n_blocks, settings_.jobs, [&](std::size_t b) {
    auto block = std::make_unique<Block>();
    const std::size_t first = b * settings_.block;
    const std::size_t last = std::min(configs_.size(), first + settings_.block);
    std::vector<UnitSpec> specs;
    for (std::size_t k = first; k < last; ++k) {
      block->members.push_back(k);
      specs.push_back(configs_[k].unit_spec);
    }
    try {
      block->ev =
          std::make_unique<Evaluator>(header, specs, settings_.display_bits, settings_.chip);
    } catch (const std::invalid_argument&) {
      // Some configuration cannot be built for this stream: find which, one by one (the slow
      // path, only on refusal), and build the block without them.
      block->members.clear();
      specs.clear();
      for (std::size_t k = first; k < last; ++k) {
        try {
          make_unit(specs_on_chip({configs_[k].unit_spec}, settings_.chip).front(), slots_);
        } catch (const std::invalid_argument& e) {
          refused_[k] = e.what();
          continue;
        }
        block->members.push_back(k);
        specs.push_back(configs_[k].unit_spec);
      }
      block->ev =
          std::make_unique<Evaluator>(header, specs, settings_.display_bits, settings_.chip);
    }
    for (const auto& unit : block->ev->units()) {
      block->timing.emplace_back(unit->timing(), settings_.sink);
      if (settings_.node) block->activity.emplace_back(*unit, settings_.gating);
    }
    blocks[b] = std::move(block);
  });
  std::vector<LaneAccumulator*> lanes;
  std::vector<TimingEngine*> timing;
  for (auto& b : blocks) {
    if (b->members.empty()) continue;
    for (std::size_t u = 0; u < b->members.size(); ++u) {
      lanes.push_back(&b->ev->lane(u));
      timing.push_back(&b->timing[u]);
      if (settings_.node) activity_.push_back(&b->activity[u]);
    }
    blocks_.push_back(std::move(b));
  }
  EngineOptions options;
  options.threads = settings_.jobs;
  options.window_rows = settings_.chunk_rows;
  engine_ = std::make_unique<EvalEngine>(slots_, std::move(lanes), std::move(timing), options);
}

SweepEngine::~SweepEngine() = default;

void SweepEngine::add(const VectorRow* rows, std::size_t count) {
  const auto t0 = Clock::now();
  engine_->add(rows, count);
  // Each configuration's switching activity, a configuration a task, its rows in stream order.
  if (!activity_.empty()) {
    parallel_for(activity_.size(), settings_.jobs, [&](std::size_t k) {
      ActivityCounter& a = *activity_[k];
      const SpecularUnit& unit = a.unit();
      for (std::size_t i = 0; i < count; ++i)
        a.add(slots_.slot(rows[i]), quantize_input(rows[i].t, unit.in_format()));
    });
  }
  profile_.evaluate_s += std::chrono::duration<double>(Clock::now() - t0).count();
  rows_ += count;
}

std::vector<nlohmann::json> SweepEngine::results() const {
  std::vector<nlohmann::json> out(configs_.size());
  for (std::size_t k = 0; k < configs_.size(); ++k) {
    if (refused_[k].empty()) continue;
    const SweepConfig& c = configs_[k];
    out[k] = {
        {"index", c.index}, {"unit", c.unit_spec.name}, {"spec", c.spec}, {"refused", refused_[k]}};
  }
  for (const auto& block_ptr : blocks_) {
    const Block& block = *block_ptr;
    const std::vector<UnitStats> stats = block.ev->stats();
    for (std::size_t u = 0; u < stats.size(); ++u) {
      const SweepConfig& c = configs_[block.members[u]];
      const SpecularUnit& unit = *block.ev->units()[u];
      const UnitStats& s = stats[u];
      const TimingStats& t = block.timing[u].stats();
      const UnitTiming& timing = block.timing[u].timing();
      // The cost and operations as `glint sim` reports them (eval/sim_report.cpp).
      const UnitCost cost = unit_cost(unit);
      // Every kind the CSV has, 0 when the unit never executes it.
      nlohmann::json per_computed = nlohmann::json::object(),
                     per_request = nlohmann::json::object(), total = nlohmann::json::object();
      for (const std::string& kind : operation_kinds())
        per_computed[kind] = per_request[kind] = total[kind] = 0.0;
      for (const auto& [kind, n] : cost.ops_per_computed) {
        per_computed[kind] = n;
        total[kind] = total.value(kind, 0.0) + n * static_cast<double>(t.computed);
      }
      for (const auto& [kind, n] : cost.ops_per_request) {
        per_request[kind] = n;
        total[kind] = total.value(kind, 0.0) + n * static_cast<double>(t.results);
      }
      out[block.members[u]] = {
          {"index", c.index},
          {"refused", nullptr},
          {"unit", unit.name()},
          {"spec", c.spec},
          {"canonical_spec", unit.canonical_spec()},
          {"area_ge", cost.area_ge},
          {"critical_path", cost.critical_path},
          {"critical_stage", cost.critical_stage},
          {"latency", timing.latency},
          {"ii", timing.ii},
          {"buffer_depth", timing.buffer_depth},
          {"area_latency", cost.area_ge * timing.latency},
          {"vectors", s.vectors},
          {"skipped", s.skipped},
          {"computed", t.computed},
          {"cycles", t.cycles},
          {"throughput", t.throughput()},
          {"latency_cycles",
           {{"min", t.latency_min}, {"mean", t.latency_mean()}, {"max", t.latency_max}}},
          {"stall_cycles", t.stall_cycles()},
          {"stalls", {{"merge_buffer_full", t.stall_credit}, {"unit_busy", t.stall_unit}}},
          {"operations",
           {{"per_computed", per_computed}, {"per_request", per_request}, {"total", total}}},
          {"errors", s.errors_json()},
          {"digest", fmt::format("{:016x}", block.ev->digest(u))},
      };
      if (settings_.node) {
        const nlohmann::json n = cost.node_json();
        nlohmann::json& row = out[block.members[u]];
        row["node"] = {{"node", n.at("node")},
                       {"area_um2", n.at("area_um2")},
                       {"critical_path_ns", n.at("critical_path_ns")},
                       {"critical_path", n.at("critical_path")},
                       {"max_clock_mhz", n.at("max_clock_mhz")}};
        if (const EnergyWeights* w = find_energy(cost.node)) {
          const LaneEnergy e = lane_energy(cost, block.activity[u].activity(), *w);
          row["node"]["energy"] = energy_json(e);
          row["energy_pj_per_request"] = e.per_request();
        }
      }
    }
  }
  return out;
}

}  // namespace glint
