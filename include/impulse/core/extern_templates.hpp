// impulse/core/extern_templates.hpp — compile once, link everywhere: explicit
// instantiation of the world and the particle system.
//
// Header-only templates are compiled again in every translation unit that
// uses them: a program that creates a world and steps it compiles the whole
// pipeline, for 2 to 3 s at -O0. An explicit instantiation declaration
// (`extern template class`) tells the compiler that one translation unit of
// the program holds the compiled members, so every other one only parses
// the headers. The members that do real work (step, create_body's
// shape-independent part, create_joint, ray_cast, the special members, ...)
// are defined outside their classes, not inline, so that neither g++ nor
// clang compiles them where the declaration is seen, at -O0 or at -O2.
//
// The default configurations, impulse::default_config (float) and
// impulse::default_double_config (double):
//
//   - build every translation unit with IMPULSE_EXTERN_TEMPLATES=1
//     (CMake: target_compile_definitions(app PRIVATE IMPULSE_EXTERN_TEMPLATES=1));
//   - include "impulse/instantiate.hpp" in exactly one .cpp file.
//
// Then world<default_config>, world<default_double_config>, and the
// particle system particle_system<..., gravity, drag, point_forces> of both
// are compiled in that file only. Another configuration, in a header the
// program shares:
//
//   struct my_config : impulse::default_config { using scalar = double; };
//   IMPULSE_DECLARE_WORLD(my_config);          // everywhere: only parsed
//
// and in one .cpp file:
//
//   IMPULSE_INSTANTIATE_WORLD(my_config);      // compiled here, once
//
// The same pair exists for particle_system (its config, then its forces).
//
// Most of a world's compiled code depends on its scalar alone: the narrow
// phase's pair tests of the default shapes (sphere, box, capsule,
// convex_hull, plane, triangle_mesh, heightfield; a compound's entries are
// empty, its children's being these), each pair's time of impact and a
// ball's sweep against each convex shape. IMPULSE_EXTERN_TEMPLATES=1
// declares them extern for float and double as well
// (IMPULSE_DECLARE_NARROW_PHASE), and impulse/instantiate.hpp compiles them
// (IMPULSE_INSTANTIATE_NARROW_PHASE): a file that instantiates a world of
// its own configuration then compiles only what that configuration
// changes. One such file at g++ -O3 -march=native took 35 s with the
// narrow phase and 28 s without it. The solvers and the dynamic BVH depend
// on the scalar alone too (IMPULSE_DECLARE_SCALAR_PARTS): without them,
// 23 s where it took 29 (two compiles side by side).
// A member template (create_body<Shape>, draw<D>, for_each_contact<F>,
// step<Field>) is still compiled where it is used; create_body's part that
// depends on the shape is short.
#pragma once

/// 1: the headers declare the default configurations' instantiations extern
/// (one translation unit must then include impulse/instantiate.hpp).
#ifndef IMPULSE_EXTERN_TEMPLATES
#define IMPULSE_EXTERN_TEMPLATES 0
#endif

/// impulse::world<Config> is compiled in another translation unit.
#define IMPULSE_DECLARE_WORLD(...) extern template class impulse::world<__VA_ARGS__>
/// Compiles impulse::world<Config> here: in one translation unit of the program.
#define IMPULSE_INSTANTIATE_WORLD(...) template class impulse::world<__VA_ARGS__>

/// impulse::particles::particle_system<Config, Forces...> is compiled in another translation unit.
#define IMPULSE_DECLARE_PARTICLE_SYSTEM(...) extern template class impulse::particles::particle_system<__VA_ARGS__>
/// Compiles impulse::particles::particle_system<Config, Forces...> here, in one translation unit.
#define IMPULSE_INSTANTIATE_PARTICLE_SYSTEM(...) template class impulse::particles::particle_system<__VA_ARGS__>

/// The narrow phase of the default shapes in scalar T, compiled in another
/// translation unit: what the world's dispatcher calls for each ordered
/// pair (narrowphase/dispatch.hpp), time_of_impact for each pair of convex
/// shapes and of a convex shape and a mesh's triangle, and sphere_cast
/// against each convex shape.
#define IMPULSE_DECLARE_NARROW_PHASE(T) IMPULSE_DETAIL_NARROW_PHASE(extern template, T)
/// Compiles the narrow phase of the default shapes in scalar T here, in one translation unit.
#define IMPULSE_INSTANTIATE_NARROW_PHASE(T) IMPULSE_DETAIL_NARROW_PHASE(template, T)

/// The rest of a world that depends on its scalar alone, compiled in
/// another translation unit: the two solvers (sequential_impulse,
/// soft_step) and the dynamic BVH. Their entry points are defined outside
/// their classes, so that a file that only sees this declaration compiles
/// none of them.
#define IMPULSE_DECLARE_SCALAR_PARTS(T) IMPULSE_DETAIL_SCALAR_PARTS(extern template, T)
/// Compiles the solvers and the dynamic BVH of scalar T here, in one translation unit.
#define IMPULSE_INSTANTIATE_SCALAR_PARTS(T) IMPULSE_DETAIL_SCALAR_PARTS(template, T)

// The lists behind these: `how` is `template` or `extern template`. The
// last item of each has no semicolon, so that a use ends with one.
#define IMPULSE_DETAIL_SCALAR_PARTS(how, T)                                                                 \
  how class impulse::basic_sequential_impulse<T>;                                                          \
  how class impulse::basic_soft_step<T>;                                                                   \
  how class impulse::broadphase::basic_dynamic_bvh<T>
