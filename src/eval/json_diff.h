// Walks a golden and a fresh report side by side and lists each difference as a line a reader can
// act on ("hast.errors.max_abs: 0.5, golden 0.4"): a field on one side only, arrays of other
// lengths, and leaves that `leaf` finds moved. The sim and render goldens' comparisons share it
// (sim_report.cpp, golden_diff.cpp); they differ only in what a leaf may move by.
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace glint {

// Appends the line for the leaves g (golden) and f (fresh) at `path` when they differ.
using LeafDiff = std::function<void(const std::string& path, const nlohmann::json& g,
                                    const nlohmann::json& f, std::vector<std::string>& out)>;

// `path` names g and f ("" at a document's top: its keys then stand alone).
void diff_json(const std::string& path, const nlohmann::json& g, const nlohmann::json& f,
               const LeafDiff& leaf, std::vector<std::string>& out);

}  // namespace glint
