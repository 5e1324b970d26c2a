#pragma once

namespace glint {

// Call before the first SystemC object is created.
void quiet_systemc_banner();

}  // namespace glint
