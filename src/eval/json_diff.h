// Walks a golden and a fresh report side by side and lists each difference as a line a reader can
// act on ("hast.errors.max_abs: 0.5, golden 0.4"): a field on one side only, arrays of other
// lengths, leaves that differ. The sim and render goldens' comparisons share it (sim_report.cpp,
// golden_diff.cpp); they differ only in which leaves are floating-point figures that may move
// within a tolerance.
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace glint {

// A golden figure a and a fresh one b differ by more than rel_tol relative (plus 1e-12 absolute).
bool moved_beyond(double a, double b, double rel_tol);

// True for leaves (golden, fresh) compared within the tolerance; every other leaf must be equal.
using Tolerant = std::function<bool(const nlohmann::json& golden, const nlohmann::json& fresh)>;

// `path` names g and f ("" at a document's top: its keys then stand alone).
void diff_json(const std::string& path, const nlohmann::json& g, const nlohmann::json& f,
               const Tolerant& tolerant, double rel_tol, std::vector<std::string>& out);

}  // namespace glint
