// Must not compile: cost (primitives below the units) cannot see units.
#include "units/catalogue.h"
