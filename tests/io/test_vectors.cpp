// Vector files v1: shipped traces, round trips, every malformed-input case, atomic writing.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <streambuf>
#include <string>
#include <vector>

#include "io/atomic_file.h"
#include "io/input_error.h"
#include "io/line_reader.h"
#include "io/vectors.h"
#include "test_support.h"

namespace fs = std::filesystem;

namespace glint {
namespace {

const std::string kTraces = std::string(GLINT_SOURCE_DIR) + "/traces";

using glint::test::TempDir;

std::vector<VectorRow> read_all(VectorReader& reader) {
  std::vector<VectorRow> rows;
  VectorRow row;
  while (reader.next(row)) rows.push_back(row);
  EXPECT_EQ(reader.rows_read(), rows.size());
  return rows;
}

std::vector<VectorRow> parse(const std::string& text, VectorHeader* header = nullptr) {
  std::istringstream in(text);
  VectorReader reader(in, "mem.vec");
  if (header != nullptr) *header = reader.header();
  return read_all(reader);
}

bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

void expect_same_rows(const std::vector<VectorRow>& a, const std::vector<VectorRow>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    SCOPED_TRACE("row " + std::to_string(i));
    EXPECT_TRUE(same_bits(a[i].t, b[i].t)) << a[i].t << " vs " << b[i].t;
    EXPECT_EQ(a[i].material, b[i].material);
    EXPECT_EQ(a[i].light, b[i].light);
    EXPECT_EQ(a[i].x, b[i].x);
    EXPECT_EQ(a[i].y, b[i].y);
  }
}

void expect_same_header(const VectorHeader& a, const VectorHeader& b) {
  EXPECT_EQ(a.version, b.version);
  EXPECT_TRUE(same_bits(a.eps, b.eps));
  EXPECT_EQ(a.lights, b.lights);
  EXPECT_EQ(a.light_intensity, b.light_intensity);
  EXPECT_EQ(a.materials, b.materials);
  EXPECT_EQ(a.has_light, b.has_light);
  EXPECT_EQ(a.has_xy, b.has_xy);
}

// Parses `text` fully and expects an InputError at `line` naming `field`.
void expect_error(const std::string& text, std::uint64_t line, const std::string& field) {
  try {
    parse(text);
    ADD_FAILURE() << "no InputError for:\n" << text;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "mem.vec");
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_EQ(e.field(), field) << e.what();
    EXPECT_FALSE(e.message().empty());
    const std::string prefix = "mem.vec:" + std::to_string(line) + ": field '" + field + "': ";
    EXPECT_EQ(std::string(e.what()).rfind(prefix, 0), 0u) << e.what();
  }
}

// Header with 6 lines; the first row is line 7.
const std::string kHead =
    "glint-vectors 1\n"
    "eps 1e-3\n"
    "lights 2\n"
    "material white specular=1,1,1 shininess=50 lobe=phong\n"
    "columns t material light x y\n"
    "data\n";

// Header lines 1-3; material/columns/data lines follow in the case.
const std::string kPre = "glint-vectors 1\neps 1e-3\nlights 2\n";
const std::string kMat = "material white specular=1,1,1 shininess=50 lobe=phong\n";

// ---- Shipped traces ----------------------------------------------------------------------

TEST(VectorTraces, EveryShippedTraceParses) {
  int files = 0;
  for (const auto& entry : fs::directory_iterator(kTraces)) {
    if (entry.path().extension() != ".vec") continue;
    SCOPED_TRACE(entry.path().string());
    ++files;
    EXPECT_LT(fs::file_size(entry.path()), 200u * 1024u);
    VectorReader reader(entry.path().string());
    const auto rows = read_all(reader);
    EXPECT_GE(rows.size(), 100u);
    const auto& h = reader.header();
    EXPECT_EQ(h.version, 1);
    EXPECT_GT(h.eps, 0);
    EXPECT_EQ(h.light_intensity.size(), static_cast<std::size_t>(h.lights));
    for (const auto& r : rows) {
      ASSERT_LT(r.material, h.materials.size());
      ASSERT_GE(r.t, -1.0);
      ASSERT_LE(r.t, 1.001);
      ASSERT_GE(r.light, 0);
      ASSERT_LT(r.light, h.lights);
      if (h.has_xy) {
        ASSERT_GE(r.x, 0);
        ASSERT_GE(r.y, 0);
      } else {
        ASSERT_EQ(r.x, -1);
        ASSERT_EQ(r.y, -1);
      }
    }
    // Each trace survives write -> read unchanged.
    TempDir dir;
    const std::string copy = dir.file("copy.vec");
    {
      VectorWriter w(copy, h);
      for (const auto& r : rows) w.write(r);
      w.commit();
    }
    VectorReader again(copy);
    expect_same_header(h, again.header());
    expect_same_rows(rows, read_all(again));
  }
  EXPECT_GE(files, 6);
}

TEST(VectorTraces, PhongBasic) {
  VectorReader r(kTraces + "/phong_basic.vec");
  const auto rows = read_all(r);
  ASSERT_EQ(rows.size(), 1001u);
  EXPECT_EQ(rows.front().t, -1.0);
  EXPECT_EQ(rows[500].t, 0.0);
  EXPECT_EQ(rows.back().t, 1.0);
  ASSERT_EQ(r.header().materials.size(), 1u);
  const auto& m = r.header().materials[0];
  EXPECT_EQ(m.name, "white");
  EXPECT_EQ(m.lobe, VectorLobe::kPhong);
  EXPECT_EQ(m.shininess, 50);
  EXPECT_EQ(m.specular, (std::array<double, 3>{1, 1, 1}));
  EXPECT_EQ(r.header().eps, 1e-3);
  EXPECT_FALSE(r.header().has_light);
  EXPECT_FALSE(r.header().has_xy);
}

TEST(VectorTraces, BlinnGaussianMultiLightPixels) {
  {
    VectorReader r(kTraces + "/blinn_colored.vec");
    for (const auto& m : r.header().materials) {
      EXPECT_EQ(m.lobe, VectorLobe::kBlinn);
      EXPECT_GE(m.shininess, 4);
      EXPECT_LE(m.shininess, 500);
    }
    EXPECT_GE(r.header().materials.size(), 4u);
  }
  {
    VectorReader r(kTraces + "/gaussian.vec");
    for (const auto& m : r.header().materials) {
      EXPECT_EQ(m.lobe, VectorLobe::kGaussian);
      EXPECT_GT(m.roughness, 0);
      EXPECT_LE(m.roughness, 1);
    }
    const auto lacquer = r.header().material_index("lacquer");
    ASSERT_NE(lacquer, VectorHeader::npos);
    EXPECT_EQ(r.header().materials[lacquer].shininess, 200);
    EXPECT_EQ(r.header().materials[r.header().material_index("satin")].shininess, 0);
  }
  {
    VectorReader r(kTraces + "/multi_light.vec");
    const auto& h = r.header();
    EXPECT_EQ(h.lights, 3);
    EXPECT_TRUE(h.has_light);
    EXPECT_EQ(h.light_intensity[0], (std::array<double, 3>{1, 1, 1}));
    EXPECT_EQ(h.light_intensity[1], (std::array<double, 3>{1, 0.8, 0.6}));
    EXPECT_EQ(h.light_intensity[2], (std::array<double, 3>{0.3, 0.4, 1}));
    std::array<int, 3> seen{};
    for (const auto& row : read_all(r)) ++seen[static_cast<std::size_t>(row.light)];
    for (int n : seen) EXPECT_GT(n, 0);
  }
  {
    VectorReader r(kTraces + "/pixels.vec");
    EXPECT_TRUE(r.header().has_xy);
    const auto rows = read_all(r);
    for (const auto& row : rows) {
      EXPECT_LT(row.x, 48);
      EXPECT_LT(row.y, 32);
    }
  }
}

