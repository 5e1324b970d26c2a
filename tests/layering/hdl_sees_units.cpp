// Must not compile: the hdl layer (Verilog text) sits below units; each unit's generator calls it.
#include "hdl/verilog.h"
#include "units/unit.h"
