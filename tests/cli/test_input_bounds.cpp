// Every input bounded before it is read, and non-finite coordinates refused (issue 29, item 3;
// src/cli/README.md "Limits and guarantees"): OBJ and patch files have a byte cap checked before
// reading and counts checked line by line; an OBJ's nan/inf/overflowing coordinates are refused
// with their line (tinyobjloader alone reads them as 0); a sweep and a render are refused before
// work beyond their memory rule, naming the limit, exit 2, no output left.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "eval/evaluate.h"
#include "fixed/fixed_point.h"
#include "io/input_error.h"
#include "render/render.h"
#include "scene/bezier.h"
#include "scene/mesh_file.h"
#include "scene/obj_mesh.h"
#include "scene/scene.h"
#include "sweep/grid.h"
#include "sweep/memory.h"
#include "test_support.h"

namespace glint {
namespace {

namespace fs = std::filesystem;
using glint::test::TempDir;

const std::string kSource = GLINT_SOURCE_DIR;

class Bounds : public ::testing::Test {
 protected:
  std::string write(const std::string& name, const std::string& text) const {
    const std::string path = dir_.file(name);
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }
  // A sparse file of `bytes` bytes: costs no disk.
  std::string sparse(const std::string& name, std::uint64_t bytes) const {
    const std::string path = write(name, "");
    fs::resize_file(path, bytes);
    return path;
  }
  glint::test::CliRun glint(const std::string& args) const {
    return glint::test::run_glint(dir_.path(), args);
  }
  TempDir dir_;
};

template <class F>
std::optional<InputError> input_error(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e;
  }
  return std::nullopt;
}

void expect_refusal(const std::optional<InputError>& e, const std::string& file, std::uint64_t line,
                    const std::string& field, const std::string& needle) {
  ASSERT_TRUE(e.has_value()) << "accepted";
  EXPECT_EQ(e->file(), file) << e->what();
  EXPECT_EQ(e->line(), line) << e->what();
  EXPECT_EQ(e->field(), field) << e->what();
  EXPECT_NE(e->message().find(needle), std::string::npos) << e->what();
}

constexpr const char* kTriangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvt 0 0\n";

TEST_F(Bounds, ObjNonFiniteCoordinatesAreRefusedWithTheirLine) {
  for (const char* bad : {"nan", "NaN", "inf", "-inf", "Infinity", "1e999", "-1e999", "abc"}) {
    for (const char* field : {"v", "vn", "vt"}) {
      SCOPED_TRACE(std::string(field) + " " + bad);
      // The bad value on line 6, after a valid triangle's lines.
      const std::string line = std::string(field) + " 0.5 " + bad + (field[1] == 't' ? "" : " 1");
      const std::string path =
          write("m.obj", std::string(kTriangle) + line + "\nf 1/1/1 2/1/1 3/1/1\n");
      expect_refusal(input_error([&] { load_obj_mesh(path, 100); }), path, 6, field,
                     bad[0] == 'a'                                       ? "not a number"
                     : std::string(bad).find("999") != std::string::npos ? "out of the range"
                                                                         : "must be finite");
    }
  }
  // The same file with finite values loads.
  const std::string good = write("m.obj", std::string(kTriangle) + "f 1/1/1 2/1/1 3/1/1\n");
  EXPECT_EQ(load_obj_mesh(good, 100).faces.size(), 1u);
  // Too few coordinates are refused too (tinyobjloader would make them 0).
  const std::string short_v = write("m.obj", "v 1 2\n");
  expect_refusal(input_error([&] { load_obj_mesh(short_v, 100); }), short_v, 1, "v",
                 "expected \"v x y z\"");
}

TEST_F(Bounds, ObjNanThroughASceneNamesTheObjLine) {
  write("n.obj", "v nan nan nan\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\n");
  nlohmann::json s =
      nlohmann::json::parse(glint::test::read_file(kSource + "/traces/scenes/small.json"));
  s["objects"] = {{{"type", "mesh"}, {"file", "n.obj"}, {"material", "red"}}};
  const std::string scene = write("scene.json", s.dump());
  expect_refusal(input_error([&] { load_scene(scene); }), dir_.file("n.obj"), 1, "v",
                 "must be finite, got 'nan'");
  const auto run = glint("render scene.json --unit pow -o out");
  EXPECT_EQ(run.status, 2) << run.err;
  EXPECT_NE(run.err.find("n.obj:1: field 'v': value must be finite"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(dir_.path() / "out"));
}

TEST_F(Bounds, ObjByteCapBeforeReading) {
  // Beyond the real cap, as a sparse file: refused by its size, nothing read (a read would meet
  // NUL bytes at line 1 instead).
  const std::string big = sparse("big.obj", kSceneMaxObjBytes + 1);
  expect_refusal(input_error([&] { load_obj_mesh(big, 100); }), big, 0, "file",
                 "more than the limit of " + std::to_string(kSceneMaxObjBytes) + " bytes");
  // A file at a test-only lower cap: at the cap it loads, one byte more is refused.
  const std::string text = std::string(kTriangle) + "f 1/1/1 2/1/1 3/1/1\n";
  const std::string path = write("m.obj", text);
  EXPECT_EQ(load_obj_mesh(path, 100, ObjLimits{text.size(), 100}).faces.size(), 1u);
  expect_refusal(input_error([&] {
                   load_obj_mesh(path, 100, ObjLimits{text.size() - 1, 100});
                 }),
                 path, 0, "file", "more than the limit of " + std::to_string(text.size() - 1));
}

TEST_F(Bounds, ObjTriangleAndVertexCapsWhileStreaming) {
  // Four triangles (a quad and two triangles): the face that crosses a cap of 3 is named.
  const std::string path = write("m.obj",
                                 "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\n"
                                 "f 1//1 2//1 3//1 4//1\nf 1//1 2//1 3//1\nf 1//1 3//1 4//1\n");
  EXPECT_EQ(load_obj_mesh(path, 4).faces.size(), 4u);
  expect_refusal(input_error([&] { load_obj_mesh(path, 3); }), path, 8, "f",
                 "more than 3 triangles");
  // Vertex lines beyond a test-only cap of 3: the fourth v line.
  expect_refusal(input_error([&] {
                   load_obj_mesh(path, 100, ObjLimits{kSceneMaxObjBytes, 3});
                 }),
                 path, 4, "v", "more than 3 'v' lines");
  // A line beyond 4096 bytes is refused without reading it to its end.
  const std::string longer = write("l.obj", "v 1 2 3" + std::string(5000, ' ') + "\n");
  expect_refusal(input_error([&] { load_obj_mesh(longer, 100); }), longer, 1, "line", "4096");
}

TEST_F(Bounds, PatchFileByteCapAndNonFinitePoints) {
  const std::string big = sparse("big.bpt", kSceneMaxPatchFileBytes + 1);
  expect_refusal(input_error([&] { read_bezier_patches(big); }), big, 0, "file",
                 "more than the limit of " + std::to_string(kSceneMaxPatchFileBytes) + " bytes");
  for (const char* bad : {"nan", "NaN", "inf", "-inf", "1e999"}) {
    SCOPED_TRACE(bad);
    const std::string path = write("p.bpt", std::string("1\n3 3\n0 0 ") + bad + "\n");
    expect_refusal(input_error([&] { read_bezier_patches(path); }), path, 3, "point",
                   bad[1] == 'e' ? "out of the range" : "must be finite");
  }
  // A long line is refused at its line, before it is read whole.
  const std::string longer = write("l.bpt", "1\n" + std::string(10000, '#') + "\n");
  expect_refusal(input_error([&] { read_bezier_patches(longer); }), longer, 2, "line", "4096");
}

TEST_F(Bounds, SceneJsonOverflowIsRefusedAtItsLine) {
  // nlohmann refuses a literal beyond a double (it would be inf) without a position; the error
  // still names its line.
  nlohmann::json s =
      nlohmann::json::parse(glint::test::read_file(kSource + "/traces/scenes/small.json"));
  s["objects"][1]["radius"] = 12345;
  std::string text = s.dump(2);
  const auto at = text.find("12345");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 5, "1e999");
  const auto line =
      static_cast<std::uint64_t>(std::count(text.begin(), text.begin() + at, '\n')) + 1;
  ASSERT_GT(line, 1u);
  const std::string scene = write("scene.json", text);
  expect_refusal(input_error([&] { load_scene(scene); }), scene, line, "json",
                 "number overflow parsing '1e999'");
}

TEST_F(Bounds, SweepMemoryIsBoundedBeforeWork) {
  // The rule: 15 KB per slot plus 40 bytes per input code of the memo, 2^F + 1 codes.
  const UnitSpec hast{"hast", {}};
  EXPECT_EQ(sweep_config_bytes(hast, 7), 7 * (kSweepBytesPerSlot + 40 * ((1u << 15) + 1)));
  EXPECT_EQ(sweep_config_bytes(hast, 100), 100 * kSweepBytesPerSlot);  // not memoised
  const UnitSpec narrow{"hast", {{"in", "uq1.11"}}};
  EXPECT_EQ(sweep_config_bytes(narrow, 1), kSweepBytesPerSlot + 40 * ((1u << 11) + 1));
  // The case: 100 000 configurations on the smallest trace, refused up front.
  const auto run = glint("sweep " + kSource +
                         "/traces/hard_cases.vec --grid "
                         "'hast:d=1..10,guard=0..9,buffer=4..103,skip=on|off,"
                         "in=uq1.15|uq1.14|uq1.13|uq1.12|uq1.11' -o s.json --csv s.csv");
  EXPECT_EQ(run.status, 2) << run.err;
  EXPECT_NE(run.err.find("glint: --grid: 100000 configurations over the input's 7 slots may take "
                         "more than the limit of 4096 MiB"),
            std::string::npos)
      << run.err;
  EXPECT_EQ(dir_.entries(), std::vector<std::string>{});
  // Just below the limit by the rule it runs; the first configuration past it is named.
  const std::uint64_t per = sweep_config_bytes(hast, 7);
  const std::size_t fits = kMaxSweepBytes / per;
  std::vector<SweepConfig> configs(fits, SweepConfig{0, 0, "hast", hast});
  EXPECT_NO_THROW(check_sweep_memory(configs, 7));
  configs.push_back(SweepConfig{fits, 0, "hast", hast});
  try {
    check_sweep_memory(configs, 7);
    ADD_FAILURE() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("configuration " + std::to_string(fits)),
              std::string::npos)
        << e.what();
  }
}