#define IMPULSE_DETAIL_NARROW_PHASE(how, T)                                                                 \
  IMPULSE_DETAIL_COLLIDE_ROW(how, sphere, T);                                                              \
  IMPULSE_DETAIL_COLLIDE_ROW(how, box, T);                                                                 \
  IMPULSE_DETAIL_COLLIDE_ROW(how, capsule, T);                                                             \
  IMPULSE_DETAIL_COLLIDE_ROW(how, convex_hull, T);                                                         \
  IMPULSE_DETAIL_COLLIDE_ROW(how, plane, T);                                                               \
  IMPULSE_DETAIL_COLLIDE_ROW(how, triangle_mesh, T);                                                       \
  IMPULSE_DETAIL_COLLIDE_ROW(how, heightfield, T);                                                         \
  IMPULSE_DETAIL_COLLIDE_ROW(how, compound, T);                                                            \
  IMPULSE_DETAIL_IMPACT_ROW(how, sphere, T);                                                               \
  IMPULSE_DETAIL_IMPACT_ROW(how, box, T);                                                                  \
  IMPULSE_DETAIL_IMPACT_ROW(how, capsule, T);                                                              \
  IMPULSE_DETAIL_IMPACT_ROW(how, convex_hull, T);                                                          \
  IMPULSE_DETAIL_TRIANGLE_IMPACT(how, sphere, T);                                                          \
  IMPULSE_DETAIL_TRIANGLE_IMPACT(how, box, T);                                                             \
  IMPULSE_DETAIL_TRIANGLE_IMPACT(how, capsule, T);                                                         \
  IMPULSE_DETAIL_TRIANGLE_IMPACT(how, convex_hull, T);                                                     \
  IMPULSE_DETAIL_BALL_SWEEP(how, sphere, T);                                                               \
  IMPULSE_DETAIL_BALL_SWEEP(how, box, T);                                                                  \
  IMPULSE_DETAIL_BALL_SWEEP(how, capsule, T);                                                              \
  IMPULSE_DETAIL_BALL_SWEEP(how, convex_hull, T)
#define IMPULSE_DETAIL_COLLIDE(how, A, B, T)                                                                \
  how std::size_t impulse::narrowphase::detail::call_collide<impulse::A<T>, impulse::B<T>, T>(              \
      const void*, const impulse::transform<T>&, const void*, const impulse::transform<T>&, T,              \
      std::span<impulse::contact_manifold<T>>)
#define IMPULSE_DETAIL_COLLIDE_ROW(how, A, T)                                                               \
  IMPULSE_DETAIL_COLLIDE(how, A, sphere, T);                                                               \
  IMPULSE_DETAIL_COLLIDE(how, A, box, T);                                                                  \
  IMPULSE_DETAIL_COLLIDE(how, A, capsule, T);                                                              \
  IMPULSE_DETAIL_COLLIDE(how, A, convex_hull, T);                                                          \
  IMPULSE_DETAIL_COLLIDE(how, A, plane, T);                                                                \
  IMPULSE_DETAIL_COLLIDE(how, A, triangle_mesh, T);                                                        \
  IMPULSE_DETAIL_COLLIDE(how, A, heightfield, T);                                                           \
  IMPULSE_DETAIL_COLLIDE(how, A, compound, T)
#define IMPULSE_DETAIL_IMPACT(how, A, B, T)                                                                 \
  how impulse::narrowphase::toi_result<T> impulse::narrowphase::time_of_impact<impulse::A<T>, impulse::B<T>, T>( \
      const impulse::A<T>&, const impulse::narrowphase::sweep<T>&, const impulse::B<T>&,                    \
      const impulse::narrowphase::sweep<T>&, const impulse::narrowphase::toi_options<T>&) noexcept
#define IMPULSE_DETAIL_IMPACT_ROW(how, A, T)                                                                \
  IMPULSE_DETAIL_IMPACT(how, A, sphere, T);                                                                \
  IMPULSE_DETAIL_IMPACT(how, A, box, T);                                                                   \
  IMPULSE_DETAIL_IMPACT(how, A, capsule, T);                                                               \
  IMPULSE_DETAIL_IMPACT(how, A, convex_hull, T)
/// A convex shape's time of impact against one triangle of a mesh or a
/// heightfield (continuous collision, world/detail/continuous.hpp).
#define IMPULSE_DETAIL_TRIANGLE_IMPACT(how, A, T)                                                           \
  how impulse::narrowphase::toi_result<T>                                                                   \
  impulse::narrowphase::time_of_impact<impulse::A<T>, impulse::narrowphase::detail::convex_triangle<T>, T>( \
      const impulse::A<T>&, const impulse::narrowphase::sweep<T>&,                                          \
      const impulse::narrowphase::detail::convex_triangle<T>&, const impulse::narrowphase::sweep<T>&,       \
      const impulse::narrowphase::toi_options<T>&) noexcept
#define IMPULSE_DETAIL_BALL_SWEEP(how, B, T)                                                                \
  how impulse::narrowphase::ray_hit<T> impulse::narrowphase::sphere_cast<impulse::B<T>, T>(                 \
      const impulse::ray<T>&, T, const impulse::B<T>&, const impulse::transform<T>&, T) noexcept
