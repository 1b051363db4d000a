// impulse/core.hpp — the core module: version, assertions, error reporting,
// the SIMD batch type and the policy concepts. Depends on the standard library only.
#pragma once

#include "core/aligned_array.hpp"
#include "core/detail/assert.hpp"
#include "core/batch.hpp"
#include "core/error.hpp"
#include "core/fwd.hpp"
#include "core/policy.hpp"
#include "core/random.hpp"
#include "core/slot_map.hpp"
#include "core/task_system.hpp"
#include "core/version.hpp"
