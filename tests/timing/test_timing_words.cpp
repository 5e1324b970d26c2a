// TimingEngine::next_words (the evaluation engine's merge) against next() a request at a time:
// the same statistics and the same state after, for every sink, latency, II and buffer depth
// below, on random skip patterns fed in calls of random sizes (empty ones and ones shorter than
// the buffer among them).
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

#include "timing/timing.h"
#include "timing_support.h"

namespace glint {
namespace {

TEST(TimingWords, EqualsNextPerRequest) {
  std::mt19937_64 rng(9);
  for (const double ready : {1.0, 0.7, 0.2})
    for (const int latency : {0, 1, 4, 12})
      for (const int ii : {1, 2, 5})
        for (const int depth : {1, 2, 8, 40})
          for (const double skip_rate : {0.0, 0.5, 0.94, 1.0}) {
            SCOPED_TRACE(testing::Message() << "ready " << ready << " latency " << latency << " ii "
                                            << ii << " depth " << depth << " skip " << skip_rate);
            const UnitTiming timing{latency, ii, depth};
            const SinkReady sink{ready, 5};
            TimingEngine one(timing, sink), words(timing, sink);
            std::bernoulli_distribution skipped(skip_rate);
            std::uniform_int_distribution<std::size_t> size(0, 90);
            for (int call = 0; call < 40; ++call) {
              std::vector<std::uint64_t> w(size(rng));
              for (auto& x : w) {
                const bool s = skipped(rng);
                x = (std::uint64_t{s} << 63) | (rng() >> 1);  // the low bits are not the flag
                one.next(s);
              }
              words.next_words(w.data(), w.size());
              EXPECT_EQ(one.stats(), words.stats());
            }
            // The state after: the next requests schedule alike.
            for (const bool s : {false, true, false}) {
              const ResultTiming a = one.next(s), b = words.next(s);
              EXPECT_EQ(a.issue, b.issue);
              EXPECT_EQ(a.done, b.done);
              EXPECT_EQ(a.retire, b.retire);
            }
          }
}

// The minimum latency is tracked from a sentinel: before any result it must read 0 like every
// other statistic, and the first result's latency must replace it.
TEST(TimingWords, LatencyMinBeforeAndAfterTheFirstResult) {
  TimingEngine engine(UnitTiming{3, 1, 4}, SinkReady{});
  EXPECT_EQ(engine.stats(), TimingStats{});
  engine.next_words(nullptr, 0);
  EXPECT_EQ(engine.stats(), TimingStats{});
  const std::uint64_t computed = 0;
  engine.next_words(&computed, 1);
  EXPECT_EQ(engine.stats().latency_min, 4u);  // issue at 0, done after 1 + L cycles
  EXPECT_EQ(engine.stats().latency_max, 4u);
  engine.next(true);  // a skipped request passes the unit in one cycle but retires in order
  EXPECT_EQ(engine.stats().latency_min, 4u);
}

}  // namespace
}  // namespace glint
