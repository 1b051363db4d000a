// impulse/world.hpp — the world module: impulse::world<Config>, its bodies,
// contacts, solver, queries, events, debug drawing and snapshots.
#pragma once

#include "config.hpp"
#include "world/body_def.hpp"
#include "world/debug_draw.hpp"
#include "world/fwd.hpp"
#include "world/world.hpp"
