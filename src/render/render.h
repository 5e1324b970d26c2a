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
#include "eval/activity.h"
#include "eval/evaluate.h"
#include "image/float_image.h"
#include "image/image.h"
#include "scene/scene.h"

namespace glint {

class OutputSet;
class OutputFile;

// Version 4: skip.fractions_of, units[].skipped_fraction (every skip fraction of light x pixel
// pairs), units[].file, heat_scale, skip_masks, reproduces, meshes[] (each mesh file and its
// normals), float_images (glint render --float); units[].unit labelled by the keys that tell
// repeated units apart. Version 3: image errors' mean_lsb is the mean of the pixels' largest
// channel (2: of every channel); display, eps_measure, skip_guarantee and
// slots[].pixel_weight added; request-level weighted errors in the scene's display encoding (2:
// linear, times c_y). Version 2 stated the chip (chip; the colour stage gone).
inline constexpr int kRenderReportVersion = 4;

// The header of a scene's shading requests: the lights, and only the materials objects use (units
// are elaborated for what the scene shows, not for what its file defines). header_of, if given,
// receives each scene material's index in the header (-1: unused).
VectorHeader scene_request_header(const Scene& scene,
                                  std::vector<std::int32_t>* header_of = nullptr);

// The heat maps' full scale: one for every unit (the largest error of any, so that colours compare
// across units), or each unit's own largest error.
enum class HeatScale { kShared, kOwn };
const char* to_string(HeatScale s);

// Per-light skip masks are written for the scene's first kMaxLightSkipMasks lights (each costs 3
// bytes per pixel until written).
inline constexpr std::size_t kMaxLightSkipMasks = 8;

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
  bool node = false;  // --node: each lane's area and critical path at the node in the report
  // With node: each lane's energy on the frame's requests (eval/energy.h), a skipped request
  // gated so (--activity GATING; glint render's default: operand, as glint rtl's lane).
  std::optional<Gating> gating;
  Chip chip;                                        // --chip (units/chip.h)
  EpsMeasure eps_measure = EpsMeasure::kLuminance;  // --eps-measure (reference/pixel_error.h)
  HeatScale heat_scale = HeatScale::kShared;        // --heat-scale
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
  // label: the unit's name, with the keys that tell it from units of the same name ("hast d=2");
  // file: its images' file-name stem (render_file_stems).
  std::string label, file, spec;
  Image8 image, specular, heatmap;
  double heatmap_scale = 1;  // LSBs at the top of the heat map's colour bar
  ImageError error;
  UnitStats stats;  // request-level accuracy (the eval report's)
  UnitCost cost;
  std::uint64_t skipped = 0;   // requests the unit's own comparator skipped
  std::uint64_t computed = 0;  // requests it computed
  nlohmann::json energy;       // energy_json on the frame (RenderOptions::gating), else null
  // The same lane without its skip (spec with skip=off) on the same requests, with "spec"; null
  // without energy or for a lane without the skip.
  nlohmann::json energy_without_skip;
  // That lane's error on the frame, measured as this lane's is (issue 26 item 5: what the skip
  // buys is a fair figure only at equal error); set exactly when energy_without_skip is.
  struct WithoutSkip {
    std::string spec;
    ImageError error;  // its final pixels against the reference's
    UnitStats stats;   // its request-level accuracy
    // Pixels whose final colour differs from this lane's, and the largest difference (LSBs of
    // the pixel error): zero when the skip leaves the frame as it is.
    std::uint64_t pixels_differing = 0;
    int max_lsb_between = 0;
  };
  std::optional<WithoutSkip> without_skip;
};

struct RenderResult {
  std::string scene_name;
  int width = 0, height = 0;
  std::uint64_t requests = 0;
  std::uint64_t shaded_pixels = 0;  // pixels with at least one shading request
  double eps = 1e-3;
  std::optional<SceneReproduces> reproduces;
  HeatScale heat_scale = HeatScale::kShared;
  bool node = false;  // units[].node in the report (RenderOptions::node)
  // skip_mask: each visible pixel coloured by the fraction of its lights skipped (facing away,
  // t <= 0 or tau); light_skip_masks: one per light (the first kMaxLightSkipMasks), each pixel by
  // how that light's pair went (Källberg & Larsson's Fig.1 view); legend: the masks' colours and
  // the heat maps' scales.
  Image8 reference, reference_specular, skip_mask, legend;
  std::vector<Image8> light_skip_masks;
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
  nlohmann::json meshes;           // each mesh's format and normals (scene/mesh_summary.h)
  Image8 contact_sheet;
  RenderImages images = RenderImages::kKeep;  // the options' (kStream: the PNGs went to the sinks)
  std::optional<FloatFormat> float_format;    // the options': float images were written

