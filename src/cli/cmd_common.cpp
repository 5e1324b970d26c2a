#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <iostream>

#include "cli/cli.h"
#include "cost/node.h"
#include "io/atomic_file.h"
#include "io/input_error.h"
#include "units/slot_plan.h"

namespace glint::cli {

int guarded(const std::function<int()>& body) {
  try {
    return body();
  } catch (const InputError& e) {
    std::fprintf(stderr, "glint: %s\n", e.what());
    return kExitBadInput;
  } catch (const OutputError& e) {
    std::fprintf(stderr, "glint: %s\n", e.what());
    return kExitBadInput;
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "glint: %s\n", e.what());
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "glint: internal error: %s\n", e.what());
    return 3;
  }
}

void print_json(const nlohmann::json& j) {
  std::cout << j.dump(2) << '\n';
}

void add_display_bits_option(CLI::App* sub, int& bits) {
  sub->add_option("--display-bits", bits,
                  "Display depth for errors in LSBs (lsb, bound_lsb, mismatch): 1..16")
      ->check(CLI::Range(1, 16))
      ->default_val(8);
}

void add_threads_option(CLI::App* sub, int& threads) {
  sub->add_option("--threads", threads,
                  "Threads, 1..256 (default: every core); results do not depend on it")
      ->check(CLI::Range(1, 256));
}

void add_seed_option(CLI::App* sub, std::uint64_t& seed, bool& given) {
  sub->add_option_function<std::string>(
      "--seed",
      [&seed, &given](const std::string& text) {
        // Digits only: std::stoull would wrap "-1" to 2^64 - 1.
        std::uint64_t v = 0;
        const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
        if (text.empty() || text[0] < '0' || text[0] > '9' || ec != std::errc() ||
            end != text.data() + text.size())
          throw CLI::ValidationError("--seed", "'" + text + "' is not an integer in 0..2^64-1");
        seed = v;
        given = true;
      },
      "Seed of the sink backpressure pattern (0..2^64-1, default 1; needs --sink-ready below 1)");
}

void require_backpressure_for_seed(bool seed_given, double sink_ready) {
  if (seed_given && sink_ready >= 1)
    throw std::invalid_argument(
        "--seed sets the pattern of a sink that is not always ready: it needs --sink-ready below "
        "1");
}

void add_node_option(CLI::App* sub, std::string& node) {
  std::string names;
  for (const std::string& n : node_names()) names += (names.empty() ? "" : ", ") + n;
  sub->add_option("--node", node,
                  fmt::format("Also state each lane's area in um2 and critical path in ns and MHz "
                              "at this node, from the cost proxy's constants calibrated against "
                              "its library ({}: OSU 0.18 um, mapped by Yosys and timed by "
                              "OpenSTA; src/cost/README.md)",
                              names))
      ->check(CLI::IsMember(node_names()));
}

void add_chip_option(CLI::App* sub, Chip& chip) {
  sub->add_option_function<std::string>(
         "--chip",
         [&chip](const std::string& text) {
           try {
             chip = parse_chip(text);
           } catch (const std::invalid_argument& e) {
             throw CLI::ValidationError("--chip", fmt::format("'{}': {}", text, e.what()));
           }
         },
         fmt::format(
             "The chip the lanes are built on (stated in every report). rom (default): every "
             "per-material table (thresholds, n, spans, coefficients, t^n, log2/exp2) is a ROM of "
             "the input's materials, fixed at synthesis. ram: registers with a write port that "
             "the driver loads with each material, as a GPU does; ram:materials=M,slots=S gives "
             "them M material entries and S comparator thresholds (1..{} each; default: what the "
             "input uses). A unit's own tables= key must agree with a chip given here",
             kMaxSlotCapacity))
      ->type_name("CHIP");
}

void refuse_chip(const Chip& chip, const std::exception& e) {
  throw std::invalid_argument(fmt::format("--chip {}: {}", chip.spec(), e.what()));
}

std::vector<UnitSpec> specs_for_chip(std::vector<UnitSpec> specs, const Chip& chip) {
  try {
    return specs_on_chip(std::move(specs), chip);
  } catch (const std::invalid_argument& e) {
    refuse_chip(chip, e);
  }
}

void add_eps_measure_option(CLI::App* sub, EpsMeasure& measure) {
  sub->add_option_function<std::string>(
         "--eps-measure",
         [&measure](const std::string& text) {
           const auto m = try_parse_eps_measure(text);
           if (!m)
             throw CLI::ValidationError("--eps-measure",
                                        "'" + text + "' is not one of luminance, channel");
           measure = *m;
         },
         "What eps bounds: luminance = Källberg & Larsson's c_y (eq.3, the default), channel = "
         "the largest channel of light x specular, so that no channel of a skipped lobe exceeds "
         "eps")
      ->type_name("luminance|channel");
}

void refuse_size(const std::string& file, const std::exception& e) {
  throw InputError(file, 0, "slots", e.what());
}

std::vector<UnitSpec> parse_unit_options(const std::vector<std::string>& units) {
  if (units.size() > kMaxUnitOptions)
    throw std::invalid_argument(fmt::format(
        "--unit given {} times: at most {} units (lanes) per run", units.size(), kMaxUnitOptions));
  std::vector<UnitSpec> specs;
  for (const auto& s : units.empty() ? default_unit_names() : units)
    specs.push_back(parse_unit_spec(s));
  return specs;
}

void require_finite_positive(double v, const std::string& option) {
  if (!(std::isfinite(v) && v > 0))
    throw std::invalid_argument(fmt::format("{} {}: expected a finite number > 0", option, v));
}

std::array<double, 3> parse_rgb(const std::string& text, const std::string& option) {
  std::array<double, 3> out{};
  std::size_t pos = 0;
  for (int i = 0; i < 3; ++i) {
    const std::size_t end = i < 2 ? text.find(',', pos) : text.size();
    if (end == std::string::npos) break;
    const char* b = text.data() + pos;
    const char* e = text.data() + end;
    auto [p, ec] = std::from_chars(b, e, out[i]);
    if (ec != std::errc() || p != e || !std::isfinite(out[i]) || out[i] < 0) {
      throw std::invalid_argument(
          fmt::format("{} '{}': expected three finite non-negative numbers r,g,b", option, text));
    }
    if (i == 2) return out;
    pos = end + 1;
  }
  throw std::invalid_argument(fmt::format("{} '{}': expected r,g,b", option, text));
}

}  // namespace glint::cli