TEST(VectorTraces, HardCases) {
  VectorReader r(kTraces + "/hard_cases.vec");
  const auto& h = r.header();
  const auto rows = read_all(r);
  bool neg_zero = false, subnormal = false, upper = false, lower = false;
  for (const auto& row : rows) {
    neg_zero |= row.t == 0 && std::signbit(row.t);
    subnormal |= row.t == std::numeric_limits<double>::denorm_min();
    upper |= row.t == 1.001;
    lower |= row.t == -1;
  }
  EXPECT_TRUE(neg_zero);
  EXPECT_TRUE(subnormal);
  EXPECT_TRUE(upper);
  EXPECT_TRUE(lower);
  EXPECT_EQ(h.materials[h.material_index("tiny_n")].shininess, 0.5);
  EXPECT_EQ(h.materials[h.material_index("huge_n")].shininess, 5000);
  const auto& dim = h.materials[h.material_index("dim")].specular;
  EXPECT_LE(0.2126 * dim[0] + 0.7152 * dim[1] + 0.0722 * dim[2], h.eps);
}

TEST(VectorTraces, ReadmeExampleParses) {
  std::ifstream in(kTraces + "/README.md");
  ASSERT_TRUE(in.is_open());
  std::string line, example;
  bool in_section = false, in_block = false;
  while (std::getline(in, line)) {
    if (line == "## Example") in_section = true;
    if (!in_section) continue;
    if (line == "```") {
      if (in_block) break;
      in_block = true;
      continue;
    }
    if (in_block) example += line + "\n";
  }
  VectorHeader h;
  const auto rows = parse(example, &h);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(h.lights, 2);
  EXPECT_EQ(h.light_intensity[1], (std::array<double, 3>{1, 0.8, 0.6}));
  EXPECT_EQ(h.materials.size(), 2u);
  EXPECT_TRUE(h.has_light);
  EXPECT_TRUE(h.has_xy);
  EXPECT_EQ(rows[1].material, 1u);
  EXPECT_EQ(rows[1].x, 11);
}

// ---- Header semantics --------------------------------------------------------------------

TEST(VectorHeaderParse, AllFields) {
  VectorHeader h;
  const auto rows = parse(
      "# leading comment\n"
      "\n"
      "glint-vectors 1   # magic and version\n"
      "light 2 0.5,0.25,0.125   # before 'lights': order of header lines is free\n"
      "eps 2.5e-4\n"
      "lights 3\n"
      "material a_1 specular=0.9,0.8,0.7 shininess=12.5 lobe=blinn\n"
      "material G.x-2 specular=1,1,1 lobe=gaussian roughness=1\n"
      "material g2 lobe=gaussian roughness=0.25 shininess=30 specular=0,0,0\n"
      "columns material t light   # any order\n"
      "data\n"
      "a_1 0.5 2\n"
      "G.x-2 -1 0\n",
      &h);
  EXPECT_EQ(h.version, 1);
  EXPECT_EQ(h.eps, 2.5e-4);
  EXPECT_EQ(h.lights, 3);
  ASSERT_EQ(h.light_intensity.size(), 3u);
  EXPECT_EQ(h.light_intensity[0], (std::array<double, 3>{1, 1, 1}));
  EXPECT_EQ(h.light_intensity[1], (std::array<double, 3>{1, 1, 1}));
  EXPECT_EQ(h.light_intensity[2], (std::array<double, 3>{0.5, 0.25, 0.125}));
  EXPECT_EQ(h.intensity(2), (std::array<double, 3>{0.5, 0.25, 0.125}));
  ASSERT_EQ(h.materials.size(), 3u);
  EXPECT_EQ(h.materials[0].name, "a_1");
  EXPECT_EQ(h.materials[0].specular, (std::array<double, 3>{0.9, 0.8, 0.7}));
  EXPECT_EQ(h.materials[0].shininess, 12.5);
  EXPECT_EQ(h.materials[0].lobe, VectorLobe::kBlinn);
  EXPECT_EQ(h.materials[0].roughness, 0);
  EXPECT_EQ(h.materials[1].lobe, VectorLobe::kGaussian);
  EXPECT_EQ(h.materials[1].roughness, 1);
  EXPECT_EQ(h.materials[1].shininess, 0);
  EXPECT_EQ(h.materials[2].shininess, 30);
  EXPECT_EQ(h.materials[2].roughness, 0.25);
  EXPECT_TRUE(h.has_light);
  EXPECT_FALSE(h.has_xy);
  EXPECT_EQ(h.material_index("g2"), 2u);
  EXPECT_EQ(h.material_index("nope"), VectorHeader::npos);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].material, 0u);
  EXPECT_EQ(rows[0].t, 0.5);
  EXPECT_EQ(rows[0].light, 2);
  EXPECT_EQ(rows[0].line, 12u);
  EXPECT_EQ(rows[1].material, 1u);
  EXPECT_EQ(rows[1].t, -1);
  EXPECT_EQ(rows[1].line, 13u);
}

TEST(VectorHeaderParse, HeaderWithoutRowsIsAnEmptyStream) {
  std::istringstream in(kHead);
  VectorReader r(in, "mem.vec");
  VectorRow row;
  EXPECT_FALSE(r.next(row));
  EXPECT_FALSE(r.next(row));
  EXPECT_EQ(r.rows_read(), 0u);
  EXPECT_TRUE(parse(kHead + "# just a comment\n\n   \n").empty());
}

TEST(VectorHeaderParse, ToString) {
  EXPECT_STREQ(to_string(VectorLobe::kPhong), "phong");
  EXPECT_STREQ(to_string(VectorLobe::kBlinn), "blinn");
  EXPECT_STREQ(to_string(VectorLobe::kGaussian), "gaussian");
}

// ---- Row syntax ----------------------------------------------------------------------------

TEST(VectorRows, SeparatorsCommentsLineEnds) {
  const auto rows = parse(kHead +
                          "0.5 white 1 3 4\n"
                          "0.5,white,1,3,4\n"
                          "  0.5 , white ,1,\t3 4   # trailing comment\n"
                          "\t0.5\twhite\t1\t3\t4\r\n"
                          "# comment line between rows\n"
                          "\n"
                          "   # indented comment\n"
                          "0.5 white 1 3 4#comment right after a field\n"
                          "+0.5 white +1 +3 +4\n"
                          "5e-1 white 1 3 4\r\n"
                          ".5 white 1 3 4");  // no trailing newline
  ASSERT_EQ(rows.size(), 8u);
  const std::uint64_t lines[] = {7, 8, 9, 10, 14, 15, 16, 17};
  for (std::size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(rows[i].t, 0.5);
    EXPECT_EQ(rows[i].material, 0u);
    EXPECT_EQ(rows[i].light, 1);
    EXPECT_EQ(rows[i].x, 3);
    EXPECT_EQ(rows[i].y, 4);
    EXPECT_EQ(rows[i].line, lines[i]);
  }
}

TEST(VectorRows, CrlfEverywhereAndBom) {
  std::string text = "\xEF\xBB\xBF" + kHead + "1 white 0 0 0\n-1 white 1 5 6\n";
  std::string crlf;
  for (char c : text) {
    if (c == '\n') crlf += '\r';
    crlf += c;
  }
  VectorHeader h;
  const auto rows = parse(crlf, &h);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[1].t, -1);
  EXPECT_EQ(rows[1].line, 8u);
  EXPECT_EQ(h.materials[0].name, "white");
  // An unterminated final line ending in "\r" is accepted too.
  EXPECT_EQ(parse(kHead + "1 white 0 0 0\r").size(), 1u);
}

TEST(VectorRows, DefaultsWithoutOptionalColumns) {
  const auto rows = parse(kPre + kMat + "columns t material\ndata\n0.25 white\n");
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].light, 0);
  EXPECT_EQ(rows[0].x, -1);
  EXPECT_EQ(rows[0].y, -1);
}

TEST(VectorRows, RangeLimitsOfT) {
  const std::string head = kPre + kMat + "columns t material\ndata\n";
  const auto rows = parse(head + "-1 white\n1.001 white\n-0 white\n4.9e-324 white\n");
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(rows[0].t, kVectorTMin);
  EXPECT_EQ(rows[1].t, kVectorTMax);
  EXPECT_TRUE(std::signbit(rows[2].t));
  EXPECT_EQ(rows[3].t, std::numeric_limits<double>::denorm_min());
  expect_error(head + "-1.0000000000000002 white\n", 7, "t");
  expect_error(head + "1.0010000000000002 white\n", 7, "t");
}

