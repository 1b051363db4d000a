// impulse/io/scene_data.hpp — a scene file's content as plain data: the
// limits a file is read within (scene_limits), its bodies, joints and
// particle systems (scene<T>), and the ids add_scene gives them
// (scene_ids). io/scene.hpp reads and adds them; docs/scenes.md is the
// schema.
#pragma once

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <ios>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <variant>
#include <vector>

#include "../particles/drag.hpp"
#include "../particles/gravity.hpp"
#include "../particles/particle_system.hpp"
#include "../particles/point_forces.hpp"
#include "../particles/springs.hpp"
#include "../particles/wind.hpp"
#include "../shapes/compound.hpp"
#include "../world/world.hpp"


namespace impulse::io {

/// What one scene file may hold at most, counted over the whole document: a
/// typo of a few zeros in a repeat count or a capacity, or a file made to
/// exhaust memory, is refused rather than allocated. Every limit is checked
/// before the memory it guards is allocated, and a refusal is a scene_error
/// (error_code::capacity_exceeded) naming the JSON path of the value that
/// crossed it and the member below. The defaults admit every scene the
/// format was made for; a program that reads larger ones passes its own:
///
///   io::scene_limits limits;
///   limits.particles = std::size_t(1) << 26;
///   auto scene = io::read_scene<float>("galaxy.json", limits);
///
/// Memory figures are for nlohmann-json 3.11 on a 64-bit machine.
struct scene_limits {
  /// Bytes of text, checked before the text is read or parsed: 64 MiB. The
  /// largest mesh the counts below admit, 10^6 triangles over about 5·10^5
  /// vertices written at float precision, is about 40 MB of text.
  std::size_t bytes = std::size_t(64) << 20;
  /// JSON values of every kind (numbers, strings, arrays, objects), counted
  /// in a first reading that builds nothing. The document built afterwards
  /// takes 35 to 50 bytes a value for arrays of numbers, and up to 130 for
  /// objects of short keys: 10^7 values bound it to about 1.3 GB at worst,
  /// 500 MB for a mesh. Both mesh limits below together need 8·10^6.
  std::size_t json_values = 10'000'000;
  /// Arrays and objects inside one another. The format's deepest value, a
  /// point of a compound's hull (/bodies/i/shape/children/j/shape/vertices/k),
  /// is inside 9, counting the document.
  int depth = 32;
  /// Bodies, counting every copy a "repeat" makes.
  std::size_t bodies = 100'000;
  /// Joints, counting every copy.
  std::size_t joints = 100'000;
  /// Particles, as the capacities of all particle systems summed, checked
  /// for all systems before any system's particles are made. 2^24 was the
  /// limit of one system before it was one of the whole document: every
  /// file with one system that loaded then loads now. A scene's particle
  /// takes 32 bytes (float) or 64 (double), and a system made from it 40 or
  /// 80 a unit of capacity.
  std::size_t particles = std::size_t(1) << 24;
  /// Points of one convex hull: quickhull's cost grows faster than linearly
  /// with them, and a hull of more points is better given as a mesh.
  std::size_t hull_points = 4096;
  /// Vertices of all meshes and hulls. An indexed mesh has about half as
  /// many vertices as triangles, so this leaves room for the largest mesh
  /// and for thousands of hulls.
  std::size_t vertices = 1'000'000;
  /// Triangles of all meshes: 10^6, the former limit of one mesh.
  std::size_t triangles = 1'000'000;
  /// Children of all compounds: 2^16, as many as one compound takes
  /// (compound::max_children). A child holds a copy of its shape: a hull
  /// named in "shapes" counts towards `vertices` again for each child that
  /// names it.
  std::size_t compound_children = 65536;
};

/// The default limits under the names they had before scene_limits.
inline constexpr std::size_t max_scene_bodies = scene_limits{}.bodies;
inline constexpr std::size_t max_scene_joints = scene_limits{}.joints;
inline constexpr std::size_t max_hull_points = scene_limits{}.hull_points;
inline constexpr std::size_t max_mesh_triangles = scene_limits{}.triangles;
inline constexpr std::size_t max_particle_capacity = scene_limits{}.particles;
inline constexpr int max_scene_depth = scene_limits{}.depth;

template <scalar_type T>
using scene_shape = std::variant<sphere<T>, box<T>, capsule<T>, convex_hull<T>, plane<T>, triangle_mesh<T>,
                                 heightfield<T>, compound<T>>;

/// A body of a scene: how to make it and where in the file it was described.
template <scalar_type T>
struct scene_body {
  std::string name;  ///< empty if unnamed; a copy of a repeated body is "name[k]"
  std::string path;  ///< JSON pointer of its element (for errors)
  body_def<T> def;
  std::shared_ptr<const scene_shape<T>> shape;  ///< copies share one
};

/// A joint of a scene; its bodies are indices into scene::bodies and its
/// anchors and axis are world values, as joint_def wants.
template <scalar_type T>
struct scene_joint {
  std::string name;
  std::string path;
  std::size_t body_a = 0, body_b = 0;
  joint_def<T> def;  ///< body ids are filled in by add_scene
};

/// A particle system of a scene: its capacity and what to set in it. A
/// force the file does not mention keeps the system's own parameters.
template <scalar_type T>
struct particle_scene {
  struct particle {
    vec3<T> position{}, velocity{};
    T mass = T(1);
    T lifetime = std::numeric_limits<T>::infinity();
  };
  std::string name;
  std::string path;
  std::size_t capacity = 0;
  std::optional<particles::gravity<T>> gravity;
  std::optional<particles::drag<T>> drag;
  std::optional<particles::wind<T>> wind;
  std::optional<particles::point_forces<T>> attractors;
  std::optional<particles::springs<T>> springs;
  std::vector<particles::plane_collider<T>> planes;
  std::vector<particles::emitter<T>> emitters;
  std::vector<particle> initial;
};

/// A scene's solver numbers, for whichever solver its world will have: a
/// file may set the shared ones (solver_settings) and any shipped solver's
/// own, and add_scene hands the world those of its solver (for_solver).
template <scalar_type T>
struct scene_solver_settings {
  sequential_impulse_settings<T> sequential_impulse{};
  soft_step_settings<T> soft_step{};

