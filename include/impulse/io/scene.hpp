// impulse/io/scene.hpp — scenes described in JSON files: bodies, shapes,
// materials, joints, particle systems and the world's settings, with rows,
// grids and paths of copies so that a domino chain is a few lines. The
// schema, with an example of every element, is docs/scenes.md.
//
//   impulse::world<my_config> world;
//   auto scene = impulse::io::read_scene<float>("dominoes.json");  // parsed and checked
//   auto ids = impulse::io::add_scene(world, scene);               // all of it or nothing
//   impulse::body_id first = ids.body("domino[0]");
//
// Reading is two stages. read_scene / parse_scene turn the text into a
// scene<T>: plain data, every value checked (shapes built, so a flat hull is
// refused here), body references resolved, copies expanded; it touches no
// world. add_scene then puts it into a world, and if anything there is
// refused (a shape the world's config does not compile) the world is put
// back as it was. Every error is an io::scene_error whose message names the
// file, the JSON path and what was expected.
//
// What a file may ask for is bounded over the whole document (scene_limits):
// its size, its JSON values and nesting, and the bodies, joints, particles,
// vertices and triangles it makes. Each limit is checked before the memory it
// guards is allocated, so a few kilobytes cannot ask for gigabytes.
//
// Needs nlohmann/json (Debian's nlohmann-json3-dev); the rest of impulse
// does not, and the single header does not include this file.
#pragma once

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <ios>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "detail/scene_parser.hpp"
#include "scene_data.hpp"

namespace impulse::io {

namespace detail {

/// Whether a particle_system's force list holds F.
template <class System, template <class> class F>
struct system_has_force : std::false_type {};
template <class C, template <class> class... Fs, template <class> class F>
struct system_has_force<particles::particle_system<C, Fs...>, F>
    : std::bool_constant<(std::is_same_v<F<typename C::scalar>, Fs<typename C::scalar>> || ...)> {};

/// A text or file of `bytes`, past limits.bytes.
[[noreturn]] inline void refuse_size(const std::string& file, std::uintmax_t bytes, const scene_limits& limits) {
  throw scene_error(file, "",
                    std::to_string(bytes) + " bytes, more than the " + std::to_string(limits.bytes) +
                        " a scene may have (scene_limits::bytes)",
                    error_code::capacity_exceeded);
}

}  // namespace detail

/// Reads a scene from JSON text. `file` names it in error messages.
template <scalar_type T>
[[nodiscard]] scene<T> parse_scene(std::string_view text, const std::string& file = "<scene>",
                                   const scene_limits& limits = {}) {
  using detail::json;
  if (text.size() > limits.bytes) detail::refuse_size(file, text.size(), limits);
  // The text is read twice: first without building anything, so that too
  // many values, too deep a nesting or a key given twice is refused before
  // the document takes memory in proportion to it; then into the document.
  detail::scan_document(text, file, limits.json_values, limits.depth);
  json document;
  try {
    document = json::parse(text.begin(), text.end());
  } catch (const json::exception& e) {
    throw scene_error(file, "", std::string("not JSON: ") + e.what());  // the scan has refused it already
  }
  return detail::scene_parser<T>(document, file, limits).parse();
}

/// Reads a scene file. A file larger than limits.bytes is refused by its
/// size, before it is read.
template <scalar_type T>
[[nodiscard]] scene<T> read_scene(const std::string& path, const scene_limits& limits = {}) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw scene_error(path, "", "cannot open the file", error_code::out_of_range);
  // A file's size is its end's position. A pipe cannot seek (its size is
  // then -1, and the stream is cleared to read it from where it is).
  in.seekg(0, std::ios::end);
  const std::streamoff size = in ? std::streamoff(in.tellg()) : -1;
  if (size > 0 && std::uintmax_t(size) > limits.bytes) detail::refuse_size(path, std::uintmax_t(size), limits);
  in.clear();
  in.seekg(0, std::ios::beg);
  in.clear();
  std::string text;
  if (size > 0) text.reserve(std::size_t(size));
  // In pieces, so that a pipe, or a file that grows while it is read, is
  // still cut off one piece past the limit.
  char piece[1 << 16];
  while (in.read(piece, sizeof piece) || in.gcount() > 0) {
    text.append(piece, std::size_t(in.gcount()));
    if (text.size() > limits.bytes) detail::refuse_size(path, text.size(), limits);
  }
  return parse_scene<T>(text, path, limits);
}