TEST(VectorRows, ManyMaterialsUseTheHashLookup) {
  std::string text = kPre;
  for (int i = 0; i < 40; ++i) {
    text += "material m" + std::to_string(i) +
            " specular=1,1,1 shininess=" + std::to_string(i + 1) + " lobe=phong\n";
  }
  text += "columns t material\ndata\n";
  for (int i = 0; i < 200; ++i) text += "0.5 m" + std::to_string((i * 7) % 40) + "\n";
  text += "0.5 m40\n";
  try {
    parse(text);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "material");
    EXPECT_EQ(e.line(), 3u + 40u + 2u + 200u + 1u);
  }
  text.resize(text.size() - 8);
  const auto rows = parse(text);
  ASSERT_EQ(rows.size(), 200u);
  for (int i = 0; i < 200; ++i)
    EXPECT_EQ(rows[static_cast<std::size_t>(i)].material, (i * 7) % 40u);
}

// ---- Malformed input: every case names its line and field --------------------------------

struct BadCase {
  const char* what;
  std::string text;
  std::uint64_t line;
  const char* field;
};

std::vector<BadCase> bad_cases() {
  const std::string h5 = kPre + kMat + "columns t material light x y\ndata\n";  // rows from line 7
  const std::string h2 = kPre + kMat + "columns t material\ndata\n";
  return {
      // File structure.
      {"empty file", "", 1, "magic"},
      {"only comments", "# a\n\n   # b\n", 4, "magic"},
      {"only comments, unterminated", "# a\n# b", 2, "magic"},
      {"wrong magic", "# c\nglint-vector 1\n", 2, "magic"},
      {"csv instead of vectors", "t,material\n0.5,white\n", 1, "magic"},
      {"missing version", "glint-vectors\n", 1, "version"},
      {"future version", "glint-vectors 2\n", 1, "version"},
      {"non-numeric version", "glint-vectors one\n", 1, "version"},
      {"extra after version", "glint-vectors 1 extra\n", 1, "version"},
      {"magic twice", kPre + "glint-vectors 1\n", 4, "header"},
      {"unknown header key", kPre + "gamma 2.2\n", 4, "header"},
      {"row before data", kPre + kMat + "columns t material\n0.5 white\n", 6, "header"},
      {"eof before data", kPre + kMat + "columns t material\n", 6, "data"},
      {"eof before data, no newline", kPre + kMat + "columns t material", 5, "data"},
      {"data with extra token", kPre + kMat + "columns t material\ndata now\n", 6, "data"},
      // Missing header lines (reported at the data line).
      {"missing eps", "glint-vectors 1\nlights 1\n" + kMat + "columns t material\ndata\n", 5,
       "eps"},
      {"missing lights", "glint-vectors 1\neps 1e-3\n" + kMat + "columns t material\ndata\n", 5,
       "lights"},
      {"missing materials", kPre + "columns t material\ndata\n", 5, "material"},
      {"missing columns", kPre + kMat + "data\n", 5, "columns"},
      {"missing eps at eof", "glint-vectors 1\n", 2, "eps"},
      // eps.
      {"eps zero", "glint-vectors 1\neps 0\n", 2, "eps"},
      {"eps negative", "glint-vectors 1\neps -1e-3\n", 2, "eps"},
      {"eps nan", "glint-vectors 1\neps nan\n", 2, "eps"},
      {"eps inf", "glint-vectors 1\neps inf\n", 2, "eps"},
      {"eps overflow", "glint-vectors 1\neps 1e999\n", 2, "eps"},
      {"eps text", "glint-vectors 1\neps small\n", 2, "eps"},
      {"eps missing value", "glint-vectors 1\neps\n", 2, "eps"},
      {"eps extra value", "glint-vectors 1\neps 1e-3 2e-3\n", 2, "eps"},
      {"eps twice", kPre + "eps 1e-3\n", 4, "eps"},
      // lights / light.
      {"lights zero", "glint-vectors 1\nlights 0\n", 2, "lights"},
      {"lights fractional", "glint-vectors 1\nlights 1.5\n", 2, "lights"},
      {"lights too many", "glint-vectors 1\nlights 1025\n", 2, "lights"},
      {"lights int overflow", "glint-vectors 1\nlights 99999999999\n", 2, "lights"},
      {"lights twice", kPre + "lights 2\n", 4, "lights"},
      {"light index >= lights", kPre + "light 2 1,1,1\n" + kMat + "columns t material\ndata\n", 4,
       "light"},
      {"light index negative", kPre + "light -1 1,1,1\n", 4, "light"},
      {"light two components", kPre + "light 1 1,1\n", 4, "light"},
      {"light four components", kPre + "light 1 1,1,1,1\n", 4, "light"},
      {"light nan component", kPre + "light 1 1,nan,1\n", 4, "light"},
      {"light negative component", kPre + "light 1 1,-1,1\n", 4, "light"},
      {"light empty component", kPre + "light 1 1,,1\n", 4, "light"},
      {"light missing rgb", kPre + "light 1\n", 4, "light"},
      {"light twice", kPre + "light 1 1,1,1\nlight 1 2,2,2\n", 5, "light"},
      // Materials.
      {"duplicate material", kPre + kMat + "# again\n" + kMat, 6, "material"},
      {"material without name", kPre + "material\n", 4, "material"},
      {"material bad name", kPre + "material 1st specular=1,1,1 shininess=5 lobe=phong\n", 4,
       "material"},
      {"material name with utf-8", kPre + "material caf\xC3\xA9 specular=1,1,1 lobe=phong\n", 4,
       "material"},
      {"material invalid utf-8", kPre + "material x\xFF specular=1,1,1 lobe=phong\n", 4,
       "material"},
      {"unknown attribute", kPre + "material m specular=1,1,1 shininess=5 lobe=phong ior=1.5\n", 4,
       "material"},
      {"attribute without =", kPre + "material m specular=1,1,1 shininess 5 lobe=phong\n", 4,
       "material"},
      {"shininess zero", kPre + "material m specular=1,1,1 shininess=0 lobe=phong\n", 4,
       "shininess"},
      {"shininess negative", kPre + "material m specular=1,1,1 shininess=-2 lobe=blinn\n", 4,
       "shininess"},
      {"shininess nan", kPre + "material m specular=1,1,1 shininess=nan lobe=blinn\n", 4,
       "shininess"},
      {"shininess overflow", kPre + "material m specular=1,1,1 shininess=1e400 lobe=blinn\n", 4,
       "shininess"},
      {"shininess empty", kPre + "material m specular=1,1,1 shininess= lobe=blinn\n", 4,
       "shininess"},
      {"shininess twice", kPre + "material m specular=1,1,1 shininess=2 shininess=3 lobe=blinn\n",
       4, "shininess"},
      {"phong without shininess", kPre + "material m specular=1,1,1 lobe=phong\n", 4, "shininess"},
      {"gaussian shininess zero",
       kPre + "material m specular=1,1,1 lobe=gaussian roughness=0.5 shininess=0\n", 4,
       "shininess"},
      {"gaussian without roughness", kPre + "material m specular=1,1,1 lobe=gaussian\n", 4,
       "roughness"},
      {"roughness zero", kPre + "material m specular=1,1,1 lobe=gaussian roughness=0\n", 4,
       "roughness"},
      {"roughness above 1", kPre + "material m specular=1,1,1 lobe=gaussian roughness=1.5\n", 4,
       "roughness"},
      {"roughness on phong",
       kPre + "material m specular=1,1,1 lobe=phong shininess=5 roughness=0.5\n", 4, "roughness"},
      {"unknown lobe", kPre + "material m specular=1,1,1 shininess=5 lobe=ward\n", 4, "lobe"},
      {"missing lobe", kPre + "material m specular=1,1,1 shininess=5\n", 4, "lobe"},
      {"missing specular", kPre + "material m shininess=5 lobe=phong\n", 4, "specular"},
      {"specular two components", kPre + "material m specular=1,1 shininess=5 lobe=phong\n", 4,
       "specular"},
      {"specular text", kPre + "material m specular=1,1,x shininess=5 lobe=phong\n", 4, "specular"},
      {"specular inf", kPre + "material m specular=1,inf,1 shininess=5 lobe=phong\n", 4,
       "specular"},
      {"specular negative", kPre + "material m specular=1,-0.5,1 shininess=5 lobe=phong\n", 4,
       "specular"},
      // Columns.
      {"columns without t", kPre + kMat + "columns material light\n", 5, "columns"},
      {"columns without material", kPre + kMat + "columns t\n", 5, "columns"},
      {"columns empty", kPre + kMat + "columns\n", 5, "columns"},
      {"unknown column", kPre + kMat + "columns t material u v\n", 5, "columns"},
      {"duplicate column", kPre + kMat + "columns t material t\n", 5, "columns"},
      {"x without y", kPre + kMat + "columns t material x\n", 5, "columns"},
      {"columns twice", kPre + kMat + "columns t material\ncolumns t material\n", 6, "columns"},
      // Rows: numbers.
      {"t not numeric", h5 + "0.5 white 0 1 1\nabc white 0 1 1\n", 8, "t"},
      {"t nan", h5 + "nan white 0 1 1\n", 7, "t"},
      {"t NaN", h5 + "NaN white 0 1 1\n", 7, "t"},
      {"t inf", h5 + "inf white 0 1 1\n", 7, "t"},
      {"t -infinity", h5 + "-infinity white 0 1 1\n", 7, "t"},
      {"t overflow", h5 + "1e999 white 0 1 1\n", 7, "t"},
      {"t underflow", h5 + "1e-999 white 0 1 1\n", 7, "t"},
      {"t above 1.001", h5 + "1.0011 white 0 1 1\n", 7, "t"},
      {"t below -1", h5 + "-1.5 white 0 1 1\n", 7, "t"},
      {"t hex float", h5 + "0x1p-1 white 0 1 1\n", 7, "t"},
      {"t trailing garbage", h5 + "0.5x white 0 1 1\n", 7, "t"},
      {"t incomplete exponent", h5 + "1e white 0 1 1\n", 7, "t"},
      {"t sign only", h5 + "- white 0 1 1\n", 7, "t"},
      {"t plus minus", h5 + "+-0.5 white 0 1 1\n", 7, "t"},
      {"t empty (leading comma)", h5 + ",white,0,1,1\n", 7, "t"},
      {"light not integer", h5 + "0.5 white 1.0 1 1\n", 7, "light"},
      {"light out of range", h5 + "0.5 white 2 1 1\n", 7, "light"},
      {"light negative", h5 + "0.5 white -1 1 1\n", 7, "light"},
      {"light int overflow", h5 + "0.5 white 4294967296 1 1\n", 7, "light"},
      {"x negative", h5 + "0.5 white 0 -3 1\n", 7, "x"},
      {"x not numeric", h5 + "0.5 white 0 a 1\n", 7, "x"},
      {"y not numeric", h5 + "0.5 white 0 1 1e3\n", 7, "y"},
      {"y overflow", h5 + "0.5 white 0 1 2147483648\n", 7, "y"},
      // Rows: structure.
      {"unknown material", h5 + "0.5 black 0 1 1\n", 7, "material"},
      {"material case differs", h5 + "0.5 White 0 1 1\n", 7, "material"},
      {"missing material column", h2 + "0.5\n", 7, "material"},
      {"missing material before comment", h2 + "0.5 # white\n", 7, "material"},
      {"missing trailing columns", h5 + "0.5 white 0 1\n", 7, "y"},
      {"extra column", h2 + "0.5 white 7\n", 7, "columns"},
      {"extra column after comma", h2 + "0.5,white,7\n", 7, "columns"},
      {"trailing comma", h2 + "0.5,white,\n", 7, "columns"},
      {"empty middle field", h5 + "0.5,,white,0,1,1\n", 7, "material"},
      {"comma then end", h5 + "0.5,white,0,1,\n", 7, "y"},
      {"row error after blank lines", h2 + "\n\n# c\n0.5 white\n\n0.5 white 1\n", 12, "columns"},
      {"row error after crlf rows", h2 + "0.5 white\r\n0.5 white\r\n2 white\r\n", 9, "t"},
      {"row error on unterminated last line", h2 + "0.5 white\n0.5 grey", 8, "material"},
      // Bytes.
      {"nul byte in a row", h2 + std::string("0.5 white\n0.5\0 white\n", 21), 8, "line"},
      {"nul byte in the header", std::string("glint-vectors 1\neps 1e-3\0\n", 26), 2, "line"},
      {"nul byte in a comment", h2 + std::string("# a\0b\n", 6), 7, "line"},
      {"carriage return inside a field", h2 + "0.5\r white\n", 7, "t"},
      {"vertical tab is not a blank", h2 + "0.5\vwhite\n", 7, "t"},
  };
}

