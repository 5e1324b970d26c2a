// glint render: deterministic images and report (any thread count, any tile height), a golden of
// the small scene, only the scene's materials elaborated, the files written, and the image-level
// error figures checked against the images themselves.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "render/render.h"
#include "scene/scene.h"
#include "test_support.h"
#include "units/catalogue.h"

namespace glint {
namespace {

std::string scene_path(const std::string& name) {
  return std::string(GLINT_SOURCE_DIR) + "/traces/scenes/" + name;
}

RenderResult render(const Scene& scene, int threads, int tile_rows = 16,
                    const std::vector<std::string>& units = {}) {
  RenderOptions o;
  for (const auto& u : units) o.units.push_back(parse_unit_spec(u));
  o.threads = threads;
  o.tile_rows = tile_rows;
  return render_scene(scene, o);
}

std::vector<std::vector<std::uint8_t>> all_png(const RenderResult& r) {
  std::vector<std::vector<std::uint8_t>> out{
      encode_png(r.reference), encode_png(r.reference_specular),
      encode_png(r.skip_mask), encode_png(r.skip_only),
      encode_png(r.legend),    encode_png(r.contact_sheet)};
  for (const Image8& mask : r.light_skip_masks) out.push_back(encode_png(mask));
  for (const UnitRender& u : r.units) {
    out.push_back(encode_png(u.image));
    out.push_back(encode_png(u.specular));
    out.push_back(encode_png(u.heatmap));
  }
  return out;
}

TEST(Render, SameBytesForAnyThreadCountAndTileHeight) {
  Scene scene = load_scene(scene_path("multi.json"));
  scene.camera.width = 120;
  scene.camera.height = 90;
  const RenderResult a = render(scene, 1, 16);
  const RenderResult b = render(scene, 2, 7);
  const RenderResult c = render(scene, 3, 90);
  EXPECT_EQ(a.to_json().dump(), b.to_json().dump());
  EXPECT_EQ(a.to_json().dump(), c.to_json().dump());
  EXPECT_TRUE(all_png(a) == all_png(b));
  EXPECT_TRUE(all_png(a) == all_png(c));
}

// The golden: traces/golden/scenes/small/ holds the small scene's images and report as
// `glint render traces/scenes/small.json -o traces/golden/scenes/small` wrote them. A change in
// any unit's bits, the ray caster, the image code or the report shows here.
TEST(Render, SmallSceneMatchesItsGolden) {
  const RenderResult r = render(load_scene(scene_path("small.json")), 2);
  test::TempDir dir;
  write_render(r, dir.path().string());
  const std::filesystem::path golden =
      std::filesystem::path(GLINT_SOURCE_DIR) / "traces/golden/scenes/small";
  for (const std::string& name : render_file_names(r)) {
    SCOPED_TRACE(name);
    ASSERT_TRUE(std::filesystem::exists(golden / name));
    EXPECT_TRUE(test::read_file((golden / name).string()) == test::read_file(dir.file(name)))
        << "regenerate with: glint render traces/scenes/small.json -o traces/golden/scenes/small";
  }
}

TEST(Render, WritesEveryFileItNames) {
  Scene scene = load_scene(scene_path("small.json"));
  const RenderResult r = render(scene, 2, 16, {"pow", "hast:d=3"});
  test::TempDir dir;
  write_render(r, dir.path().string());
  std::vector<std::string> names = render_file_names(r);
  std::sort(names.begin(), names.end());
  EXPECT_EQ(dir.entries(), names);
  EXPECT_EQ(r.units.size(), 2u);
  EXPECT_EQ(r.units[1].label, "hast");
}

// Only the materials objects use get slots: an extra, unused material elaborates nothing.
TEST(Render, UnusedMaterialsGetNoSlot) {
  Scene scene = load_scene(scene_path("small.json"));
  scene.camera.width = 32;
  scene.camera.height = 24;
  const std::size_t before = render(scene, 1, 16, {"lut"}).slots.size();
  SceneMaterial extra = scene.materials.front();
  extra.name = "unused";
  extra.shininess = 999;
  scene.materials.push_back(extra);
  const RenderResult r = render(scene, 1, 16, {"lut"});
  EXPECT_EQ(r.slots.size(), before);
  for (const auto& s : r.slots)
    EXPECT_EQ(s["name"].get<std::string>().find("unused"), std::string::npos);
  EXPECT_EQ(scene_request_header(scene).materials.size(), r.used_materials.size());
}

// The image-level figures against the images: max and differing fraction recomputed from the
// pixels; the reference's own error is zero; the pow unit stays close to the reference.
TEST(Render, ImageErrorMatchesThePixels) {
  Scene scene = load_scene(scene_path("multi.json"));
  scene.camera.width = 96;
  scene.camera.height = 72;
  const RenderResult r = render(scene, 2);
  for (const UnitRender& u : r.units) {
    SCOPED_TRACE(u.label);
    int max = 0;
    std::uint64_t differing = 0, lit = 0, ref_lit = 0;
    for (int y = 0; y < r.height; ++y)
      for (int x = 0; x < r.width; ++x) {
        const Rgb8 a = r.reference.at(x, y), b = u.image.at(x, y);
        int worst = 0;
        for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(a[c] - b[c]));
        max = std::max(max, worst);
        differing += worst > 0;
        const Rgb8 s = u.specular.at(x, y), rs = r.reference_specular.at(x, y);
        lit += (s[0] | s[1] | s[2]) != 0;
        ref_lit += (rs[0] | rs[1] | rs[2]) != 0;
      }
    EXPECT_EQ(u.error.max_lsb, max);
    EXPECT_DOUBLE_EQ(u.error.differing_fraction,
                     static_cast<double>(differing) / (r.width * r.height));
    // A tenth of a material's peak is well above sRGB code 0: every highlight pixel is lit in 8
    // bits.
    EXPECT_LE(u.error.highlight_pixels, lit);
    EXPECT_GT(u.error.highlight_pixels, 0u);
    EXPECT_GT(ref_lit, 0u);
    EXPECT_EQ(u.stats.vectors, r.requests);
  }
  EXPECT_LE(r.units.front().error.max_lsb, 2.0);  // pow: correctly rounded t^n, within 2 LSB
}

using test::CliRun;

CliRun glint_cli(const test::TempDir& dir, const std::string& args) {
  return test::run_glint(dir.path(), args);
}

// The scene's requests written as a vector file give `glint eval` exactly the accuracy figures
// the render reported: one stream, in memory or through a file.
TEST(RenderCli, WrittenVectorsEvaluateToTheSameFigures) {
  test::TempDir dir;
  const CliRun r = glint_cli(dir, "render '" + scene_path("small.json") +
                                      "' -o out --write-vectors small.vec --json --unit pow "
                                      "--unit hast:d=3 --unit horner");
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json render = nlohmann::json::parse(r.out);
  const CliRun e = glint_cli(dir, "eval small.vec --json --unit pow --unit hast:d=3 --unit horner");
  ASSERT_EQ(e.status, 0) << e.err;
  const nlohmann::json eval = nlohmann::json::parse(e.out);
  ASSERT_EQ(eval.at("units").size(), 3u);
  EXPECT_EQ(eval.at("rows"), render.at("requests"));
  for (std::size_t u = 0; u < 3; ++u) {
    const auto& a = render.at("units")[u];
    const auto& b = eval.at("units")[u];
    EXPECT_EQ(a.at("skipped"), b.at("skipped"));
    EXPECT_EQ(a.at("errors").dump(), b.at("errors").dump()) << a.at("unit");
  }
}

TEST(RenderCli, BadSceneIsExitTwoNamingTheFieldAndWritesNothing) {
  test::TempDir dir;
  std::string text = test::read_file(scene_path("small.json"));
  const auto at = text.find("\"shininess\"");
  ASSERT_NE(at, std::string::npos);
  text.insert(text.find_first_of("0123456789", at), "-");  // shininess: -N
  std::ofstream(dir.file("bad.json"), std::ios::trunc) << text;
  const CliRun r = glint_cli(dir, "render bad.json -o out");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("bad.json"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("shininess"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("out")));
}

TEST(RenderCli, OutputFolderThatIsAFileIsExitTwo) {
  test::TempDir dir;
  std::ofstream(dir.file("out")) << "keep";
  const CliRun r = glint_cli(dir, "render '" + scene_path("small.json") + "' -o out --unit lut");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(test::read_file(dir.file("out")), "keep");
}

// --chip ram:materials=N,slots=N: a chip of fixed capacity; a scene that needs more is refused
// before anything is written, a larger chip costs more area and changes no pixel.
TEST(RenderSlots, FixedCapacityChip) {
  Scene scene = load_scene(scene_path("multi.json"));
  scene.camera.width = 48;
  scene.camera.height = 36;
  RenderOptions o;
  o.units = {parse_unit_spec("lut")};
  const RenderResult fit = render_scene(scene, o);
  const std::size_t needed = fit.slots.size();
  const auto chip = [](std::size_t n) {
    return "ram:materials=" + std::to_string(n) + ",slots=" + std::to_string(n);
  };
  o.chip = parse_chip(chip(needed - 1));
  EXPECT_THROW(render_scene(scene, o), SlotCapacityError);
  o.chip = parse_chip(chip(needed + 16));
  const RenderResult big = render_scene(scene, o);
  EXPECT_GT(big.units[0].cost.area_ge, fit.units[0].cost.area_ge);
  EXPECT_TRUE(encode_png(big.units[0].image) == encode_png(fit.units[0].image));

  test::TempDir dir;
  const CliRun r =
      glint_cli(dir, "render '" + scene_path("multi.json") + "' -o out --chip " + chip(needed - 1));
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--chip " + chip(needed - 1)), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("out")));
}

// Large renders get a contact sheet of reduced tiles (the files keep full size); an error is kept
// in its reduced heat map by the block maximum.
TEST(RenderSheet, LargeImagesAreReducedOnTheSheet) {
  Scene scene = load_scene(scene_path("small.json"));
  scene.camera.width = 1290;
  scene.camera.height = 60;
  RenderOptions o;
  o.units = {parse_unit_spec("schlick")};
  const RenderResult r = render_scene(scene, o);
  EXPECT_EQ(r.units[0].image.width, 1290);
  EXPECT_EQ(r.units[0].heatmap.width, 1290);  // the scale is in legend.png, not beside the map
  // Factor 3: tiles of 430 pixels, every one.
  EXPECT_EQ(r.contact_sheet.width, 3 * 430 + 4 * 8);
}

TEST(Downscale, BlockMeanRounded) {
  Image8 img(4, 3, {0, 0, 0});
  img.set(0, 0, {9, 0, 255});
  img.set(1, 1, {0, 3, 255});
  const Image8 d = downscale(img, 2);
  ASSERT_EQ(d.width, 2);
  ASSERT_EQ(d.height, 2);
  EXPECT_EQ(d.at(0, 0), (Rgb8{2, 1, 128}));  // (9 + 2) / 4, (3 + 2) / 4, (510 + 2) / 4
  EXPECT_EQ(d.at(0, 1), (Rgb8{0, 0, 0}));    // an edge block of two pixels
  EXPECT_THROW(downscale(img, 0), std::invalid_argument);
}

}  // namespace
}  // namespace glint
