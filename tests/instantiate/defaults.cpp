// The default configurations' worlds and particle systems, compiled once for
// the unit-test executable, which is built with IMPULSE_EXTERN_TEMPLATES=1
// (impulse/core/extern_templates.hpp).
#include "impulse/instantiate.hpp"
