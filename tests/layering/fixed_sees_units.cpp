// Must not compile: fixed (the lowest layer) cannot see units.
#include "units/common.h"