TEST(VectorErrors, EveryBadInputNamesLineAndField) {
  for (const auto& c : bad_cases()) {
    SCOPED_TRACE(c.what);
    expect_error(c.text, c.line, c.field);
  }
}

TEST(VectorErrors, LongLines) {
  const std::string h2 = kPre + kMat + "columns t material\ndata\n";
  // Exactly 4096 bytes of content is fine, with "\n" or "\r\n".
  const std::string max_comment = "#" + std::string(4095, 'c');
  EXPECT_EQ(parse(h2 + max_comment + "\n0.5 white\n").size(), 1u);
  EXPECT_EQ(parse(h2 + max_comment + "\r\n0.5 white\r\n").size(), 1u);
  EXPECT_EQ(parse(h2 + "0.5 white #" + std::string(4085, 'c') + "\n").size(), 1u);
  EXPECT_EQ(parse(kPre + max_comment + "\n" + kMat + "columns t material\ndata\n").size(), 0u);
  // 4097 bytes is not, whether terminated or not, in the header or in the rows.
  expect_error(h2 + max_comment + "c\n0.5 white\n", 7, "line");
  expect_error(h2 + "0.5 white\n" + max_comment + "c", 8, "line");
  expect_error(kPre + max_comment + "c\n", 4, "line");
  expect_error(h2 + "0.5 " + std::string(5000, '9') + "\n", 7, "line");
  // A huge line without any newline is rejected from the first buffer, not read to the end.
  expect_error(h2 + "0.5 white\n" + std::string(3u << 20, 'x'), 8, "line");
}

// The reader's buffer starts at 64 KiB and doubles at each refill up to 1 MiB. Lines of every
// length up to the longest fall across each of those boundaries: LineReader gives back every byte
// of every line, line by line and a block at a time, and the rows and their line numbers are the
// same through next() and next_block().
std::string random_lines(std::size_t bytes, std::vector<std::string>& lines) {
  std::minstd_rand rng(11);
  std::string text;
  while (text.size() < bytes) {
    std::string line(rng() % (kVectorMaxLineBytes + 1), ' ');
    for (char& c : line) c = static_cast<char>('!' + rng() % 94);
    text += line + (rng() % 2 ? "\r\n" : "\n");
    lines.push_back(std::move(line));
  }
  return text;
}

