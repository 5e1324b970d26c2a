#include "render/render.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <stdexcept>

#include "eval/parallel.h"
#include "render/image_error.h"
#include "scene/tracer.h"
#include "units/catalogue.h"
#include "units/lane_cost.h"

namespace glint {
namespace {

// How a pixel's requests went, for the skip mask: computed by at least one light, else skipped by
// tau for at least one light, else skipped by t <= 0 (or facing away) for every light.
enum class PixelSkip : std::uint8_t { kBackground, kZero, kTau, kComputed };

// Linear RGB accumulators of one tile, one per image source (reference, skip-only, each unit).
struct TileBuffers {
  std::vector<Rgb> diffuse;                // ambient + diffuse, shared by every image
  std::vector<std::vector<Rgb>> specular;  // [source][pixel]
  std::vector<PixelSkip> skip;
  std::vector<double> peak;  // the pixel material's peak specular luminance under every light
};

void add_scaled(Rgb& acc, const Rgb& colour, double s) {
  acc.r += colour.r * s;
  acc.g += colour.g * s;
  acc.b += colour.b * s;
}

Rgb8 to_srgb8(const Rgb& c) {
  return {srgb8(c.r), srgb8(c.g), srgb8(c.b)};
}

// The materials objects use, in scene order.
std::vector<std::uint32_t> used_materials(const Scene& scene) {
  std::set<std::uint32_t> used;
  for (const Mesh& m : scene.meshes) used.insert(m.material);
  for (const Sphere& s : scene.spheres) used.insert(s.material);
  for (const Plane& p : scene.planes) used.insert(p.material);
  return {used.begin(), used.end()};
}

}  // namespace

VectorHeader scene_request_header(const Scene& scene, std::vector<std::int32_t>* header_of) {
  VectorHeader h = scene_vector_header(scene);
  const std::vector<VectorMaterial> all = std::move(h.materials);
  h.materials.clear();
  if (header_of) header_of->assign(scene.materials.size(), -1);
  for (std::uint32_t m : used_materials(scene)) {
    if (header_of) (*header_of)[m] = static_cast<std::int32_t>(h.materials.size());
    h.materials.push_back(all[m]);
  }
  return h;
}

RenderResult render_scene(const Scene& scene, const RenderOptions& options) {
  if (options.tile_rows < 1) throw std::invalid_argument("render: tile_rows must be >= 1");
  const int width = scene.camera.width, height = scene.camera.height;
  const std::size_t lights = scene.lights.size();
  RenderResult out;
  out.scene_name = scene.name;
  out.width = width;
  out.height = height;

  const std::vector<std::uint32_t> used = used_materials(scene);
  std::vector<std::int32_t> header_of;
  const VectorHeader header = scene_request_header(scene, &header_of);
  std::vector<UnitSpec> specs = options.units;
  if (specs.empty())
    for (const std::string& name : unit_names()) specs.push_back(parse_unit_spec(name));
  Evaluator ev(header, specs, 8, options.slot_capacity);
  const SlotMap& slots = ev.slots();
  const std::size_t n_units = ev.units().size();
  std::set<std::string> lobes;
  for (const SceneMaterial& m : scene.materials) out.materials.push_back(m.name);
  for (std::size_t l = 0; l < lights; ++l)
    out.lights.push_back(scene.lights[l].name.empty() ? fmt::format("light {}", l)
                                                      : scene.lights[l].name);
  for (std::uint32_t m : used) {
    out.used_materials.push_back(scene.materials[m].name);
    lobes.insert(to_string(scene.materials[m].lobe));
  }
  out.lobes.assign(lobes.begin(), lobes.end());
  out.skips.assign(lights, std::vector<SkipCounts>(scene.materials.size()));

  const SceneTracer tracer(scene);
  // Images: reference, reference specular, skip-only, skip mask, and per unit image + specular.
  out.reference = Image8(width, height);
  out.reference_specular = Image8(width, height);
  out.skip_only = Image8(width, height);
  out.skip_mask = Image8(width, height);
  std::vector<Image8> unit_image(n_units, Image8(width, height));
  std::vector<Image8> unit_specular(n_units, Image8(width, height));
  std::vector<std::vector<std::uint8_t>> unit_error(
      n_units, std::vector<std::uint8_t>(static_cast<std::size_t>(width) * height));
  std::vector<ImageErrorAccumulator> unit_acc(n_units);
  ImageErrorAccumulator skip_acc;
  std::vector<double> ulp(n_units);
  for (std::size_t u = 0; u < n_units; ++u) ulp[u] = ev.units()[u]->out_format().ulp();

  const int tile_rows = std::min(options.tile_rows, height);
  std::vector<SurfaceSample> samples(static_cast<std::size_t>(tile_rows) * width);
  std::vector<VectorRow> rows;
  std::vector<std::uint32_t> row_pixel;  // the tile pixel of each request
  BatchResults results;
  // Sources of specular light: 0 the reference, 1 the reference with the skip alone, 2+u unit u.
  const std::size_t sources = 2 + n_units;
  TileBuffers tile;
  for (int y0 = 0; y0 < height; y0 += tile_rows) {
    const int y1 = std::min(height, y0 + tile_rows);
    const std::size_t pixels = static_cast<std::size_t>(y1 - y0) * width;
    parallel_for(static_cast<std::size_t>(y1 - y0), options.threads, [&](std::size_t r) {
      tracer.trace_rows(y0 + static_cast<int>(r), y0 + static_cast<int>(r) + 1,
                        samples.data() + r * width);
    });

    // One request per visible pixel and light facing it; the diffuse term needs no unit.
    tile.diffuse.assign(pixels, Rgb{});
    tile.skip.assign(pixels, PixelSkip::kBackground);
    tile.peak.assign(pixels, 0.0);
    rows.clear();
    row_pixel.clear();
    for (std::size_t p = 0; p < pixels; ++p) {
      const SurfaceSample& s = samples[p];
      if (!s.hit) {
        tile.diffuse[p] = scene.background;
        continue;
      }
      const SceneMaterial& mat = scene.materials[s.material];
      tile.diffuse[p] = Rgb{scene.ambient.r * mat.diffuse.r, scene.ambient.g * mat.diffuse.g,
                            scene.ambient.b * mat.diffuse.b};
      tile.skip[p] = PixelSkip::kZero;
      for (std::size_t l = 0; l < lights; ++l) {
        tile.peak[p] += c_y(scene.lights[l].intensity, mat.specular);
        const LightSample ls = light_sample(scene, s, l);
        if (ls.n_dot_l <= 0) {
          ++out.skips[l][s.material].facing_away;
          continue;
        }
        const Rgb& i = scene.lights[l].intensity;
        add_scaled(tile.diffuse[p],
                   Rgb{i.r * mat.diffuse.r, i.g * mat.diffuse.g, i.b * mat.diffuse.b}, ls.n_dot_l);
        VectorRow row;
        // Rounding can leave |t| a hair above 1 for unit vectors; the lobe peaks at t = 1.
        row.t = std::clamp(mat.lobe == Lobe::kPhong ? ls.t_phong : ls.t_blinn, -1.0, 1.0);
        row.material = static_cast<std::uint32_t>(header_of[s.material]);
        row.light = static_cast<std::int32_t>(l);
        row.x = static_cast<std::int32_t>(p % width);
        row.y = y0 + static_cast<std::int32_t>(p / width);
        rows.push_back(row);
        row_pixel.push_back(static_cast<std::uint32_t>(p));
      }
    }

    if (options.on_requests) options.on_requests(rows.data(), rows.size());
    ev.add_batch(rows.data(), rows.size(), results, options.threads);
    out.requests += rows.size();

    tile.specular.assign(sources, std::vector<Rgb>(pixels, Rgb{}));
    for (std::size_t k = 0; k < rows.size(); ++k) {
      const VectorRow& row = rows[k];
      const std::size_t p = row_pixel[k];
      const std::uint32_t scene_mat = samples[p].material;
      const Rgb& ks = scene.materials[scene_mat].specular;
      const Rgb& i = scene.lights[static_cast<std::size_t>(row.light)].intensity;
      const Rgb colour{ks.r * i.r, ks.g * i.g, ks.b * i.b};
      const MaterialParams& params = slots.params[slots.slot(row)];
      SkipCounts& counts = out.skips[static_cast<std::size_t>(row.light)][scene_mat];
      const bool tau_skip = params.always_skip || row.t <= params.tau;
      if (row.t <= 0) {
        ++counts.zero;
      } else if (tau_skip) {
        ++counts.tau;
        if (tile.skip[p] == PixelSkip::kZero) tile.skip[p] = PixelSkip::kTau;
      } else {
        ++counts.computed;
        tile.skip[p] = PixelSkip::kComputed;
      }
      add_scaled(tile.specular[0][p], colour, results.reference[k]);
      if (!tau_skip && row.t > 0) add_scaled(tile.specular[1][p], colour, results.reference[k]);
      for (std::size_t u = 0; u < n_units; ++u) {
        const std::size_t at = u * rows.size() + k;
        add_scaled(tile.specular[2 + u][p], colour, static_cast<double>(results.raw[at]) * ulp[u]);
      }
    }

    // Final 8-bit pixels, their errors against the reference, in raster order.
    for (std::size_t p = 0; p < pixels; ++p) {
      const int x = static_cast<int>(p % width), y = y0 + static_cast<int>(p / width);
      const auto final_of = [&](std::size_t src) {
        const Rgb& d = tile.diffuse[p];
        const Rgb& s = tile.specular[src][p];
        return to_srgb8(Rgb{d.r + s.r, d.g + s.g, d.b + s.b});
      };
      const Rgb8 ref = final_of(0);
      const Rgb8 ref_spec = to_srgb8(tile.specular[0][p]);
      out.reference.set(x, y, ref);
      out.reference_specular.set(x, y, ref_spec);
      const Rgb8 skip_only = final_of(1);
      out.skip_only.set(x, y, skip_only);
      // The highlight's extent and core are levels relative to the material's peak (10 % and
      // 50 %), not "8-bit code above 0" or "above eps": sRGB's steep toe makes a lobe of 1e-3 code
      // 3, and the threshold may drop up to eps per pixel (eps/K for each of K lights), so any
      // level near eps would measure the skip rather than the shape.
      const auto highlight = [&](std::size_t src) {
        const double y = luminance(tile.specular[src][p]);
        return ImageErrorAccumulator::Highlight{y > 0 && y >= 0.1 * tile.peak[p],
                                                y > 0 && y >= 0.5 * tile.peak[p]};
      };
      const auto ref_hl = highlight(0);
      skip_acc.add(ref, skip_only, ref_hl, highlight(1));
      static constexpr Rgb8 kZeroColour{20, 30, 110}, kTauColour{90, 170, 255};
      const std::uint8_t grey =
          static_cast<std::uint8_t>((ref[0] * 54 + ref[1] * 183 + ref[2] * 19) >> 8);
      switch (tile.skip[p]) {
        case PixelSkip::kBackground:
          out.skip_mask.set(x, y, {0, 0, 0});
          break;
        case PixelSkip::kZero:
          out.skip_mask.set(x, y, kZeroColour);
          break;
        case PixelSkip::kTau:
          out.skip_mask.set(x, y, kTauColour);
          break;
        case PixelSkip::kComputed:
          out.skip_mask.set(x, y, {grey, grey, grey});
          break;
      }
      for (std::size_t u = 0; u < n_units; ++u) {
        const Rgb8 img = final_of(2 + u);
        const Rgb8 spec = to_srgb8(tile.specular[2 + u][p]);
        unit_image[u].set(x, y, img);
        unit_specular[u].set(x, y, spec);
        unit_error[u][static_cast<std::size_t>(y) * width + x] =
            static_cast<std::uint8_t>(unit_acc[u].add(ref, img, ref_hl, highlight(2 + u)));
      }
    }
    if (options.progress) std::fprintf(stderr, "\rrender: %d/%d rows", y1, height);
  }
  if (options.progress) std::fprintf(stderr, "\n");

  out.skip_only_error = skip_acc.result();
  const std::vector<UnitStats> stats = ev.stats();
  for (std::size_t u = 0; u < n_units; ++u) {
    UnitRender r;
    r.label = stats[u].name;
    r.spec = stats[u].spec;
    r.image = std::move(unit_image[u]);
    r.specular = std::move(unit_specular[u]);
    r.error = unit_acc[u].result();
    r.stats = stats[u];
    r.cost = unit_cost(*ev.units()[u]);
    r.skipped = stats[u].skipped;
    r.computed = stats[u].vectors - stats[u].skipped;
    // Each heat map on its own scale (at least 1 LSB): a shared one would paint a 1-LSB unit
    // black beside a 60-LSB one. The scale is drawn in and reported.
    r.heatmap_scale = std::max(1.0, r.error.max_lsb);
    const std::vector<double> lsb(unit_error[u].begin(), unit_error[u].end());
    r.heatmap =
        heatmap_with_scale(lsb, width, height, r.heatmap_scale, r.label + " error, 8-bit LSB");
    out.units.push_back(std::move(r));
  }
  out.slots = nlohmann::json::array();
  for (std::size_t s = 0; s < slots.params.size(); ++s) {
    const MaterialParams& p = slots.params[s];
    out.slots.push_back({{"name", p.name},
                         {"lobe", to_string(slots.lobe[s])},
                         {"shininess", p.shininess},
                         {"c_y", slots.c_y[s]},
                         {"tau", p.tau},
                         {"always_skip", p.always_skip}});
  }
  std::vector<std::pair<std::string, const Image8*>> tiles{
      {"reference", &out.reference},
      {"reference specular", &out.reference_specular},
      {"skip mask (light blue: tau, dark: t<=0)", &out.skip_mask}};
  for (const UnitRender& r : out.units) {
    tiles.emplace_back(r.label, &r.image);
    tiles.emplace_back(r.label + " specular", &r.specular);
    tiles.emplace_back(r.label + " error", &r.heatmap);
  }
  out.contact_sheet = contact_sheet(tiles, 3);
  return out;
}

}  // namespace glint
