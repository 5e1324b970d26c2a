// Process-wide SystemC setup shared by every entry point that elaborates modules.
#include "rtl_model/sc_setup.h"

#include <cstdlib>

namespace glint {

void quiet_systemc_banner() {
  // SystemC prints its banner on stdout when the first simulation context is created; glint's
  // stdout carries results (and JSON), so the banner is turned off before that happens.
  setenv("SYSTEMC_DISABLE_COPYRIGHT_MESSAGE", "1", 0);
}

}  // namespace glint
