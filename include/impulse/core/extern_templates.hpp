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