TEST(LineReaderTest, EveryByteAcrossEveryBufferBoundary) {
  std::vector<std::string> lines;
  const std::string text = random_lines(std::size_t{5} << 20, lines);
  {
    std::istringstream in(text + "tail");
    LineReader reader(in, "lines.txt");
    std::string_view line;
    for (std::size_t i = 0; i < lines.size(); ++i) {
      ASSERT_TRUE(reader.next(line)) << i;
      ASSERT_EQ(line, lines[i]) << "line " << i + 1;
      ASSERT_EQ(reader.line_number(), i + 1);
    }
    ASSERT_TRUE(reader.next(line));
    EXPECT_EQ(line, "tail");
    EXPECT_FALSE(reader.next(line));
  }
  {
    std::istringstream in(text);
    LineReader reader(in, "lines.txt");
    std::string joined;
    const char *begin, *end;
    while (reader.block(begin, end)) {
      joined.append(begin, end);
      reader.skip_block(end, static_cast<std::uint64_t>(std::count(begin, end, '\n')));
    }
    EXPECT_EQ(joined, text);
    EXPECT_EQ(reader.line_number(), lines.size());
  }
  // A NUL byte is reported on its own line: in the first buffer's unfinished last line (carried
  // into the grown buffer), and megabytes on.
  for (std::size_t at : {std::size_t{65535}, std::size_t{3} << 20}) {
    while (text[at] == '\r' || text[at] == '\n') ++at;  // in a line, not its end
    std::string with_nul = text;
    with_nul[at] = '\0';
    const auto line = 1 + static_cast<std::uint64_t>(std::count(
                              text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
    std::istringstream in(with_nul);
    LineReader reader(in, "nul.txt");
    std::string_view view;
    try {
      while (reader.next(view)) {
      }
      ADD_FAILURE() << "no error for a NUL at byte " << at;
    } catch (const InputError& e) {
      EXPECT_EQ(e.line(), line) << at;
    }
  }
}

TEST(VectorRows, NextBlockAcrossEveryBufferBoundary) {
  const std::string head = kPre + kMat + "columns t material\ndata\n";
  std::string text = head;
  std::minstd_rand rng(5);
  while (text.size() < (std::size_t{3} << 20))
    text +=
        std::to_string(rng() % 1000 / 1000.0) + " white #" + std::string(rng() % 4000, 'c') + "\n";
  const std::vector<VectorRow> by_line = parse(text);
  for (int threads : {1, 2}) {
    std::istringstream in(text);
    VectorReader reader(in, "blocks.vec");
    std::vector<VectorRow> by_block, block;
    while (reader.next_block(block, threads))
      by_block.insert(by_block.end(), block.begin(), block.end());
    expect_same_rows(by_line, by_block);
    ASSERT_EQ(by_line.size(), by_block.size());
    for (std::size_t i = 0; i < by_line.size(); ++i)
      ASSERT_EQ(by_block[i].line, by_line[i].line) << i;
    // append_block: the same rows after those already held, counted once each.
    std::istringstream again(text);
    VectorReader appender(again, "blocks.vec");
    std::vector<VectorRow> appended(1);
    while (appender.append_block(appended, threads)) {
    }
    ASSERT_EQ(appended.size(), by_line.size() + 1);
    EXPECT_EQ(appender.rows_read(), by_line.size());
    EXPECT_EQ(appended[0].line, 0u);
    appended.erase(appended.begin());
    expect_same_rows(by_line, appended);
    for (std::size_t i = 0; i < by_line.size(); ++i)
      ASSERT_EQ(appended[i].line, by_line[i].line) << i;
  }
}

// A malformed row anywhere in a block parsed in pieces (each numbered from 0, then renumbered):
// the rows before it, then its error with its own line, as a row at a time gives them.
TEST(VectorRows, NextBlockErrorsKeepTheirLines) {
  const std::string head = kPre + kMat + "columns t material\ndata\n";
  std::string rows;
  for (int i = 0; i < 60000; ++i) rows += std::to_string(i % 1000 / 1000.0) + " white\n";
  const std::size_t row_lines = 60000;
  for (const std::size_t bad :
       {std::size_t{0}, std::size_t{17}, std::size_t{31000}, row_lines - 1}) {
    std::string text = head;
    std::size_t line = 0;
    for (std::size_t at = 0; at < rows.size(); ++line) {
      const std::size_t nl = rows.find('\n', at);
      text += line == bad ? std::string("0.5 nosuch\n") : rows.substr(at, nl + 1 - at);
      at = nl + 1;
    }
    std::string by_line_error;
    std::uint64_t by_line_rows = 0;
    {
      std::istringstream in(text);
      VectorReader reader(in, "bad.vec");
      VectorRow row;
      try {
        while (reader.next(row)) ++by_line_rows;
      } catch (const InputError& e) {
        by_line_error = e.what();
      }
    }
    ASSERT_FALSE(by_line_error.empty()) << bad;
    for (int threads : {1, 2, 4}) {
      std::istringstream in(text);
      VectorReader reader(in, "bad.vec");
      std::vector<VectorRow> block;
      std::uint64_t by_block_rows = 0;
      std::uint64_t last_line = 0;
      try {
        while (reader.next_block(block, threads)) {
          for (const VectorRow& r : block) EXPECT_EQ(r.line, ++last_line + 6) << bad;
          by_block_rows += block.size();
        }
        ADD_FAILURE() << "no error for line " << bad;
      } catch (const InputError& e) {
        EXPECT_EQ(e.what(), by_line_error) << bad << " threads " << threads;
      }
      EXPECT_EQ(by_block_rows, by_line_rows) << bad << " threads " << threads;
    }
  }
}

TEST(VectorErrors, ErrorsAreStickyAndWhatIsFormatted) {
  std::istringstream in(kPre + kMat + "columns t material\ndata\n0.5 white\n7 white\n0.5 white\n");
  VectorReader r(in, "sticky.vec");
  VectorRow row;
  ASSERT_TRUE(r.next(row));
  try {
    r.next(row);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "sticky.vec:8: field 't': t = 7 outside [-1, 1.001]");
  }
  EXPECT_THROW(r.next(row), InputError);
  EXPECT_EQ(r.rows_read(), 1u);
}

TEST(VectorErrors, MissingFileAndFormatting) {
  try {
    VectorReader r("/nonexistent/dir/x.vec");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 0u);
    EXPECT_EQ(e.field(), "file");
    EXPECT_EQ(std::string(e.what()).rfind("/nonexistent/dir/x.vec: field 'file': ", 0), 0u);
  }
  try {
    VectorReader r(kTraces);  // a directory
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "file") << e.what();
  }
  {
    // A caller's exception mask does not leak std::ios_base::failure out of the reader.
    std::istringstream in(kPre + kMat + "columns t material\ndata\n0.5 white\n");
    in.exceptions(std::ios_base::failbit);
    VectorReader r(in, "mem.vec");
    EXPECT_EQ(read_all(r).size(), 1u);
  }
  const InputError e("a.vec", 12, "shininess", "must be > 0");
  EXPECT_STREQ(e.what(), "a.vec:12: field 'shininess': must be > 0");
  EXPECT_EQ(quote_input(std::string("a\0b'\xff", 5)), "'a\\x00b\\x27\\xff'");
  EXPECT_EQ(quote_input(std::string(50, 'z'), 4), "'zzzz'...");
}

TEST(VectorErrors, MessagesQuoteTheOffendingText) {
  try {
    parse(kPre + kMat + "columns t material\ndata\n0.5 whit\n");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(e.message().find("'whit'"), std::string::npos) << e.what();
  }
  try {
    parse(kPre + kMat + "columns t material\ndata\n1e999 white\n");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(e.message().find("range"), std::string::npos) << e.what();
  }
  try {
    parse(kPre + kMat + "columns t material\ndata\nnan white\n");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(e.message().find("finite"), std::string::npos) << e.what();
  }
}

// The message of the InputError that parsing `text` raises ("" if it parses).
std::string error_message(const std::string& text) {
  try {
    parse(text);
  } catch (const InputError& e) {
    return e.message();
  }
  return "";
}

std::string shortest(double v) {
  char text[32];
  return std::string(text, std::to_chars(text, text + sizeof text, v).ptr);
}

// Messages spell the limits from the constants the checks use, so they cannot go stale.
TEST(VectorErrors, MessagesQuoteTheLimitsTheyCheck) {
  const std::string h2 = kPre + kMat + "columns t material\ndata\n";
  const std::string t_range = "[" + shortest(kVectorTMin) + ", " + shortest(kVectorTMax) + "]";
  EXPECT_EQ(error_message(h2 + std::string(kVectorMaxLineBytes + 1, '#') + "\n"),
            "line longer than " + std::to_string(kVectorMaxLineBytes) + " bytes");
  const std::string too_many_lights = std::to_string(kVectorMaxLights + 1);
  EXPECT_EQ(
      error_message("glint-vectors 1\nlights " + too_many_lights + "\n"),
      "must be in 1.." + std::to_string(kVectorMaxLights) + ", got '" + too_many_lights + "'");
  EXPECT_EQ(error_message(h2 + "2 white\n"), "t = 2 outside " + t_range);
  EXPECT_EQ(error_message(kPre + "material m specular=1,1,1 lobe=gaussian roughness=1.5\n"),
            "roughness must be in (0, " + shortest(kVectorMaxRoughness) + "], got '1.5'");
  EXPECT_EQ(error_message("glint-vectors 2\n"),
            "unsupported format version 2 (this reader supports version " +
                std::to_string(kVectorFormatVersion) + ")");
  EXPECT_EQ(error_message(""),
            "empty file: expected 'glint-vectors " + std::to_string(kVectorFormatVersion) + "'");
  EXPECT_EQ(error_message(kPre + "material 1st specular=1,1,1 lobe=phong shininess=1\n"),
            "invalid material name '1st': names are 1-" + std::to_string(kVectorMaxNameLength) +
                " characters [A-Za-z0-9_.-] starting with a letter or '_'");

  VectorHeader h;
  h.eps = 1e-3;
  h.materials.push_back({"m", {1, 1, 1}, 10, VectorLobe::kPhong, 0});
  VectorHeader bad = h;
  bad.lights = kVectorMaxLights + 1;
  try {
    validate(bad);
    ADD_FAILURE() << "validate accepted lights = " << bad.lights;
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()),
              "invalid vector header: lights must be in 1.." + std::to_string(kVectorMaxLights));
  }
  std::ostringstream out;
  VectorWriter w(out, h);
  try {
    w.write({2, 0, 0, -1, -1, 0});
    ADD_FAILURE() << "the writer accepted t = 2";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()),
              "VectorWriter: row 1: t = 2 is not finite or outside " + t_range);
  }
}

