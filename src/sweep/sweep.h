// `glint sweep` as a library call: a grid of unit specs over one input (a vector file, or a scene
// whose shading requests the render layer's ray caster makes in memory), one report row per
// configuration (report.h).
#pragma once

#include <cstddef>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "sweep/engine.h"
#include "sweep/grid.h"

namespace glint {

struct SweepInput {
  std::string path;
  bool scene = false;  // a scene file (JSON, traces/scenes/README.md); else a vector file
};

struct SweepJob {
  SweepInput input;
  std::vector<Grid> grids;
  // --shard K/N: the configurations i with i mod N == K. shards 0: the whole sweep.
  std::size_t shard = 0, shards = 0;
  SweepSettings settings;
  std::string error_measure = "max_lsb";  // the "error" of the Pareto flags (measures.h)
  // Scenes: also the image-level error of every configuration, from the final 8-bit pixels as
  // `glint render` composes them (render_scene, a group of configurations per render).
  bool image = true;
  // Called now and then with a line of progress (stderr on a terminal), or empty.
  std::function<void(const std::string&)> progress;
};

// Runs the sweep: every grid's configurations (those of the shard), the input read once.
// Bad input throws InputError or std::invalid_argument, before any output exists; SlotCapacityError
// when the chip (--chip) is too small for the input.
nlohmann::json run_sweep(const SweepJob& job);

}  // namespace glint
