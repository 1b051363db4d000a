// impulse/world.hpp — the world module: impulse::world<Config>, its bodies,
// contacts, solver, queries, events, debug drawing and snapshots.
#pragma once

#include "config.hpp"
#include "world/body_def.hpp"
#include "world/debug_draw.hpp"
#include "world/fwd.hpp"
#include "world/world.hpp"
#include "world/world_events.hpp"
#include "world/world_ray_hit.hpp"
#include "world/world_settings.hpp"
