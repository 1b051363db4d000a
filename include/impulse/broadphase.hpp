// impulse/broadphase.hpp — the broad phase module: which boxes overlap.
// (brute_force so far; sweep_and_prune, spatial_hash, dynamic_bvh and
// octree follow behind the same concept.)
#pragma once

#include "broadphase/broad_phase.hpp"
#include "broadphase/brute_force.hpp"
#include "broadphase/sweep_and_prune.hpp"
#include "broadphase/fwd.hpp"
#include "broadphase/pair_tracker.hpp"
#include "broadphase/proxy.hpp"
#include "broadphase/proxy_store.hpp"