  SkipCounts skip_total() const;
  // The scene's reproduced quantity as glint measures it on this render (nullopt: no reference,
  // a figure without a number, or "tau" on a scene of more than one slot).
  std::optional<double> reproduced_value() const;
  // The unit's skipped share of the light x pixel pairs, the one denominator of every skip
  // fraction: the pairs facing away (no request) plus the requests its comparator skipped.
  double unit_skipped_fraction(const UnitRender& unit) const;
  std::vector<std::string> t_inputs() const;  // "r.v" and/or "n.h": the cosines the scene needs
  nlohmann::json to_json() const;             // the render report (report.json)
};

// A render that keeps its images (kKeep) holds every unit's images and per-pixel results whole:
// about kRenderBytesPerPixel + kRenderBytesPerPixelUnit x units + 3 x masked lights bytes per pixel
// (measured: 33 bytes per pixel for one unit, 17 more per further unit, before the object map's
// byte and the per-light masks). One that streams them (kStream, glint render) keeps a byte per
// pixel and unit (its error, for the error map drawn at the end, where the shared scale is known)
// and the object map's byte (error maps tell a zero error on an object from the background); the
// per-light masks are strips of the current tile; each thread draws one error map at a time (its
// errors as doubles and its pixels): about kStreamBytesPerPixel + kStreamBytesPerPixelUnit x
// units + kStreamBytesPerHeatmap x min(threads, units) (the teapot at 3840x2160 through the
// five default units: 309 MB peak RSS on 2 threads, 209 MB on 1; the rule 332 MB and 224 MB).
// Beyond kMaxRenderBytes by its rule, render_scene refuses the scene before any work (InputError
// at "camera.resolution").
inline constexpr std::uint64_t kRenderBytesPerPixel = 17;
inline constexpr std::uint64_t kRenderBytesPerPixelUnit = 17;
inline constexpr std::uint64_t kStreamBytesPerPixel = 9;
inline constexpr std::uint64_t kStreamBytesPerPixelUnit = 1;
inline constexpr std::uint64_t kStreamBytesPerHeatmap = 13;
inline constexpr std::uint64_t kMaxRenderBytes = std::uint64_t{4} << 30;
// The bytes a render of `pixels` pixels through `units` units on `threads` threads, with
// `masked_lights` per-light skip masks, takes by the rule above (kNone takes no per-pixel memory
// but its tiles').
std::uint64_t render_bytes(std::uint64_t pixels, std::size_t units,
                           RenderImages images = RenderImages::kKeep, int threads = 1,
                           std::size_t masked_lights = 0);

RenderResult render_scene(const Scene& scene, const RenderOptions& options);

// The contact sheet's title: scene, resolution, lights, eps, tau, chip; then reproduces_line.
std::vector<std::string> render_title(const RenderResult& result);
// "reproduces Källberg & Larsson 2014 Fig. 1: tau 0.87 in the paper, 0.8710 here" (empty when
// the scene names no figure).
std::string reproduces_line(const RenderResult& result);

// The file names write_render uses, in contact-sheet order.
std::vector<std::string> render_file_names(const RenderResult& result);
// The same before rendering: the labels render_scene gives the units of `specs` (every unit at its
// defaults when empty; std::invalid_argument for an unknown unit): the unit's name, followed by
// the keys whose values differ among the units of that name ("hast d=2", "hast d=4"; name.1,
// name.2 when their specs are the same); their files' stems (filesystem-safe and unique: spaces
// to '_', any character but [A-Za-z0-9._=-] to '-'); and the files, given the lights' names.
std::vector<std::string> render_unit_labels(const std::vector<UnitSpec>& specs);
std::vector<std::string> render_file_stems(const std::vector<std::string>& labels);
std::vector<std::string> render_file_names(const std::vector<std::string>& labels,
                                           const std::vector<std::string>& lights);
// The lights' names as the scene gives them ("light N" when unnamed).
std::vector<std::string> render_light_names(const Scene& scene);
// The float images' files (RenderOptions::float_sinks): reference, reference_specular and
// STEM_specular (render_file_stems of the labels), with the format's extension.
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
                                     const std::vector<std::string>& lights,
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
