// impulse/particles/fwd.hpp — the particle module's names.
#pragma once

namespace impulse::particles {

template <class T> struct gravity;
template <class T> struct drag;
template <class T> struct point_forces;
template <class T> struct wind;
template <class T> class springs;
template <class T> struct plane_collider;
template <class T> struct emitter;
template <class Config, template <class> class... Forces>
class particle_system;

}  // namespace impulse::particles
