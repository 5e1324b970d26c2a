// Must not compile: units cannot see cost (cost builds on units).
#include "cost/cost_model.h"
