// How GoogleTest prints a TimingStats when an EXPECT_EQ on two of them fails (operator== is in
// timing/timing.h): every field, so the one that differs shows.
#pragma once

#include <ostream>

#include "timing/timing.h"

namespace glint {

inline void PrintTo(const TimingStats& s, std::ostream* os) {
  *os << "results " << s.results << " computed " << s.computed << " cycles " << s.cycles
      << " stall_credit " << s.stall_credit << " stall_unit " << s.stall_unit << " sink_wait "
      << s.sink_wait << " latency " << s.latency_min << ".." << s.latency_max << " sum "
      << s.latency_sum;
}

}  // namespace glint
