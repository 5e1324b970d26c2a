#include "eval/golden_diff.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "eval/json_diff.h"
#include "units/catalogue.h"

namespace glint {
namespace {

using Json = nlohmann::json;

// A field of the hardware: where it is (a JSON pointer into a lane, or into the report for the
// run's), and what a colleague calls it.
struct HardwareField {
  const char* pointer;
  const char* words;
};

// The chip (units/chip.h) is the run's; a lane's storage and capacities follow from it. A spec's
// keys come first: the spec resolves every key, so a changed default shows.
constexpr HardwareField kSimLaneHardware[] = {{"/spec", "spec"},
                                              {"/elaboration/storage", "table storage"},
                                              {"/timing/latency", "latency"},
                                              {"/timing/ii", "initiation interval"},
                                              {"/timing/buffer_depth", "merge buffer depth"},
                                              {"/elaboration/capacity", "slot capacity"},
                                              {"/elaboration/slots", "slots"},
                                              {"/elaboration/datapath_groups", "datapath groups"},
                                              {"/elaboration/group_capacity", "material capacity"},
                                              {"/elaboration/table_entries", "table entries"},
                                              {"/elaboration/sized_to", "tables sized to"},
                                              {"/elaboration/n_register/built", "n register"}};
constexpr HardwareField kSimRunHardware[] = {{"/chip/spec", "chip"},
                                             {"/per_light_slots", "per-light slots"},
                                             {"/datapath_groups", "datapath groups"},
                                             {"/sink_ready", "sink ready"},
                                             {"/seed", "sink seed"},
                                             {"/mode", "mode"}};
constexpr HardwareField kRenderLaneHardware[] = {
    {"/spec", "spec"},
    {"/description/elaboration/storage", "table storage"},
    {"/description/timing/latency", "latency"},
    {"/description/timing/ii", "initiation interval"},
    {"/description/timing/buffer_depth", "merge buffer depth"},
    {"/description/elaboration/capacity", "slot capacity"},
    {"/description/elaboration/slots", "slots"},
    {"/description/elaboration/datapath_groups", "datapath groups"},
    {"/description/elaboration/group_capacity", "material capacity"},
    {"/description/elaboration/table_entries", "table entries"},
    {"/description/elaboration/sized_to", "tables sized to"},
    {"/description/elaboration/n_register/built", "n register"}};
constexpr HardwareField kRenderRunHardware[] = {{"/chip/spec", "chip"}};

// How a headline figure reads: an error "rose" or "fell"; a fraction in per cent.
enum class Style { kError, kPlain, kPercent };

struct Headline {
  const char* pointer;
  const char* words;
  const char* unit;  // after the number ("" for none)
  Style style;
};

constexpr Headline kSimHeadlines[] = {
    {"/errors/max_lsb", "max error", "LSB", Style::kError},
    {"/errors/weighted/max_lsb", "weighted max error", "LSB", Style::kError},
    {"/errors/bound_lsb", "error bound", "LSB", Style::kError},
    {"/errors/mismatch_fraction", "display mismatches", "%", Style::kPercent},
    {"/area/ge", "area", "GE", Style::kPlain},
    {"/critical_path/delay", "critical path", "gates", Style::kPlain},
    {"/throughput", "throughput", "results/cycle", Style::kPlain},
    {"/cycles", "cycles", "", Style::kPlain},
    {"/latency/mean", "mean latency", "cycles", Style::kPlain},
    {"/stall_cycles", "stall cycles", "", Style::kPlain},
    {"/skipped", "skipped", "requests", Style::kPlain}};
constexpr Headline kRenderHeadlines[] = {
    {"/image_error/max_lsb", "image max error", "LSB", Style::kError},
    {"/image_error/mean_lsb", "image mean error", "LSB", Style::kError},
    {"/image_error/differing_fraction", "pixels differing", "%", Style::kPercent},
    {"/image_error/highlight_ratio", "highlight extent", "x", Style::kPlain},
    {"/errors/max_lsb", "request max error", "LSB", Style::kError},
    {"/area_ge", "area", "GE", Style::kPlain},
    {"/critical_path", "critical path", "gates", Style::kPlain},
    {"/skipped", "skipped", "requests", Style::kPlain}};
constexpr Headline kRenderRunHeadlines[] = {
    {"/skip_only_image_error/max_lsb", "skip alone: image max error", "LSB", Style::kError}};

const Json* at(const Json& doc, const char* pointer) {
  const Json::json_pointer p(pointer);
  return doc.contains(p) ? &doc.at(p) : nullptr;
}

std::string value_text(const Json* v) {
  if (!v) return "(none)";
  if (v->is_boolean()) return v->get<bool>() ? "on" : "off";
  if (v->is_string()) return v->get<std::string>();
  return v->dump();
}

// "name:a=1,b=2" -> the keys that differ ("b=2 -> b=3", "c=4 added"), or the whole specs when
// the unit itself changed.
std::string spec_change(const std::string& was, const std::string& now) {
  const auto split = [](const std::string& s) {
    std::pair<std::string, std::vector<std::string>> out;
    const auto colon = s.find(':');
    out.first = s.substr(0, colon);
    if (colon == std::string::npos) return out;
    std::size_t from = colon + 1;
    for (;;) {
      const auto comma = s.find(',', from);
      out.second.push_back(s.substr(from, comma - from));
      if (comma == std::string::npos) break;
      from = comma + 1;
    }
    return out;
  };
  const auto [wname, wkeys] = split(was);
  const auto [nname, nkeys] = split(now);
  if (wname != nname) return fmt::format("spec {} -> {}", was, now);
  const auto key_of = [](const std::string& kv) { return kv.substr(0, kv.find('=')); };
  std::vector<std::string> parts;
  for (const auto& kv : wkeys) {
    const auto it = std::find_if(nkeys.begin(), nkeys.end(),
                                 [&](const std::string& n) { return key_of(n) == key_of(kv); });
    if (it == nkeys.end()) {
      parts.push_back(kv + " removed");
    } else if (*it != kv) {
      parts.push_back(kv + " -> " + *it);
    }
  }
  for (const auto& kv : nkeys)
    if (std::none_of(wkeys.begin(), wkeys.end(),
                     [&](const std::string& w) { return key_of(w) == key_of(kv); }))
      parts.push_back(kv + " added");
  std::string out = "spec";
  for (std::size_t i = 0; i < parts.size(); ++i) out += (i ? ", " : " ") + parts[i];
  return out;
}

// The leaves of two values that differ, "path old -> new" (objects walked key by key, so that
// a chip object names the setting that changed).
void leaf_changes(const Json* g, const Json* f, const std::string& path,
                  std::vector<std::string>& out) {
  if (g && f && g->is_object() && f->is_object()) {
    for (auto it = g->begin(); it != g->end(); ++it)
      leaf_changes(&*it, f->contains(it.key()) ? &f->at(it.key()) : nullptr, path + "." + it.key(),
                   out);
    for (auto it = f->begin(); it != f->end(); ++it)
      if (!g->contains(it.key())) leaf_changes(nullptr, &*it, path + "." + it.key(), out);
    return;
  }
  if ((g == nullptr) == (f == nullptr) && (!g || *g == *f)) return;
  out.push_back(fmt::format("{} {} -> {}", path, value_text(g), value_text(f)));
}

template <std::size_t N>
void field_changes(const Json& g, const Json& f, const HardwareField (&fields)[N],
                   const std::string& who, std::vector<std::string>& out) {
  // The run's fields read alone ("slot capacity 42 -> 64"), a lane's after its label.
  const std::string prefix = who.empty() ? "" : who + ": ";
  for (const HardwareField& h : fields) {
    const Json* gv = at(g, h.pointer);
    const Json* fv = at(f, h.pointer);
    if (!gv && !fv) continue;
    if (std::string(h.words) == "spec" && gv && fv && gv->is_string() && fv->is_string()) {
      if (*gv != *fv)
        out.push_back(prefix + spec_change(gv->get<std::string>(), fv->get<std::string>()));
      continue;
    }
    std::vector<std::string> leaves;
    leaf_changes(gv, fv, h.words, leaves);
    for (const auto& l : leaves) out.push_back(prefix + l);
  }
}

// A number for a colleague: grouped thousands ("6 301"), else three significant digits, more
// when needed to tell `v` from `other`.
std::string number_text(double v, double other) {
  if (std::fabs(v) >= 1000 && std::fabs(v - other) >= 1) {
    const auto n = static_cast<long long>(std::llround(std::fabs(v)));
    std::string digits = std::to_string(n), out;
    for (std::size_t i = 0; i < digits.size(); ++i) {
      if (i > 0 && (digits.size() - i) % 3 == 0) out += ' ';
      out += digits[i];
    }
    return (v < 0 ? "-" : "") + out;
  }
  for (int p = 3; p < 17; ++p) {
    const std::string a = fmt::format("{:.{}g}", v, p);
    if (a != fmt::format("{:.{}g}", other, p)) return a;
  }
  return fmt::format("{:.17g}", v);
}

std::string percent_text(double was, double now) {
  if (was == 0) return "(was 0)";
  const double p = 100.0 * (now - was) / std::fabs(was);
  if (std::fabs(p) >= 10) return fmt::format("({:+.0f} %)", p);
  if (std::fabs(p) >= 0.1) return fmt::format("({:+.1f} %)", p);
  return fmt::format("({:+.2g} %)", p);
}

struct Move {
  double size = 0;  // |relative change|; infinite from 0
  std::string text;
  int order = 0;  // the headline's place in its table: errors first, then cost, then counts
};

// A lane's line names its largest few moves, in the table's order.
constexpr std::size_t kMovesPerLane = 4;

template <std::size_t N>
void headline_moves(const Json& g, const Json& f, const Headline (&list)[N], double rel_tol,
                    std::vector<Move>& out) {
  for (const Headline& h : list) {
    const Json* gv = at(g, h.pointer);
    const Json* fv = at(f, h.pointer);
    if (!gv || !fv || !gv->is_number() || !fv->is_number()) continue;
    const double scale = h.style == Style::kPercent ? 100.0 : 1.0;
    const double was = gv->get<double>() * scale, now = fv->get<double>() * scale;
    if (!moved_beyond(was, now, rel_tol)) continue;
    const std::string unit = *h.unit ? std::string(" ") + h.unit : "";
    const char* verb = h.style == Style::kError ? (now > was ? " rose" : " fell") : "";
    Move m;
    m.order = static_cast<int>(&h - list);
    m.size = was == 0 ? HUGE_VAL : std::fabs(now - was) / std::fabs(was);
    // "max error rose 0.31 LSB -> 0.52 LSB", "area 6 301 -> 6 762 GE".
    const std::string first_unit = h.style == Style::kPlain ? "" : unit;
    m.text = fmt::format("{}{} {}{} -> {}{} {}", h.words, verb, number_text(was, now), first_unit,
                         number_text(now, was), unit, percent_text(was, now));
    out.push_back(std::move(m));
  }
}

struct LaneMoves {
  std::string lane;
  std::vector<Move> moves;
  double largest() const {
    double m = 0;
    for (const Move& x : moves) m = std::max(m, x.size);
    return m;
  }
};

}  // namespace

std::vector<std::string> lane_labels(const nlohmann::json& report) {
  std::vector<std::string> names;
  if (report.is_object() && report.contains("units") && report["units"].is_array())
    for (const auto& u : report["units"])
      names.push_back(u.is_object() && u.contains("unit") && u["unit"].is_string()
                          ? u["unit"].get<std::string>()
                          : "lane");
  return unit_labels(names);
}

std::vector<std::string> hardware_changes(GoldenKind kind, const nlohmann::json& golden,
                                          const nlohmann::json& fresh) {
  std::vector<std::string> out;
  const bool trace = kind == GoldenKind::kTrace;
  if (trace) {
    field_changes(golden, fresh, kSimRunHardware, "", out);
  } else {
    field_changes(golden, fresh, kRenderRunHardware, "", out);
  }
  const auto labels = lane_labels(golden);
  const auto& gu = golden.at("units");
  const auto& fu = fresh.at("units");
  if (gu.size() != fu.size()) out.push_back(fmt::format("lanes: {} -> {}", gu.size(), fu.size()));
  // A change shared by several lanes (a chip's capacity reaches every table) is one line naming
  // them, "every lane" when it is all of them; lines in order of first appearance.
  std::vector<std::pair<std::string, std::vector<std::string>>> shared;  // change, lanes
  const std::size_t lanes = std::min(gu.size(), fu.size());
  for (std::size_t i = 0; i < lanes; ++i) {
    std::vector<std::string> changes;
    if (trace) {
      field_changes(gu[i], fu[i], kSimLaneHardware, "", changes);
    } else {
      field_changes(gu[i], fu[i], kRenderLaneHardware, "", changes);
    }
    for (auto& c : changes) {
      auto it =
          std::find_if(shared.begin(), shared.end(), [&](const auto& s) { return s.first == c; });
      if (it == shared.end()) it = shared.insert(shared.end(), {std::move(c), {}});
      it->second.push_back(labels[i]);
    }
  }
  for (const auto& [change, who] : shared) {
    std::string names;
    for (const auto& w : who) names += (names.empty() ? "" : ", ") + w;
    out.push_back((who.size() == lanes && lanes > 1 ? std::string("every lane") : names) + ": " +
                  change);
  }
  return out;
}

std::vector<std::string> largest_changes(GoldenKind kind, const nlohmann::json& golden,
                                         const nlohmann::json& fresh, double rel_tol,
                                         std::size_t max_lanes) {
  std::vector<LaneMoves> lanes;
  const bool trace = kind == GoldenKind::kTrace;
  if (!trace) {
    LaneMoves run{"scene", {}};
    headline_moves(golden, fresh, kRenderRunHeadlines, rel_tol, run.moves);
    if (!run.moves.empty()) lanes.push_back(std::move(run));
  }
  const auto labels = lane_labels(golden);
  const auto& gu = golden.at("units");
  const auto& fu = fresh.at("units");
  for (std::size_t i = 0; i < std::min(gu.size(), fu.size()); ++i) {
    LaneMoves lane{labels[i], {}};
    if (trace) {
      headline_moves(gu[i], fu[i], kSimHeadlines, rel_tol, lane.moves);
    } else {
      headline_moves(gu[i], fu[i], kRenderHeadlines, rel_tol, lane.moves);
    }
    std::stable_sort(lane.moves.begin(), lane.moves.end(),
                     [](const Move& a, const Move& b) { return a.size > b.size; });
    const std::size_t more =
        lane.moves.size() > kMovesPerLane ? lane.moves.size() - kMovesPerLane : 0;
    lane.moves.resize(lane.moves.size() - more);
    std::sort(lane.moves.begin(), lane.moves.end(),
              [](const Move& a, const Move& b) { return a.order < b.order; });
    if (more > 0)
      lane.moves.push_back({0, fmt::format("{} more figure{}", more, more == 1 ? "" : "s"), 0});
    // A lane whose every figure held may still compute other bits: its digest says so.
    const bool digest_moved = trace && gu[i].contains("digest") && fu[i].contains("digest") &&
                              gu[i]["digest"] != fu[i]["digest"];
    if (digest_moved) lane.moves.push_back({0, "results differ bit for bit (digest)", 0});
    if (!lane.moves.empty()) lanes.push_back(std::move(lane));
  }
  std::stable_sort(lanes.begin(), lanes.end(), [](const LaneMoves& a, const LaneMoves& b) {
    return a.largest() > b.largest();
  });
  std::vector<std::string> out;
  for (std::size_t i = 0; i < lanes.size() && i < max_lanes; ++i) {
    std::string line = lanes[i].lane + ":";
    for (std::size_t k = 0; k < lanes[i].moves.size(); ++k)
      line += (k ? "; " : " ") + lanes[i].moves[k].text;
    out.push_back(std::move(line));
  }
  if (lanes.size() > max_lanes)
    out.push_back(fmt::format("(and {} more lanes)", lanes.size() - max_lanes));
  return out;
}

namespace {

void diff_render_value(const std::string& path, const Json& g, const Json& f, double rel_tol,
                       std::vector<std::string>& out) {
  // Counts are integers in the JSON: exact. Other numbers are floating-point figures.
  const Tolerant tolerant = [](const Json& a, const Json& b) {
    return a.is_number_float() && b.is_number() && !b.is_number_integer();
  };
  diff_json(path, g, f, tolerant, rel_tol, out);
}

}  // namespace

std::vector<std::string> diff_render_reports(const nlohmann::json& golden,
                                             const nlohmann::json& fresh, double rel_tol) {
  std::vector<std::string> out;
  // Lanes by their labels, as diff_sim_reports names them ("hast.errors.max_abs").
  for (auto it = golden.begin(); it != golden.end(); ++it) {
    if (it.key() == "units") continue;
    if (!fresh.contains(it.key())) {
      out.push_back(it.key() + ": missing in the new report");
    } else {
      diff_render_value(it.key(), *it, fresh.at(it.key()), rel_tol, out);
    }
  }
  for (auto it = fresh.begin(); it != fresh.end(); ++it)
    if (!golden.contains(it.key())) out.push_back(it.key() + ": new field (not in the golden)");
  const auto& gu = golden.at("units");
  const auto& fu = fresh.at("units");
  if (gu.size() != fu.size()) {
    out.push_back(
        fmt::format("units: {} in the new report, {} in the golden", fu.size(), gu.size()));
    return out;
  }
  const auto labels = lane_labels(golden);
  for (std::size_t i = 0; i < gu.size(); ++i)
    diff_render_value(labels[i], gu[i], fu[i], rel_tol, out);
  return out;
}

}  // namespace glint