  void validate() const {
    sequential_impulse.validate();
    soft_step.validate();
  }
  /// The numbers for a world whose solver reads S: the shipped solvers'
  /// own; for another solver's type, the shared numbers in its defaults.
  template <class S>
  [[nodiscard]] S for_solver() const {
    if constexpr (std::is_same_v<S, sequential_impulse_settings<T>>) {
      return sequential_impulse;
    } else if constexpr (std::is_same_v<S, soft_step_settings<T>>) {
      return soft_step;
    } else {
      S out{};
      static_cast<solver_settings<T>&>(out) = sequential_impulse;
      return out;
    }
  }
};

/// A scene read from a file: checked, and not yet in any world.
template <scalar_type T>
struct scene {
  std::string file;
  /// The world's settings: the defaults, with what the file's "settings" set.
  world_settings<T, scene_solver_settings<T>> settings{};
  bool has_settings = false;
  /// How long the scene is meant to run, s (0: the file does not say).
  T duration = T(0);
  std::vector<scene_body<T>> bodies;
  std::vector<scene_joint<T>> joints;
  std::vector<particle_scene<T>> particle_systems;

  /// The index in `bodies` of the body called `name`, if there is one.
  [[nodiscard]] std::optional<std::size_t> find_body(std::string_view name) const {
    for (std::size_t i = 0; i < bodies.size(); ++i)
      if (bodies[i].name == name) return i;
    return std::nullopt;
  }
  [[nodiscard]] const particle_scene<T>* find_particles(std::string_view name) const {
    for (const particle_scene<T>& p : particle_systems)
      if (p.name == name) return &p;
    return nullptr;
  }
};

/// The ids a scene's bodies and joints got in a world, in the scene's order.
struct scene_ids {
  std::vector<body_id> bodies;
  std::vector<joint_id> joints;
  std::map<std::string, body_id, std::less<>> body_names;
  std::map<std::string, joint_id, std::less<>> joint_names;

  /// The body called `name`; a name the scene does not have is an error.
  [[nodiscard]] body_id body(std::string_view name) const {
    const auto it = body_names.find(name);
    if (it == body_names.end())
      throw invalid_argument(error_code::out_of_range, ("scene_ids: no body named " + std::string(name)).c_str());
    return it->second;
  }
  [[nodiscard]] joint_id joint(std::string_view name) const {
    const auto it = joint_names.find(name);
    if (it == joint_names.end())
      throw invalid_argument(error_code::out_of_range, ("scene_ids: no joint named " + std::string(name)).c_str());
    return it->second;
  }
};

}  // namespace impulse::io
