// Must not compile: io cannot see eval (a higher layer).
#include "eval/evaluate.h"
