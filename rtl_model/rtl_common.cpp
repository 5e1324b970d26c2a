#include "rtl_model/rtl_common.h"

namespace glint::rtl {

std::ostream& operator<<(std::ostream& os, const Request& r) {
  return os << "{seq " << r.seq << ", t " << r.t_raw << ", slot " << r.slot
            << (r.last ? ", last}" : "}");
}

std::ostream& operator<<(std::ostream& os, const Result& r) {
  if (!r.valid) return os << "{}";
  return os << "{seq " << r.seq << ", t " << r.t_raw << ", slot " << r.slot << ", value " << r.value
            << (r.skipped ? ", skipped" : "") << ", issue " << r.issue << ", done " << r.done
            << (r.last ? ", last}" : "}");
}

}  // namespace glint::rtl
