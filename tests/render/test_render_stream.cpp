// A render's image modes: streamed PNGs (kStream, what glint render writes) are byte for byte the
// PNGs of the kept images (kKeep) for any thread count and tile height, contact sheet included;
// a render without images (kNone, sweeps) gives the same figures; and the memory rules order as
// the modes do.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "render/render.h"
#include "scene/scene.h"
#include "units/catalogue.h"

namespace glint {
namespace {

using Bytes = std::vector<std::uint8_t>;

// Wider than the contact sheet's tiles (factor 3), so the streamed sheet is reduced strip by strip.
Scene wide_scene() {
  Scene scene = load_scene(std::string(GLINT_SOURCE_DIR) + "/traces/scenes/multi.json");
  scene.camera.width = 1300;
  scene.camera.height = 47;
  return scene;
}

RenderOptions options(RenderImages images, int threads, int tile_rows) {
  RenderOptions o;
  o.units = {parse_unit_spec("pow"), parse_unit_spec("hast:d=3"), parse_unit_spec("hast")};
  o.images = images;
  o.threads = threads;
  o.tile_rows = tile_rows;
  return o;
}

// Every PNG in render_file_names order (report.json left out).
std::vector<Bytes> kept_pngs(const RenderResult& r) {
  std::vector<Bytes> out{encode_png(r.reference), encode_png(r.reference_specular),
                         encode_png(r.skip_mask)};
  for (const Image8& mask : r.light_skip_masks) out.push_back(encode_png(mask));
  out.push_back(encode_png(r.skip_only));
  for (const UnitRender& u : r.units) {
    out.push_back(encode_png(u.image));
    out.push_back(encode_png(u.specular));
    out.push_back(encode_png(u.heatmap));
  }
  out.push_back(encode_png(r.legend));
  out.push_back(encode_png(r.contact_sheet));
  return out;
}

struct Streamed {
  RenderResult result;
  std::vector<Bytes> files;
};

Streamed stream(const Scene& scene, int threads, int tile_rows) {
  Streamed s;
  RenderOptions o = options(RenderImages::kStream, threads, tile_rows);
  s.files.resize(render_file_names(render_unit_labels(o.units), render_light_names(scene)).size() -
                 1);
  for (Bytes& file : s.files)
    o.png_sinks.emplace_back([&file](const std::uint8_t* data, std::size_t n) {
      file.insert(file.end(), data, data + n);
    });
  s.result = render_scene(scene, o);
  return s;
}

TEST(RenderStream, SameBytesAsTheKeptImagesForAnyThreadsAndTiles) {
  const Scene scene = wide_scene();
  const RenderResult kept = render_scene(scene, options(RenderImages::kKeep, 1, 16));
  const std::vector<Bytes> expected = kept_pngs(kept);
  for (const auto& [threads, tile_rows] : std::vector<std::pair<int, int>>{{1, 16}, {2, 7}}) {
    SCOPED_TRACE(std::to_string(threads) + " threads, tiles of " + std::to_string(tile_rows));
    const Streamed s = stream(scene, threads, tile_rows);
    ASSERT_EQ(s.files.size(), expected.size());
    for (std::size_t i = 0; i < expected.size(); ++i)
      EXPECT_TRUE(s.files[i] == expected[i]) << render_file_names(s.result)[i];
    EXPECT_EQ(s.result.to_json().dump(), kept.to_json().dump());
    // Nothing kept: the images went to the sinks.
    EXPECT_TRUE(s.result.reference.pixels.empty());
    EXPECT_TRUE(s.result.units[0].image.pixels.empty());
    EXPECT_TRUE(s.result.contact_sheet.pixels.empty());
    EXPECT_TRUE(s.result.legend.pixels.empty());
    EXPECT_TRUE(s.result.light_skip_masks.empty());
  }
}

TEST(RenderStream, WrongNumberOfSinksIsRefused) {
  RenderOptions o = options(RenderImages::kStream, 1, 16);
  o.png_sinks.resize(3, [](const std::uint8_t*, std::size_t) {});
  EXPECT_THROW(render_scene(wide_scene(), o), std::logic_error);
}

TEST(RenderNoImages, SameFiguresWithoutImages) {
  const Scene scene = wide_scene();
  const RenderResult kept = render_scene(scene, options(RenderImages::kKeep, 1, 16));
  const RenderResult none = render_scene(scene, options(RenderImages::kNone, 2, 5));
  EXPECT_EQ(none.to_json().dump(), kept.to_json().dump());
  EXPECT_TRUE(none.reference.pixels.empty());
  EXPECT_TRUE(none.units[1].heatmap.pixels.empty());
  EXPECT_TRUE(none.contact_sheet.pixels.empty());
}

TEST(RenderMemory, StreamingNeedsLessThanKeepingAndNoImagesLeast) {
  const std::uint64_t pixels = 3840ull * 2160;
  EXPECT_LT(render_bytes(pixels, 5, RenderImages::kStream),
            render_bytes(pixels, 5, RenderImages::kKeep));
  EXPECT_EQ(render_bytes(pixels, 5, RenderImages::kNone), 0u);
  // The stated rule of glint render (kStream) keeps a 4K render of the default units on two
  // threads under 400 MB; more threads draw more heat maps at once.
  EXPECT_LT(render_bytes(pixels, default_unit_names().size(), RenderImages::kStream, 2),
            400ull << 20);
  EXPECT_GT(render_bytes(pixels, 5, RenderImages::kStream, 4),
            render_bytes(pixels, 5, RenderImages::kStream, 2));
  EXPECT_EQ(render_bytes(pixels, 5, RenderImages::kStream, 5),
            render_bytes(pixels, 5, RenderImages::kStream, 50));
}

}  // namespace
}  // namespace glint