TEST(VectorErrors, MaterialCountLimit) {
  std::string text = kPre;
  for (std::size_t i = 0; i < kVectorMaxMaterials; ++i) {
    text += "material m" + std::to_string(i) + " specular=1,1,1 lobe=gaussian roughness=1\n";
  }
  VectorHeader h;
  EXPECT_TRUE(parse(text + "columns t material\ndata\n", &h).empty());
  EXPECT_EQ(h.materials.size(), kVectorMaxMaterials);
  text += "material one_more specular=1,1,1 lobe=gaussian roughness=1\n";
  expect_error(text, 3 + kVectorMaxMaterials + 1, "material");
  EXPECT_EQ(error_message(text),
            "too many materials (limit " + std::to_string(kVectorMaxMaterials) + ")");
}

// Material lookup switches from a linear scan to a hash map past a handful of names: both find
// every name, and the last hit first.
TEST(VectorRows, MaterialLookupAtEverySize) {
  for (int count : {1, 2, 8, 9, 17}) {
    SCOPED_TRACE(count);
    std::string text = kPre;
    for (int i = 0; i < count; ++i) {
      text += "material m" + std::to_string(i) + " specular=1,1,1 shininess=2 lobe=phong\n";
    }
    text += "columns t material\ndata\n";
    std::vector<std::uint32_t> expected;
    for (int i = 0; i < 3 * count; ++i) {
      const int m = (i * 5 + i / 2) % count;
      text += "0.5 m" + std::to_string(m) + "\n";
      expected.push_back(static_cast<std::uint32_t>(m));
    }
    const auto rows = parse(text);
    ASSERT_EQ(rows.size(), expected.size());
    for (std::size_t i = 0; i < rows.size(); ++i) EXPECT_EQ(rows[i].material, expected[i]);
    expect_error(text + "0.5 m" + std::to_string(count) + "\n",
                 static_cast<std::uint64_t>(3 + count + 2 + 3 * count + 1), "material");
  }
}

// A header written as text, every value as given (shortest form, nan/inf as such), so the reader
// sees exactly what validate() sees. Like the writer, a Gaussian's shininess 0 (not given) and
// a zero roughness elsewhere are left out.
std::string header_text(const VectorHeader& h) {
  std::string text = "glint-vectors " + std::to_string(h.version) + "\neps " + shortest(h.eps) +
                     "\nlights " + std::to_string(h.lights) + "\n";
  const auto rgb = [](const std::array<double, 3>& c) {
    return shortest(c[0]) + "," + shortest(c[1]) + "," + shortest(c[2]);
  };
  for (std::size_t i = 0; i < h.light_intensity.size(); ++i) {
    text += "light " + std::to_string(i) + " " + rgb(h.light_intensity[i]) + "\n";
  }
  for (const auto& m : h.materials) {
    text += "material " + m.name + " specular=" + rgb(m.specular) + " lobe=" + to_string(m.lobe);
    if (m.shininess != 0 || m.lobe != VectorLobe::kGaussian) {
      text += " shininess=" + shortest(m.shininess);
    }
    if (m.roughness != 0 || m.lobe == VectorLobe::kGaussian) {
      text += " roughness=" + shortest(m.roughness);
    }
    text += "\n";
  }
  return text + "columns t material\ndata\n";
}

// The reader and validate() share one definition of every rule: each header value either passes
// both or neither.
TEST(VectorErrors, ReaderAndValidateAgree) {
  VectorHeader base;
  base.eps = 1e-3;
  base.lights = 2;
  base.light_intensity = {{1, 1, 1}, {0.5, 0.25, 1}};
  base.materials.push_back({"m", {1, 1, 1}, 10, VectorLobe::kPhong, 0});
  base.materials.push_back({"g", {1, 0.5, 0}, 0, VectorLobe::kGaussian, 0.5});
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const double numbers[] = {0,
                            -0.0,
                            1e-3,
                            1,
                            0.5,
                            1.5,
                            -1e-3,
                            1e300,
                            5e-324,
                            kVectorMaxRoughness,
                            std::nextafter(kVectorMaxRoughness, 2),
                            nan,
                            inf,
                            -inf};
  std::vector<std::pair<std::string, VectorHeader>> cases;
  const auto add = [&](const std::string& what, auto change) {
    VectorHeader h = base;
    change(h);
    cases.emplace_back(what, h);
  };
  for (const double v : numbers) {
    const std::string s = shortest(v);
    add("eps " + s, [&](VectorHeader& h) { h.eps = v; });
    add("light 1 red " + s, [&](VectorHeader& h) { h.light_intensity[1][0] = v; });
    add("specular " + s, [&](VectorHeader& h) { h.materials[0].specular[2] = v; });
    add("phong shininess " + s, [&](VectorHeader& h) { h.materials[0].shininess = v; });
    add("phong roughness " + s, [&](VectorHeader& h) { h.materials[0].roughness = v; });
    add("gaussian shininess " + s, [&](VectorHeader& h) { h.materials[1].shininess = v; });
    add("gaussian roughness " + s, [&](VectorHeader& h) { h.materials[1].roughness = v; });
  }
  for (const int lights : {-1, 0, 1, 2, kVectorMaxLights, kVectorMaxLights + 1}) {
    add("lights " + std::to_string(lights), [&](VectorHeader& h) {
      h.lights = lights;
      h.light_intensity.assign(static_cast<std::size_t>(std::max(lights, 0)), {1, 1, 1});
    });
  }
  const std::string longest(kVectorMaxNameLength, 'n');
  for (const std::string& name : {std::string("a"), std::string("_a.b-1"), std::string("1a"),
                                  std::string(".a"), longest, longest + "n", std::string("m")}) {
    add("name '" + name + "'", [&](VectorHeader& h) { h.materials[1].name = name; });
  }
  add("version 2", [](VectorHeader& h) { h.version = 2; });
  int accepted = 0;
  for (const auto& [what, h] : cases) {
    SCOPED_TRACE(what);
    bool valid = true;
    try {
      validate(h);
    } catch (const std::invalid_argument&) {
      valid = false;
    }
    bool readable = true;
    VectorHeader back;
    try {
      parse(header_text(h), &back);
    } catch (const InputError&) {
      readable = false;
    }
    EXPECT_EQ(valid, readable) << header_text(h);
    if (valid && readable) {
      ++accepted;
      expect_same_header(h, back);
    }
  }
  EXPECT_GT(accepted, 20);
  EXPECT_LT(accepted, static_cast<int>(cases.size()) - 20);
}