/// Puts a scene's bodies and joints into `world`, and its settings if the
/// file had any. All or nothing: on an error the world is restored as it
/// was, and the error names the element at fault.
template <class World>
scene_ids add_scene(World& world, const scene<typename World::scalar>& s) {
  using T = typename World::scalar;
  // Shapes the world's config does not compile are found before anything changes.
  for (const scene_body<T>& b : s.bodies) {
    std::visit(
        [&](const auto& shape) {
          using Shape = std::decay_t<decltype(shape)>;
          constexpr bool compiled =
              impulse::detail::shape_store<typename World::shapes, T>::template index_of<Shape>() <
              World::shapes::size;
          if constexpr (!compiled)
            throw scene_error(s.file, b.path + "/shape",
                              "this world's config does not compile the shape (add it to config::shapes)");
        },
        *b.shape);
  }
  scene_ids ids;
  const auto before = world.snapshot();
  const std::string* at = nullptr;
  try {
    for (const scene_body<T>& b : s.bodies) {
      at = &b.path;
      const body_id id = std::visit(
          [&](const auto& shape) -> body_id {
            using Shape = std::decay_t<decltype(shape)>;
            if constexpr (impulse::detail::shape_store<typename World::shapes, T>::template index_of<Shape>() <
                          World::shapes::size)
              return world.create_body(b.def, shape);
            else
              return body_id{};  // refused above
          },
          *b.shape);
      ids.bodies.push_back(id);
      if (!b.name.empty()) ids.body_names.emplace(b.name, id);
    }
    for (const scene_joint<T>& j : s.joints) {
      at = &j.path;
      joint_def<T> def = j.def;
      def.body_a = ids.bodies[j.body_a];
      def.body_b = ids.bodies[j.body_b];
      const joint_id id = world.create_joint(def);
      ids.joints.push_back(id);
      if (!j.name.empty()) ids.joint_names.emplace(j.name, id);
    }
    if (s.has_settings) {
      typename World::settings_type settings;
      static_cast<impulse::detail::world_settings_base<T>&>(settings) = s.settings;
      settings.solver = s.settings.solver.template for_solver<typename World::settings_type::solver_settings_type>();
      world.set_settings(settings);
    }
  } catch (const invalid_argument& e) {
    world.restore(before);
    throw scene_error(s.file, at ? *at : std::string(), e.what(), e.code());
  } catch (...) {
    world.restore(before);
    throw;
  }
  return ids;
}

/// Sets a particle system as a scene's particle_scene says: its forces'
/// parameters, planes, emitters and particles (added to those it has). A
/// force the system's force list lacks, or more particles than it has
/// room for, is an error and the system is unchanged.
template <class System>
void add_particles(System& system, const particle_scene<typename System::scalar>& p,
                   const std::string& file = "<scene>") {
  const auto missing = [&](const char* force) {
    throw scene_error(file, p.path + "/forces/" + force,
                      std::string("this particle_system's force list has no ") + force);
  };
  if (p.gravity && !detail::system_has_force<System, particles::gravity>::value) missing("gravity");
  if (p.drag && !detail::system_has_force<System, particles::drag>::value) missing("drag");
  if (p.wind && !detail::system_has_force<System, particles::wind>::value) missing("wind");
  if (p.attractors && !detail::system_has_force<System, particles::point_forces>::value) missing("attractors");
  if (p.springs && !detail::system_has_force<System, particles::springs>::value) missing("springs");
  if (system.size() + p.initial.size() > system.capacity())
    throw scene_error(file, p.path + "/particles",
                      "more particles than the system has room for (" + std::to_string(system.capacity()) + ")",
                      error_code::capacity_exceeded);
  if (p.springs && !system.empty())
    throw scene_error(file, p.path + "/forces/springs", "springs name particles by index: the system must be empty");
  // Everything was checked when the scene was read; nothing below can fail.
  if constexpr (detail::system_has_force<System, particles::gravity>::value)
    if (p.gravity) system.template force<particles::gravity>() = *p.gravity;
  if constexpr (detail::system_has_force<System, particles::drag>::value)
    if (p.drag) system.template force<particles::drag>() = *p.drag;
  if constexpr (detail::system_has_force<System, particles::wind>::value)
    if (p.wind) system.template force<particles::wind>() = *p.wind;
  if constexpr (detail::system_has_force<System, particles::point_forces>::value)
    if (p.attractors) system.template force<particles::point_forces>() = *p.attractors;
  for (const auto& plane : p.planes) system.add_plane(plane);
  for (const auto& e : p.emitters) system.add_emitter(e);
  for (const auto& q : p.initial) system.add(q.position, q.velocity, q.mass, q.lifetime);
  if constexpr (detail::system_has_force<System, particles::springs>::value)
    if (p.springs) system.template force<particles::springs>() = *p.springs;
}

/// A particle system of the scene's capacity, set as add_particles does.
template <class System>
[[nodiscard]] System make_particles(const particle_scene<typename System::scalar>& p,
                                    const std::string& file = "<scene>") {
  System system(p.capacity);
  add_particles(system, p, file);
  return system;
}

}  // namespace impulse::io

// The reader of each scalar (parse_scene and read_scene, JSON included)
// compiled once per program, as core/extern_templates.hpp does for the
// world: IMPULSE_INSTANTIATE_SCENE_READER(T) in one .cpp file, and every
// file built with IMPULSE_EXTERN_SCENE_READER=1 only parses it (float and
// double). It depends on the scalar alone, and was half of a small
// program's compile time (30 s of 60 at g++ -O3).
#define IMPULSE_DETAIL_SCENE_READER(how, T)                                                                  \
  how impulse::io::scene<T> impulse::io::parse_scene<T>(std::string_view, const std::string&,               \
                                                        const impulse::io::scene_limits&);                  \
  how impulse::io::scene<T> impulse::io::read_scene<T>(const std::string&, const impulse::io::scene_limits&)
#define IMPULSE_DECLARE_SCENE_READER(T) IMPULSE_DETAIL_SCENE_READER(extern template, T)
#define IMPULSE_INSTANTIATE_SCENE_READER(T) IMPULSE_DETAIL_SCENE_READER(template, T)

#if defined(IMPULSE_EXTERN_SCENE_READER) && IMPULSE_EXTERN_SCENE_READER
IMPULSE_DECLARE_SCENE_READER(float);
IMPULSE_DECLARE_SCENE_READER(double);
#endif
