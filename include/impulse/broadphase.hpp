// impulse/broadphase.hpp — the broad phase module: which boxes overlap.
// Five broad phases behind one concept (broadphase/broad_phase.hpp), chosen
// by a config's `broadphase`: brute_force (the reference), sweep_and_prune,
// spatial_hash, dynamic_bvh and octree. docs/broadphase.md compares them.
#pragma once

#include "broadphase/broad_phase.hpp"
#include "broadphase/brute_force.hpp"
#include "broadphase/dynamic_bvh.hpp"
#include "broadphase/fwd.hpp"
#include "broadphase/octree.hpp"
#include "broadphase/detail/pair_tracker.hpp"
#include "broadphase/proxy.hpp"
#include "broadphase/detail/proxy_store.hpp"
#include "broadphase/spatial_hash.hpp"
#include "broadphase/sweep_and_prune.hpp"