// Random byte-level damage to a valid file: the reader either parses it or throws InputError
// with a sane line and field, never anything else (run under ASan/UBSan to check for UB).
TEST(VectorErrors, RandomMutationsOnlyEverGiveInputError) {
  std::string base =
      "# fuzz base\nglint-vectors 1\neps 1e-3\nlights 3\nlight 1 0.5,0.5,1\n"
      "material a specular=1,0.5,0.25 shininess=40 lobe=phong\n"
      "material b specular=0.2,0.2,0.2 lobe=gaussian roughness=0.3 shininess=12\n"
      "columns t material light x y\ndata\n";
  for (int i = 0; i < 40; ++i) {
    base += std::to_string(i / 20.0 - 1) + (i % 2 ? " a " : ",b,") + std::to_string(i % 3) + " " +
            std::to_string(i) + " " + std::to_string(2 * i) + (i % 7 ? "\n" : " # c\r\n");
  }
  const char interesting[] = {'\0', '\n', '\r', ',', ' ', '#',  '-',    '+',
                              '.',  'e',  '9',  'x', '=', '\t', '\xff', '\xc3'};
  std::mt19937_64 rng(1234);
  int ok = 0, errors = 0;
  for (int iter = 0; iter < 4000; ++iter) {
    std::string text = base;
    const int edits = 1 + static_cast<int>(rng() % 4);
    for (int k = 0; k < edits && !text.empty(); ++k) {
      const std::size_t at = rng() % text.size();
      switch (rng() % 5) {
        case 0:
          text[at] = interesting[rng() % sizeof interesting];
          break;
        case 1:
          text[at] = static_cast<char>(rng() % 256);
          break;
        case 2:
          text.erase(at, 1 + rng() % 8);
          break;
        case 3:
          text.insert(at, text.substr(rng() % text.size(), 1 + rng() % 16));
          break;
        default:
          text.resize(at);
          break;
      }
    }
    const auto lines = static_cast<std::uint64_t>(std::count(text.begin(), text.end(), '\n'));
    try {
      parse(text);
      ++ok;
    } catch (const InputError& e) {
      ++errors;
      ASSERT_GE(e.line(), 1u) << e.what();
      ASSERT_LE(e.line(), lines + 1) << e.what();
      ASSERT_FALSE(e.field().empty());
    }
  }
  EXPECT_GT(ok, 100);
  EXPECT_GT(errors, 1000);
}

// ---- Round trip ----------------------------------------------------------------------------

VectorHeader random_header(std::mt19937_64& rng, bool has_light, bool has_xy) {
  std::uniform_real_distribution<double> u01(0, 1);
  VectorHeader h;
  h.eps = std::ldexp(u01(rng) + 0.1, -10);
  h.lights = has_light ? 5 : 1;
  for (int i = 0; i < h.lights; ++i) {
    h.light_intensity.push_back({u01(rng) * 3, i == 0 ? 1.0 : u01(rng), 1 / 3.0});
  }
  h.has_light = has_light;
  h.has_xy = has_xy;
  const VectorLobe lobes[] = {VectorLobe::kPhong, VectorLobe::kBlinn, VectorLobe::kGaussian};
  for (int i = 0; i < 12; ++i) {
    VectorMaterial m;
    m.name = "mat_" + std::to_string(i) + (i % 2 ? ".b" : "-a");
    m.specular = {u01(rng), 0.1 * u01(rng), i == 3 ? 0.0 : std::nextafter(1.0, 0.0)};
    m.lobe = lobes[i % 3];
    if (m.lobe == VectorLobe::kGaussian) {
      m.roughness = i == 2 ? 1.0 : u01(rng) * 0.999 + 1e-3;
      m.shininess = i % 2 ? 1e4 * u01(rng) + 1e-6 : 0;
    } else {
      m.shininess = std::exp(u01(rng) * 12 - 3);
    }
    h.materials.push_back(m);
  }
  return h;
}

std::vector<VectorRow> random_rows(std::mt19937_64& rng, const VectorHeader& h, std::size_t n) {
  std::uniform_real_distribution<double> t_dist(-1, 1.001);
  const double specials[] = {-1.0,
                             -0.0,
                             0.0,
                             1.0,
                             1.001,
                             std::numeric_limits<double>::denorm_min(),
                             -std::numeric_limits<double>::min(),
                             1e-300,
                             std::nextafter(1.0, 0.0),
                             std::nextafter(-1.0, 0.0),
                             0.1,
                             1.0 / 3};
  std::vector<VectorRow> rows(n);
  for (std::size_t i = 0; i < n; ++i) {
    auto& r = rows[i];
    r.t = i < std::size(specials) ? specials[i] : t_dist(rng);
    if (i % 17 == 5) r.t = std::ldexp(r.t, -static_cast<int>(rng() % 1070));
    r.material = static_cast<std::uint32_t>(rng() % h.materials.size());
    if (h.has_light) r.light = static_cast<std::int32_t>(rng() % 5);
    if (h.has_xy) {
      r.x = i % 9 == 0 ? std::numeric_limits<std::int32_t>::max() : static_cast<int>(rng() % 4096);
      r.y = static_cast<std::int32_t>(rng() % 2160);
    }
  }
  return rows;
}

TEST(VectorRoundTrip, EveryFieldBitExact) {
  std::mt19937_64 rng(42);
  TempDir dir;
  for (int variant = 0; variant < 4; ++variant) {
    SCOPED_TRACE(variant);
    const VectorHeader h = random_header(rng, variant & 1, variant & 2);
    const auto rows = random_rows(rng, h, 5000);
    const std::string path = dir.file("rt" + std::to_string(variant) + ".vec");
    {
      VectorWriter w(path, h);
      for (const auto& r : rows) w.write(r);
      EXPECT_EQ(w.rows_written(), rows.size());
      w.commit();
    }
    VectorReader reader(path);
    expect_same_header(h, reader.header());
    const auto back = read_all(reader);
    expect_same_rows(rows, back);
    for (std::size_t i = 0; i < back.size(); ++i) {
      // magic, eps, lights, one line per (non-white) light, 12 materials, columns, data.
      const std::uint64_t header_lines = 3 + static_cast<std::uint64_t>(h.lights) + 12 + 2;
      ASSERT_EQ(back[i].line, header_lines + 1 + i) << i;
    }
  }
}

TEST(VectorRoundTrip, StreamWriterAndWhiteDefault) {
  VectorHeader h;
  h.eps = 1e-3;
  h.lights = 2;  // light_intensity empty: all white
  h.has_light = true;
  h.materials.push_back({"w", {1, 1, 1}, 8, VectorLobe::kBlinn, 0});
  std::ostringstream out;
  VectorWriter w(out, h);
  w.write({0.5, 0, 1, -1, -1, 0});
  w.commit();
  EXPECT_EQ(out.str(),
            "glint-vectors 1\neps 0.001\nlights 2\nmaterial w specular=1,1,1 lobe=blinn "
            "shininess=8\ncolumns t material light\ndata\n0.5 w 1\n");
  VectorHeader back;
  const auto rows = parse(out.str(), &back);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(back.light_intensity.size(), 2u);
  EXPECT_EQ(back.intensity(1), (std::array<double, 3>{1, 1, 1}));
  EXPECT_EQ(h.intensity(1), (std::array<double, 3>{1, 1, 1}));
  EXPECT_THROW(h.intensity(2), std::out_of_range);
}