TEST_F(Bounds, EvalMemosAreBoundedBeforeWork) {
  // The memo's rule: 40 bytes per code, 2^F + 1 codes per slot, none beyond 16 bits or 2^22
  // codes per lane.
  EXPECT_EQ(memo_bytes(parse_q_format("uq1.15"), 64), 40ull * 32769 * 64);
  EXPECT_EQ(memo_bytes(parse_q_format("uq1.11"), 1), 40ull * 2049);
  EXPECT_EQ(memo_bytes(parse_q_format("uq1.15"), 65), 0u);  // 65 << 16 codes: not memoised
  EXPECT_EQ(memo_bytes(parse_q_format("uq1.20"), 1), 0u);   // wider than 16 bits
  // 64 materials of shininess near 1 (every code above the threshold): 64 units would take
  // 5 GiB by the rule, refused before a row is read; eval and sim alike.
  std::string vec = "glint-vectors 1\neps 1e-3\nlights 1\n";
  for (int m = 0; m < 64; ++m)
    vec += "material m" + std::to_string(m) + " specular=1,1,1 shininess=1." +
           std::to_string(m + 10) + " lobe=phong\n";
  vec += "columns t material\ndata\n";
  for (int m = 0; m < 64; ++m) vec += "0.5 m" + std::to_string(m) + "\n";
  write("m.vec", vec);
  std::string units;
  for (int u = 0; u < 64; ++u) units += " --unit pow:buffer=" + std::to_string(u + 4);
  for (const char* command : {"eval", "sim"}) {
    SCOPED_TRACE(command);
    const auto run = glint(std::string(command) + " m.vec" + units + " --dump d.csv");
    EXPECT_EQ(run.status, 2) << run.err;
    EXPECT_NE(run.err.find("m.vec: field 'slots': the memos of input codes of this run's 64 units "
                           "may take 5120 MiB, more than the limit of 4096 MiB per run"),
              std::string::npos)
        << run.err;
    EXPECT_FALSE(fs::exists(dir_.path() / "d.csv"));
  }
  // Eight units are 640 MiB by the rule: they run.
  std::string eight;
  for (int u = 0; u < 8; ++u) eight += " --unit pow:buffer=" + std::to_string(u + 4);
  const auto run = glint("eval m.vec" + eight);
  EXPECT_EQ(run.status, 0) << run.err;
}

