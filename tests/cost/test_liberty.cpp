// liberty_registers (cost/liberty.h): the sequential cells of a Liberty library, which
// `glint synth --liberty` counts as flip-flops. The shipped test library, the groups that make a
// cell sequential and the words that must not, and inputs that once overflowed the stack.
#include <gtest/gtest.h>

#include <chrono>
#include <set>
#include <string>

#include "cost/liberty.h"
#include "test_support.h"

namespace {

using glint::liberty_registers;
using Names = std::set<std::string>;

TEST(Liberty, TheTinyLibraryHasOneFlipFlop) {
  const std::string text = glint::test::read_file(GLINT_SOURCE_DIR "/tests/rtl/tiny.lib");
  EXPECT_EQ(liberty_registers(text), Names{"DFF"});
}

TEST(Liberty, SequentialGroupsAndNames) {
  const std::string lib = R"lib(library(x) {
    cell ( "DFFR_X1" ) { ff (IQ, IQN) { clocked_on : CK; } }
    cell(LAT) { latch(IQ, IQN) { enable : G; } }
    cell(BANK4) { ff_bank ( IQ, IQN, 4 ) { } }
    cell(LBANK) { latch_bank(IQ, IQN, 2) { } }
    cell(BUF) { function : "buff(A)"; cell_footprint : ff; }
    cell(ODD) { stuff(x) ; ffx(y); }
    cell($weird.name[0]) {
      ff
        (IQ) {}
    }
    subcell(NOTACELL) { ff(IQ) {} }
  })lib";
  EXPECT_EQ(liberty_registers(lib), (Names{"DFFR_X1", "LAT", "BANK4", "LBANK", "$weird.name[0]"}));
  EXPECT_TRUE(liberty_registers("").empty());
  EXPECT_TRUE(liberty_registers("cell").empty());
  EXPECT_TRUE(liberty_registers("cell(").empty());
  EXPECT_TRUE(liberty_registers("cell(\"A").empty());
  EXPECT_TRUE(liberty_registers("cell()  ff(").empty());
  EXPECT_EQ(liberty_registers("cell(A)ff("), Names{"A"});
}

// std::regex recursed once per blank after `cell` and died near 100 000 of them.
TEST(Liberty, LongRunsOfBlanksAndManyCells) {
  const std::string blanks(2'000'000, ' ');
  EXPECT_EQ(liberty_registers("cell" + blanks + "(A" + blanks + ") { ff" + blanks + "(IQ) }"),
            Names{"A"});
  std::string many;
  for (int i = 0; i < 200'000; ++i) many += "cell(C" + std::to_string(i) + ") { ff(IQ) }\n";
  EXPECT_EQ(liberty_registers(many).size(), 200'000u);
  std::string opens;
  for (int i = 0; i < 1'000'000; ++i) opens += "cell(";
  EXPECT_TRUE(liberty_registers(opens).empty());
}

}  // namespace

namespace {

TEST(Liberty, TheSmallestTwoInputNandIsTheUnitOfEquivalents) {
  const std::string lib = R"lib(library(x) {
    cell(NAND2X2) { area : 32; pin(Y) { direction : output; function : "(!(A B))"; } }
    cell(NAND2X1) { area : 24; pin(Y) { direction : output; function : "(!(A B))"; } }
    cell(NAND3X1) { area : 36; pin(Y) { function : "(!((A B) C))"; } }
    cell(AND2X1) { area : 20; pin(Y) { function : "(A B)"; } }
    cell(NANDSELF) { area : 1; pin(Y) { function : "!(A&A)"; } }
    cell(DFFN) { area : 2; ff(IQ, IQN) { } pin(Q) { function : "!(A B)"; } }
  })lib";
  const glint::Nand2 n = glint::liberty_nand2(lib);
  EXPECT_EQ(n.cell, "NAND2X1");
  EXPECT_EQ(n.area, 24);
}

TEST(Liberty, NandFunctionsInEveryNotation) {
  for (const char* f : {"!(A B)", "!(A&B)", "!(A * B)", "(A*B)'", "(!(IN1  IN2))"}) {
    const std::string lib =
        std::string("library(x) { cell(N) { area : 3; pin(Y) { function : \"") + f + "\"; } } }";
    EXPECT_EQ(glint::liberty_nand2(lib).cell, "N") << f;
  }
  for (const char* f : {"!(A+B)", "(A B)", "!(A B C)", "!A", "!(A)"}) {
    const std::string lib =
        std::string("library(x) { cell(N) { area : 3; pin(Y) { function : \"") + f + "\"; } } }";
    EXPECT_EQ(glint::liberty_nand2(lib).cell, "") << f;
  }
  const std::string tiny = glint::test::read_file(GLINT_SOURCE_DIR "/tests/rtl/tiny.lib");
  EXPECT_EQ(glint::liberty_nand2(tiny).cell, "NAND2");
}

}  // namespace

namespace {

// The cell abc buffers high fan-out nets with (cmd_synth.cpp): the smallest one-input identity
// with delay tables (BUFX1 has none).
TEST(Liberty, TheSmallestBufferIsTheOneAbcBuffersWith) {
  const std::string lib = R"lib(library(x) {
    cell(BUFX4) { area : 32; pin(A) { direction : input; } pin(Y) { direction : output;
      function : "A"; timing() { cell_rise(t) { } } } }
    cell(BUFX2) { area : 24; pin(A) { direction : input; } pin(Y) { direction : output;
      function : "(A)"; timing() { cell_rise(t) { } } } }
    cell(BUFX1) { area : 20; pin(A) { direction : input; } pin(Y) { direction : output;
      function : "A"; } }
    cell(INVX1) { area : 16; pin(A) { direction : input; } pin(Y) { direction : output;
      function : "(!A)"; } }
    cell(AND2) { area : 8; pin(A) { direction : input; } pin(B) { direction : input; }
      pin(Y) { direction : output; function : "A"; } }
    cell(LATCH) { area : 4; latch(IQ, IQN) { } pin(D) { direction : input; }
      pin(Q) { direction : output; function : "D"; } }
    cell(NOAREA) { pin(A) { direction : input; } pin(Y) { direction : output; function : "A"; } }
  })lib";
  EXPECT_EQ(glint::liberty_buffer(lib), "BUFX2");
  EXPECT_EQ(glint::liberty_buffer("library(x) { cell(INVX1) { area : 16; pin(A) { direction : "
                                  "input; } pin(Y) { direction : output; function : \"!A\"; } } }"),
            "");
  EXPECT_EQ(glint::liberty_buffer(""), "");
  // Its BUF has no delay tables: abc cannot buffer with it.
  EXPECT_EQ(glint::liberty_buffer(glint::test::read_file(GLINT_SOURCE_DIR "/tests/rtl/tiny.lib")),
            "");
}

}  // namespace
