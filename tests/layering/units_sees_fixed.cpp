// Must compile: units links fixed (the control for the probes that must fail).
#include "fixed/fixed_point.h"
#include "units/common.h"