TEST(VectorWriterTest, RejectsInvalidHeadersAndRows) {
  TempDir dir;
  VectorHeader good;
  good.eps = 1e-3;
  good.materials.push_back({"m", {1, 1, 1}, 10, VectorLobe::kPhong, 0});
  EXPECT_NO_THROW(validate(good));

  auto broken = [&](auto change) {
    VectorHeader h = good;
    change(h);
    return h;
  };
  const std::vector<VectorHeader> bad = {
      broken([](VectorHeader& h) { h.eps = 0; }),
      broken([](VectorHeader& h) { h.eps = std::nan(""); }),
      broken([](VectorHeader& h) { h.version = 2; }),
      broken([](VectorHeader& h) { h.lights = 0; }),
      broken([](VectorHeader& h) {
        h.light_intensity = {{1, 1, 1}, {1, 1, 1}};
      }),
      broken([](VectorHeader& h) {
        h.light_intensity = {{1, -1, 1}};
      }),
      broken([](VectorHeader& h) { h.materials.clear(); }),
      broken([](VectorHeader& h) { h.materials.push_back(h.materials[0]); }),
      broken([](VectorHeader& h) { h.materials[0].name = "has space"; }),
      broken([](VectorHeader& h) { h.materials[0].name = ""; }),
      broken([](VectorHeader& h) { h.materials[0].shininess = 0; }),
      broken([](VectorHeader& h) { h.materials[0].shininess = INFINITY; }),
      broken([](VectorHeader& h) { h.materials[0].roughness = 0.5; }),
      broken([](VectorHeader& h) { h.materials[0].specular[1] = -1; }),
      broken([](VectorHeader& h) {
        h.materials[0].lobe = VectorLobe::kGaussian;
        h.materials[0].roughness = 0;
      }),
      broken([](VectorHeader& h) {
        h.materials[0].lobe = VectorLobe::kGaussian;
        h.materials[0].roughness = 1.5;
      }),
  };
  for (std::size_t i = 0; i < bad.size(); ++i) {
    SCOPED_TRACE(i);
    EXPECT_THROW(validate(bad[i]), std::invalid_argument);
    EXPECT_THROW(VectorWriter(dir.file("bad.vec"), bad[i]), std::invalid_argument);
  }
  EXPECT_TRUE(dir.entries().empty());

  VectorWriter w(dir.file("rows.vec"), good);
  EXPECT_THROW(w.write({std::nan(""), 0, 0, -1, -1, 0}), std::invalid_argument);
  EXPECT_THROW(w.write({INFINITY, 0, 0, -1, -1, 0}), std::invalid_argument);
  EXPECT_THROW(w.write({1.0011, 0, 0, -1, -1, 0}), std::invalid_argument);
  EXPECT_THROW(w.write({-1.0001, 0, 0, -1, -1, 0}), std::invalid_argument);
  EXPECT_THROW(w.write({0.5, 1, 0, -1, -1, 0}), std::invalid_argument);  // material
  EXPECT_THROW(w.write({0.5, 0, 1, -1, -1, 0}), std::invalid_argument);  // no light column
  EXPECT_THROW(w.write({0.5, 0, 0, 3, 4, 0}), std::invalid_argument);    // no x y columns
  w.write({0.5, 0, 0, -1, -1, 0});
  w.commit();
  EXPECT_THROW(w.write({0.5, 0, 0, -1, -1, 0}), std::logic_error);
  VectorReader r(dir.file("rows.vec"));
  EXPECT_EQ(read_all(r).size(), 1u);
}

TEST(VectorWriterTest, NoFileWithoutCommitNoTempAfterCommit) {
  TempDir dir;
  VectorHeader h;
  h.eps = 1e-3;
  h.materials.push_back({"m", {1, 1, 1}, 10, VectorLobe::kPhong, 0});
  const std::string path = dir.file("out.vec");
  {
    VectorWriter w(path, h);
    for (int i = 0; i < 100000; ++i) w.write({i / 100000.0, 0, 0, -1, -1, 0});  // > 1 MiB
    EXPECT_EQ(dir.entries().size(), 1u);  // only the temporary
    EXPECT_FALSE(fs::exists(path));
  }  // no commit
  EXPECT_TRUE(dir.entries().empty());

  // An exception while writing leaves nothing either.
  try {
    VectorWriter w(path, h);
    w.write({0.5, 0, 0, -1, -1, 0});
    w.write({2.0, 0, 0, -1, -1, 0});
  } catch (const std::invalid_argument&) {
  }
  EXPECT_TRUE(dir.entries().empty());

  {
    VectorWriter w(path, h);
    w.write({0.25, 0, 0, -1, -1, 0});
    w.commit();
  }
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"out.vec"});

  // Replacing an existing file: the old content stays until commit.
  {
    VectorWriter w(path, h);
    w.write({-0.75, 0, 0, -1, -1, 0});
    w.write({-0.5, 0, 0, -1, -1, 0});
    VectorReader old(path);
    EXPECT_EQ(read_all(old).size(), 1u);
    w.commit();
  }
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"out.vec"});
  VectorReader r(path);
  const auto rows = read_all(r);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].t, -0.75);
}

TEST(AtomicOutputFileTest, CommitAbortAndErrors) {
  TempDir dir;
  const std::string path = dir.file("a.txt");
  {
    AtomicOutputFile f(path);
    EXPECT_EQ(f.temp_path().rfind(path + ".tmp.", 0), 0u);
    EXPECT_TRUE(fs::exists(f.temp_path()));
    f.stream() << "hello\n";
    EXPECT_FALSE(fs::exists(path));
    f.commit(false);
    EXPECT_TRUE(f.committed());
    EXPECT_THROW(f.commit(), std::logic_error);
  }
  {
    std::ifstream in(path);
    std::string s;
    std::getline(in, s);
    EXPECT_EQ(s, "hello");
  }
  {
    AtomicOutputFile f(path);
    f.stream() << "discarded";
    f.abort();
    EXPECT_FALSE(fs::exists(f.temp_path()));
    f.abort();
    EXPECT_THROW(f.commit(), std::logic_error);
  }
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"a.txt"});
  {
    // Two at once get distinct temporaries; the last commit wins.
    AtomicOutputFile f1(path), f2(path);
    EXPECT_NE(f1.temp_path(), f2.temp_path());
    f1.stream() << "one";
    f2.stream() << "two";
    f1.commit();
    f2.commit();
  }
  {
    std::ifstream in(path);
    std::string s;
    in >> s;
    EXPECT_EQ(s, "two");
  }
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"a.txt"});
  try {
    AtomicOutputFile f(dir.file("no/such/dir/x.txt"));
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("no/such/dir/x.txt"), std::string::npos) << e.what();
  }
  // A target that exists but is not a regular file (here a directory) is refused up front, naming
  // the path, and leaves no temporary: the rename would otherwise replace it (or fail late).
  fs::create_directories(dir.file("isdir"));
  fs::create_directories(dir.file("isdir/sub"));
  try {
    AtomicOutputFile f(dir.file("isdir"));
    ADD_FAILURE() << "a directory target must be refused";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("isdir"), std::string::npos) << e.what();
  }
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"a.txt", "isdir"}));
  // Large writes go through the buffer and around it.
  {
    AtomicOutputFile f(dir.file("big.bin"));
    const std::string chunk(200000, 'q');
    for (int i = 0; i < 10; ++i) f.stream() << chunk << 'r';
    f.commit();
  }
  EXPECT_EQ(fs::file_size(dir.file("big.bin")), 10u * 200001u);
}

// ---- Constant memory: a million rows through an on-the-fly stream ------------------------

// A streambuf that produces a header and then `rows` generated rows, never holding more than one
// line: the reader consumes it in constant memory.
class GeneratedStream : public std::streambuf {
 public:
  GeneratedStream(std::string header, std::uint64_t rows) : line_(std::move(header)), rows_(rows) {
    setg(line_.data(), line_.data(), line_.data() + line_.size());
  }

 protected:
  int_type underflow() override {
    if (next_ >= rows_) return traits_type::eof();
    const std::uint64_t i = next_++;
    line_ = std::to_string(static_cast<double>(i % 2001) / 1000.0 - 1.0) +
            (i % 3 ? ",m1," : " m0 ") + std::to_string(i % 3) + " " + std::to_string(i % 1920) +
            " " + std::to_string(i % 1080) + (i % 1000 == 0 ? "  # checkpoint\r\n" : "\n");
    setg(line_.data(), line_.data(), line_.data() + line_.size());
    return traits_type::to_int_type(line_[0]);
  }

 private:
  std::string line_;
  std::uint64_t rows_;
  std::uint64_t next_ = 0;
};

TEST(VectorStreaming, MillionRowsInConstantMemory) {
  const std::uint64_t n = 1000000;
  GeneratedStream gen(
      "glint-vectors 1\neps 1e-3\nlights 3\n"
      "material m0 specular=1,1,1 shininess=50 lobe=phong\n"
      "material m1 specular=0.5,0.4,0.3 shininess=20 lobe=blinn\n"
      "columns t material light x y\ndata\n",
      n);
  std::istream in(&gen);
  VectorReader reader(in, "generated");
  VectorRow row;
  std::uint64_t count = 0, m1 = 0, light_sum = 0;
  while (reader.next(row)) {
    ASSERT_EQ(row.line, count + 8);
    ASSERT_EQ(row.x, static_cast<std::int32_t>(count % 1920));
    ASSERT_EQ(row.y, static_cast<std::int32_t>(count % 1080));
    m1 += row.material;
    light_sum += static_cast<std::uint64_t>(row.light);
    ++count;
  }
  EXPECT_EQ(count, n);
  EXPECT_EQ(reader.rows_read(), n);
  EXPECT_EQ(m1, n - (n + 2) / 3);
  EXPECT_EQ(light_sum, (n / 3) * 3 + (n % 3 == 2 ? 1 : 0));
}

}  // namespace
}  // namespace glint
