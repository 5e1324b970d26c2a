// A unit built for a trace's slots, for the tests that link the eval layer (activity, energy).
#pragma once

#include <memory>
#include <string>

#include "eval/evaluate.h"
#include "io/vectors.h"
#include "units/catalogue.h"
#include "vector_rows.h"

namespace glint::test {

struct TraceUnit {
  VectorHeader header;
  SlotMap slots;
  std::unique_ptr<SpecularUnit> unit;
};

// `spec` built for the slots of a shipped trace (traces/<trace>).
inline TraceUnit trace_unit(const std::string& spec, const std::string& trace = "phong_basic.vec") {
  TraceUnit b;
  read_rows(std::string(GLINT_SOURCE_DIR) + "/traces/" + trace, b.header);
  b.slots = make_slots(b.header);
  b.unit = make_unit(parse_unit_spec(spec), b.slots);
  return b;
}

}  // namespace glint::test