TEST_F(Bounds, RenderMemoryIsBoundedBeforeWork) {
  nlohmann::json s =
      nlohmann::json::parse(glint::test::read_file(kSource + "/traces/scenes/small.json"));
  s["camera"]["resolution"] = {16384, 16384};
  write("big.json", s.dump());
  const auto run = glint("render big.json --unit pow -o out");
  EXPECT_EQ(run.status, 2) << run.err;
  EXPECT_NE(
      run.err.find("big.json: field 'camera.resolution': 16384 x 16384 pixels through 1 unit"),
      std::string::npos)
      << run.err;
  EXPECT_NE(run.err.find("more than the limit of 4096 MiB per render"), std::string::npos)
      << run.err;
  EXPECT_FALSE(fs::exists(dir_.path() / "out"));
  // The rule against the limit: one unit at 11000^2 fits, five units do not.
  EXPECT_LE(render_bytes(11000ull * 11000, 1), kMaxRenderBytes);
  EXPECT_GT(render_bytes(11000ull * 11000, 5), kMaxRenderBytes);
  s["camera"]["resolution"] = {11000, 11000};
  const std::string five = write("five.json", s.dump());
  expect_refusal(input_error([&] { render_scene(load_scene(five), RenderOptions{}); }), five, 0,
                 "camera.resolution", "through 5 units");
}

}  // namespace
}  // namespace glint
