// Must not compile: scene sees only io and reference, not the units.
#include "units/catalogue.h"
