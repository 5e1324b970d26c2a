// Evaluator::add_batch: the same statistics, digests and results as add() row by row, for any
// thread count (the render and, later, sweep engines rely on it).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "eval/evaluate.h"
#include "eval/parallel.h"
#include "io/vectors.h"
#include "test_support.h"
#include "units/catalogue.h"
#include "vector_rows.h"

namespace glint {
namespace {

std::vector<UnitSpec> every_unit() {
  std::vector<UnitSpec> specs;
  for (const std::string& name : unit_names()) specs.push_back(parse_unit_spec(name));
  specs.push_back(parse_unit_spec("hast:d=3"));
  return specs;
}

class BatchEval : public ::testing::TestWithParam<std::string> {};

TEST_P(BatchEval, EqualsRowByRowForAnyThreadCount) {
  VectorHeader header;
  const std::vector<VectorRow> rows =
      test::read_rows(std::string(GLINT_SOURCE_DIR) + "/traces/" + GetParam(), header);
  ASSERT_FALSE(rows.empty());
  Evaluator serial(header, every_unit());
  for (const VectorRow& row : rows) serial.add(row);
  const std::string expected = serial.to_json().dump();

  for (int threads : {1, 2, 3, 7}) {
    Evaluator batched(header, every_unit());
    BatchResults results;
    // Uneven batches, so that a batch boundary falls anywhere.
    std::size_t at = 0, size = 1;
    while (at < rows.size()) {
      const std::size_t n = std::min(size, rows.size() - at);
      batched.add_batch(rows.data() + at, n, results, threads);
      ASSERT_EQ(results.rows, n);
      for (std::size_t u = 0; u < batched.units().size(); ++u) {
        const SpecularUnit& unit = *batched.units()[u];
        for (std::size_t i = 0; i < n; ++i) {
          const VectorRow& row = rows[at + i];
          const std::size_t slot = batched.slots().slot(row);
          const std::int64_t t_raw = quantize_input(row.t, unit.in_format());
          EXPECT_EQ(results.raw[u * n + i], unit.eval_with_skip(slot, t_raw));
          EXPECT_EQ(results.skipped[u * n + i], unit.skip(slot, t_raw) ? 1 : 0);
        }
      }
      EXPECT_EQ(results.reference[0],
                reference_value(batched.slots(), batched.slots().slot(rows[at]), rows[at].t));
      at += n;
      size = size * 3 + 1;
    }
    EXPECT_EQ(batched.to_json().dump(), expected) << threads << " threads";
  }
}

INSTANTIATE_TEST_SUITE_P(Traces, BatchEval,
                         ::testing::Values("multi_light.vec", "hard_cases.vec", "pixels.vec"),
                         [](const auto& info) {
                           std::string n = info.param;
                           return n.substr(0, n.find('.'));
                         });

TEST(ParallelFor, RunsEveryTaskOnceAndRethrows) {
  std::vector<int> hits(1000, 0);
  parallel_for(hits.size(), 4, [&](std::size_t i) { hits[i] += 1; });
  for (int h : hits) EXPECT_EQ(h, 1);
  EXPECT_THROW(parallel_for(100, 3,
                            [](std::size_t i) {
                              if (i == 57) throw std::runtime_error("task 57");
                            }),
               std::runtime_error);
}

}  // namespace
}  // namespace glint
