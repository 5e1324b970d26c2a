// glint render: a scene ray-cast once, its shading requests streamed in memory through the float
// reference and every unit, and the images an architect judges a highlight unit by: the reference
// and each unit's image, the specular term alone, an error heat map per unit in 8-bit LSBs,
// Källberg & Larsson's skip mask, and a labelled contact sheet; plus image-level error and skip
// statistics. Memory is bounded by the image (the requests of one tile of rows at a time), and
// every byte is independent of the thread count.
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cost/cost_model.h"
#include "eval/evaluate.h"
#include "image/float_image.h"
#include "image/image.h"
#include "scene/scene.h"

namespace glint {

class OutputSet;
class OutputFile;

// Version 4: float_images (glint render --float). Version 3: image errors' mean_lsb is the mean of
// the pixels' largest channel (2: of every channel); display, eps_measure, skip_guarantee and
// slots[].pixel_weight added; request-level weighted errors in the scene's display encoding (2:
// linear, times c_y). Version 2 stated the chip (chip; the colour stage gone).
inline constexpr int kRenderReportVersion = 4;

// The header of a scene's shading requests: the lights, and only the materials objects use (units
// are elaborated for what the scene shows, not for what its file defines). header_of, if given,
// receives each scene material's index in the header (-1: unused).
VectorHeader scene_request_header(const Scene& scene,
                                  std::vector<std::int32_t>* header_of = nullptr);

// What a render does with its images.
enum class RenderImages {
  kKeep,    // the result holds every image whole (write_render encodes them)
  kStream,  // each PNG is encoded as its rows are made and handed to png_sinks; the result's
            // images are left empty, so memory is the error maps', not the images'
  kNone,    // no images: the image errors and skip counts only (sweeps)
};

struct RenderOptions {
  std::vector<UnitSpec> units;  // empty: every unit at its defaults
  int threads = 1;
  Chip chip;                                        // --chip (units/chip.h)
  EpsMeasure eps_measure = EpsMeasure::kLuminance;  // --eps-measure (reference/pixel_error.h)
  int tile_rows = 16;     // rows ray-cast and evaluated together (memory: one tile's requests)
  bool progress = false;  // a progress line on stderr
  // Receives every tile's requests in raster order (pixel, then light), e.g. for a vector file.
  std::function<void(const VectorRow* rows, std::size_t count)> on_requests;
  RenderImages images = RenderImages::kKeep;
  // kStream: one sink per PNG of render_file_names, in its order (report.json excluded). Sinks
  // are called on the render's threads, each from one thread at a time.
  std::vector<PngRowWriter::Sink> png_sinks;
  // Linear float images, in any mode: the reference (ambient, diffuse and specular light), its
  // specular term and each unit's, as rows of linear R, G, B floats a tile at a time, one sink per
  // file of render_float_file_names in its order (each called from one thread at a time).
  // float_format names the files in the report.
  std::optional<FloatFormat> float_format;
  std::vector<std::function<void(const float* rgb, int rows)>> float_sinks;
};

// Error of one image against the reference, on the final 8-bit pixels in the scene's display
// encoding. A pixel's error is its largest channel's code difference (reference/pixel_error.h);
// max and mean are of that figure, and the heat map shows it.
struct ImageError {
  double max_lsb = 0;
  double mean_lsb = 0;  // mean of the pixels' errors (before schema 2: of every channel)
  double psnr_db = std::numeric_limits<double>::infinity();  // 10 log10(255^2 / MSE); inf if equal
  double differing_fraction = 0;                             // pixels with any channel different
  // The highlight's extent: pixels whose specular luminance reaches a tenth of the material's peak
  // under the scene's lights, and its ratio to the reference's (Schlick's "broader frontiers",
  // Hast's d).
  std::uint64_t highlight_pixels = 0;
  double highlight_ratio = 1;
  // Its bright core: pixels whose specular luminance reaches half the material's peak under the
  // scene's lights (the half-maximum extent, the size the eye reads as the highlight).
  std::uint64_t core_pixels = 0;
  double core_ratio = 1;

  nlohmann::json to_json() const;
};

// Where the requests of one (material, light) pair went, by Källberg & Larsson's criteria.
struct SkipCounts {
  std::uint64_t facing_away = 0;  // n.l <= 0: the light is behind the surface, no request made
  std::uint64_t zero = 0;         // t <= 0: skipped by the standard test
  std::uint64_t tau = 0;          // 0 < t <= tau: skipped only by the threshold
  std::uint64_t computed = 0;     // t > tau

  std::uint64_t total() const { return facing_away + zero + tau + computed; }
  void add(const SkipCounts& o);
  nlohmann::json to_json() const;
};

struct UnitRender {
  std::string label, spec;
  Image8 image, specular, heatmap;
  double heatmap_scale = 1;  // LSBs at the top of the heat map's colour bar
  ImageError error;
  UnitStats stats;  // request-level accuracy (the eval report's)
  UnitCost cost;
  std::uint64_t skipped = 0;   // requests the unit's own comparator skipped
  std::uint64_t computed = 0;  // requests it computed
};

struct RenderResult {
  std::string scene_name;
  int width = 0, height = 0;
  std::uint64_t requests = 0;
  Image8 reference, reference_specular, skip_mask;
  // The reference with Källberg's skip alone (every request at t <= tau gives 0): the image cost
  // of the threshold itself.
  Image8 skip_only;
  ImageError skip_only_error;
  // What eps guarantees of it (skip_guarantee_lsb): the scene's display, the eps measure, the
  // largest channel weight over a slot's tau weight, the bound in LSB, and whether the image holds
  // it (it must: a false here is a bug, and the render then states no bound).
  DisplayEncoding display = DisplayEncoding::kSrgb8;
  EpsMeasure eps_measure = EpsMeasure::kLuminance;
  double skip_ratio = 1;
  int skip_guarantee_lsb = 0;
  bool skip_within_guarantee = false;
  std::vector<std::string> materials;          // every scene material (the index of skips)
  std::vector<std::string> lights;             // every light's name
  std::vector<std::string> used_materials;     // those objects use: the ones units are built for
  std::vector<std::vector<SkipCounts>> skips;  // [light][scene material]
  std::vector<UnitRender> units;
  std::vector<std::string> lobes;  // lobes present in the scene's visible materials
  nlohmann::json slots;            // the slots the units were elaborated for
  nlohmann::json chip;             // the chip they are built on (eval/chip_report.h)
  Image8 contact_sheet;
  RenderImages images = RenderImages::kKeep;  // the options' (kStream: the PNGs went to the sinks)
  std::optional<FloatFormat> float_format;    // the options': float images were written

  SkipCounts skip_total() const;
  std::vector<std::string> t_inputs() const;  // "r.v" and/or "n.h": the cosines the scene needs
  nlohmann::json to_json() const;             // the render report (report.json)
};

// A render that keeps its images (kKeep) holds every unit's images and per-pixel results whole:
// about kRenderBytesPerPixel + kRenderBytesPerPixelUnit x units bytes per pixel (measured: 33
// bytes per pixel for one unit, 17 more per further unit). One that streams them (kStream, glint
// render) keeps a byte per pixel and unit (its error, for the heat map drawn at the end), and
// each thread draws one heat map at a time (its errors as doubles and its pixels): about
// kStreamBytesPerPixel + kStreamBytesPerPixelUnit x units + kStreamBytesPerHeatmap x min(threads,
// units) (measured at 3840x2160 with 1 to 5 units on 1 and 2 threads: 17 to 35 bytes per pixel,
// the rule 22 to 39; tests/bench/RESULTS.md). Beyond kMaxRenderBytes by its rule, render_scene
// refuses the scene before any work (InputError at "camera.resolution").
inline constexpr std::uint64_t kRenderBytesPerPixel = 16;
inline constexpr std::uint64_t kRenderBytesPerPixelUnit = 17;
inline constexpr std::uint64_t kStreamBytesPerPixel = 8;
inline constexpr std::uint64_t kStreamBytesPerPixelUnit = 1;
inline constexpr std::uint64_t kStreamBytesPerHeatmap = 13;
inline constexpr std::uint64_t kMaxRenderBytes = std::uint64_t{4} << 30;
// The bytes a render of `pixels` pixels through `units` units on `threads` threads takes by the
// rule above (kNone takes no per-pixel memory but its tiles').
std::uint64_t render_bytes(std::uint64_t pixels, std::size_t units,
                           RenderImages images = RenderImages::kKeep, int threads = 1);

RenderResult render_scene(const Scene& scene, const RenderOptions& options);

// The file names write_render uses, in contact-sheet order.
std::vector<std::string> render_file_names(const RenderResult& result);
// The same before rendering: the labels render_scene gives the units of `specs` (every unit at its
// defaults when empty; std::invalid_argument for an unknown unit), and their files.
std::vector<std::string> render_unit_labels(const std::vector<UnitSpec>& specs);
std::vector<std::string> render_file_names(const std::vector<std::string>& labels);
// The float images' files (RenderOptions::float_sinks): reference, reference_specular and
// LABEL_specular, with the format's extension.
std::vector<std::string> render_float_file_names(const std::vector<std::string>& labels,
                                                 FloatFormat format);

// The render's files as outputs of an OutputSet (io/output_set.h), declared before rendering:
// `dir` made if missing (removed again if the run fails), every file checked and its temporary
// created. `option` names the folder in messages.
struct RenderOutputs {
  std::vector<std::pair<std::string, OutputFile*>> files;  // name in `dir`, output
};
RenderOutputs declare_render_outputs(OutputSet& outputs, const std::string& dir,
                                     const std::vector<std::string>& labels,
                                     const std::string& option = "-o");
// Writes every image as PNG (encoded on `threads` threads; the bytes do not depend on it) and
// report.json into the declared outputs (the names must be the result's: std::logic_error
// otherwise); the caller commits them with its other outputs. A streamed result (kStream) wrote
// its PNGs already: only report.json is written. A result without images (kNone) is a
// std::logic_error.
void write_render(const RenderResult& result, const RenderOutputs& outputs, int threads = 1);
// The PNG sinks of kStream (RenderOptions::png_sinks) writing into the declared outputs.
std::vector<PngRowWriter::Sink> render_png_sinks(const RenderOutputs& outputs);
// The same into `dir` with an OutputSet of its own, committed: every file is written to its
// temporary, and all are renamed into place only when all were written (output_set.h).
void write_render(const RenderResult& result, const std::string& dir);

}  // namespace glint
