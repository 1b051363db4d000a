// impulse/io/detail/scene_parser.hpp — the JSON of a scene file turned
// into a scene<T> (io/scene_data.hpp): every value checked, shapes built,
// body references resolved, copies expanded, and every limit of
// scene_limits checked before what it guards is allocated. io/scene.hpp's
// read_scene and parse_scene run it.
#pragma once

#include <cstddef>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "../scene_data.hpp"
#include "json_reader.hpp"

namespace impulse::io::detail {

/// The pose of copy k of a repeated element. A path ("count": n, "step": a
/// transform) walks like a turtle: each copy is the previous one moved by
/// the step in its own frame, so a step forward and a small turn lays
/// copies along an arc. A grid ("count": [nx, ny, nz], "spacing") places
/// copy (i, j, l) at i·sx, j·sy, l·sz along the first copy's own axes.
template <class T>
struct repeat_plan {
  std::size_t nx = 1, ny = 1, nz = 1;
  bool grid = false;
  transform<T> step = transform<T>::identity();
  vec3<T> spacing{};
  std::size_t index_step = 1;  ///< joints: how far a copy's body references advance

  [[nodiscard]] std::size_t count() const noexcept { return nx * ny * nz; }
  /// The poses of every copy, the first being `first`.
  [[nodiscard]] std::vector<transform<T>> poses(const transform<T>& first) const {
    std::vector<transform<T>> out;
    out.reserve(count());
    if (grid) {
      for (std::size_t l = 0; l < nz; ++l)
        for (std::size_t j = 0; j < ny; ++j)
          for (std::size_t i = 0; i < nx; ++i) {
            const vec3<T> local{T(i) * spacing.x, T(j) * spacing.y, T(l) * spacing.z};
            out.push_back({first.position + rotate(first.rotation, local), first.rotation});
          }
    } else {
      transform<T> pose = first;
      for (std::size_t k = 0; k < nx; ++k) {
        out.push_back(pose);
        pose = {pose.position + rotate(pose.rotation, step.position), normalize(pose.rotation * step.rotation)};
      }
    }
    return out;
  }
};

template <class T>
class scene_parser {
 public:
  scene_parser(const json& document, std::string file, const scene_limits& limits)
      : r_(std::move(file)), root_{document, "", &r_.file()}, limits_(limits) {}

  scene<T> parse() {
    r_.object(root_, {"impulse_scene", "description", "settings", "duration", "materials", "shapes", "bodies",
                      "joints", "particles"});
    if (!root_.has("impulse_scene")) r_.fail(root_, "expected the key \"impulse_scene\": 1 (the format's version)");
    if (r_.integer(root_["impulse_scene"], 1, 1000) != 1) r_.fail(root_["impulse_scene"], "this reader knows version 1");
    if (root_.has("description")) (void)r_.string(root_["description"]);
    out_.file = r_.file();
    if (root_.has("settings")) {
      out_.settings = settings(root_["settings"]);
      out_.has_settings = true;
    }
    if (root_.has("duration")) out_.duration = r_.non_negative(root_["duration"]);
    if (root_.has("materials")) {
      const json_at all = root_["materials"];
      if (!all.value.is_object()) r_.fail_expected(all, "an object of named materials");
      for (const auto& item : all.value.items())
        materials_[item.key()] = material(all[item.key()], impulse::material<T>{});
    }
    if (root_.has("shapes")) {
      const json_at all = root_["shapes"];
      if (!all.value.is_object()) r_.fail_expected(all, "an object of named shapes");
      // Compounds after the others: a child may name a shape, and the keys come sorted, not as written.
      for (const bool compounds : {false, true})
        for (const auto& item : all.value.items())
          if ((item.value().is_object() && item.value().value("type", json()) == "compound") == compounds)
            shapes_[item.key()] = shape(all[item.key()]);
    }
    if (root_.has("bodies")) {
      const json_at all = root_["bodies"];
      r_.array(all);
      for (std::size_t i = 0; i < all.value.size(); ++i) body(all[i]);
    }
    if (root_.has("joints")) {
      const json_at all = root_["joints"];
      r_.array(all);
      for (std::size_t i = 0; i < all.value.size(); ++i) joint(all[i]);
    }
    if (root_.has("particles")) {
      const json_at all = root_["particles"];
      r_.array(all);
      check_particle_capacities(all);
      for (std::size_t i = 0; i < all.value.size(); ++i) out_.particle_systems.push_back(particle_system(all[i]));
    }
    return std::move(out_);
  }

 private:
  /// A limit of scene_limits crossed at `at`; `limit` names the member.
  [[noreturn]] void exceeded(const json_at& at, const std::string& what, const char* limit) const {
    r_.fail(at, what + " (scene_limits::" + limit + ")", error_code::capacity_exceeded);
  }

  // ---- settings ----

  world_settings<T, scene_solver_settings<T>> settings(const json_at& at) {
    r_.object(at, {"gravity", "time_step", "max_steps_per_advance", "sleep_linear_speed", "sleep_angular_speed",
                   "sleep_time", "contact_reuse_distance", "contact_reuse_angle", "ccd_motion_fraction", "ccd_gap",
                   "max_linear_speed", "max_angular_speed", "max_coordinate", "max_joint_lever", "max_contact_pairs",
                   "solver"});
    world_settings<T, scene_solver_settings<T>> s;
    if (at.has("gravity")) s.gravity = r_.vector(at["gravity"]);
    if (at.has("time_step")) s.fixed_dt = r_.positive(at["time_step"]);
    if (at.has("max_steps_per_advance")) s.max_steps_per_advance = int(r_.integer(at["max_steps_per_advance"], 1, 1000));
    if (at.has("max_contact_pairs"))
      s.max_contact_pairs = std::uint32_t(r_.integer(at["max_contact_pairs"], 1, std::int64_t(0xffffffff)));
    const std::pair<const char*, T impulse::detail::world_settings_base<T>::*> numbers[] = {
        {"sleep_linear_speed", &impulse::detail::world_settings_base<T>::sleep_linear_speed},
        {"sleep_angular_speed", &impulse::detail::world_settings_base<T>::sleep_angular_speed},
        {"sleep_time", &impulse::detail::world_settings_base<T>::sleep_time},
        {"contact_reuse_distance", &impulse::detail::world_settings_base<T>::contact_reuse_distance},
        {"contact_reuse_angle", &impulse::detail::world_settings_base<T>::contact_reuse_angle},
        {"ccd_motion_fraction", &impulse::detail::world_settings_base<T>::ccd_motion_fraction},
        {"ccd_gap", &impulse::detail::world_settings_base<T>::ccd_gap},
        {"max_linear_speed", &impulse::detail::world_settings_base<T>::max_linear_speed},
        {"max_angular_speed", &impulse::detail::world_settings_base<T>::max_angular_speed},
        {"max_coordinate", &impulse::detail::world_settings_base<T>::max_coordinate},
        {"max_joint_lever", &impulse::detail::world_settings_base<T>::max_joint_lever}};
    for (const auto& [key, member] : numbers)
      if (at.has(key)) s.*member = r_.non_negative(at[key]);
    if (at.has("solver")) s.solver = solver(at["solver"]);
    check(at, [&] { s.validate(); });
    return s;
  }

  /// The "solver" object: the shared numbers go to every shipped solver's
  /// settings, each solver's own to its settings alone.
  scene_solver_settings<T> solver(const json_at& at) {
    using S = solver_settings<T>;
    using SI = sequential_impulse_settings<T>;
    using SS = soft_step_settings<T>;
    scene_solver_settings<T> out{};
    const auto shared = [&](auto member, auto value) {
      out.sequential_impulse.*member = value;
      out.soft_step.*member = value;
    };
    const std::pair<const char*, int S::*> integers[] = {{"velocity_iterations", &S::velocity_iterations},
                                                         {"position_iterations", &S::position_iterations},
                                                         {"manifold_sweeps", &S::manifold_sweeps}};
    const std::pair<const char*, int SS::*> soft_integers[] = {{"substep_iterations", &SS::substep_iterations},
                                                               {"relax_iterations", &SS::relax_iterations}};
    const std::pair<const char*, T S::*> numbers[] = {{"linear_slop", &S::linear_slop},
                                                      {"max_correction_speed", &S::max_correction_speed},
                                                      {"speculative_distance", &S::speculative_distance},
                                                      {"max_speculative_distance", &S::max_speculative_distance},
                                                      {"restitution_threshold", &S::restitution_threshold},
                                                      {"rest_slip_speed", &S::rest_slip_speed},
                                                      {"joint_correction", &S::joint_correction}};
    const std::pair<const char*, T SI::*> sequential_numbers[] = {{"position_correction", &SI::position_correction},
                                                                  {"rest_depth", &SI::rest_depth}};
    const std::pair<const char*, T SS::*> soft_numbers[] = {{"contact_hertz", &SS::contact_hertz},
                                                            {"contact_damping_ratio", &SS::contact_damping_ratio},
                                                            {"joint_hertz", &SS::joint_hertz},
                                                            {"joint_damping_ratio", &SS::joint_damping_ratio}};
    const std::pair<const char*, bool S::*> flags[] = {{"exact_joint_trees", &S::exact_joint_trees},
                                                       {"warm_starting", &S::warm_starting}};
    if (!at.value.is_object()) r_.fail_expected(at, "an object");
    for (const auto& item : at.value.items()) {
      const json_at v = at[item.key()];
      bool known = false;
      for (const auto& [key, member] : integers)
        if (item.key() == key) shared(member, int(r_.integer(v, 0, 1000))), known = true;
      if (item.key() == "substeps") {  // both solvers have them, each its own kind (solver_settings.hpp)
        const int n = int(r_.integer(v, 0, 1000));
        out.sequential_impulse.substeps = n, out.soft_step.substeps = n, known = true;
      }
      for (const auto& [key, member] : soft_integers)
        if (item.key() == key) out.soft_step.*member = int(r_.integer(v, 0, 1000)), known = true;
      for (const auto& [key, member] : numbers)
        if (item.key() == key) shared(member, r_.non_negative(v)), known = true;
      for (const auto& [key, member] : sequential_numbers)
        if (item.key() == key) out.sequential_impulse.*member = r_.non_negative(v), known = true;
      for (const auto& [key, member] : soft_numbers)
        if (item.key() == key) out.soft_step.*member = r_.non_negative(v), known = true;
      for (const auto& [key, member] : flags)
        if (item.key() == key) shared(member, r_.boolean(v)), known = true;
      if (!known) r_.fail(v, "unknown solver setting \"" + item.key() + "\" (docs/scenes.md lists them)");
    }
    return out;
  }

  // ---- materials and shapes ----

  impulse::material<T> material(const json_at& at, impulse::material<T> m) {
    if (at.value.is_string()) {
      const auto it = materials_.find(r_.string(at));
      if (it == materials_.end()) r_.fail(at, "no material named " + describe(at.value) + " in \"materials\"");
      return it->second;
    }
    r_.object(at, {"density", "friction", "restitution"});
    if (at.has("density")) m.density = r_.positive(at["density"]);
    if (at.has("friction")) m.friction = r_.non_negative(at["friction"]);
    if (at.has("restitution")) m.restitution = r_.within(at["restitution"], T(0), T(1));
    return m;
  }

  std::shared_ptr<const scene_shape<T>> shape(const json_at& at) {
    if (at.value.is_string()) {
      const auto it = shapes_.find(r_.string(at));
      if (it == shapes_.end()) r_.fail(at, "no shape named " + describe(at.value) + " in \"shapes\"");
      return it->second;
    }
    if (!at.value.is_object() || !at.has("type"))
      r_.fail_expected(at, "a shape: an object with a \"type\", or the name of one in \"shapes\"");
    const std::string& type = r_.string(at["type"]);
    if (type == "sphere") {
      r_.object(at, {"type", "radius"});
      return make(at, sphere<T>{r_.positive(at["radius"])});
    }
    if (type == "box") {
      r_.object(at, {"type", "half_extents"});
      return make(at, box<T>{r_.vector(at["half_extents"])});
    }
    if (type == "capsule") {
      r_.object(at, {"type", "radius", "half_height"});
      return make(at, capsule<T>{r_.positive(at["radius"]), r_.non_negative(at["half_height"])});
    }
    if (type == "plane") {
      r_.object(at, {"type", "normal", "offset"});
      return make(at, plane<T>{r_.direction(at["normal"]), at.has("offset") ? r_.number(at["offset"]) : T(0)});
    }
    if (type == "convex_hull") {
      r_.object(at, {"type", "vertices"});
      const json_at list = at["vertices"];
      r_.array(list, 1);
      if (list.value.size() > limits_.hull_points)
        exceeded(list, "more than " + std::to_string(limits_.hull_points) + " points in one hull", "hull_points");
      const std::vector<vec3<T>> points = vertices(list);
      std::shared_ptr<const scene_shape<T>> out;
      check(at["vertices"], [&] { out = std::make_shared<const scene_shape<T>>(convex_hull<T>::from_points(points)); });
      return out;
    }
    if (type == "triangle_mesh") {
      r_.object(at, {"type", "vertices", "triangles"});
      const std::vector<vec3<T>> points = vertices(at["vertices"]);
      const json_at list = at["triangles"];
      r_.array(list, 1);
      if (list.value.size() > limits_.triangles - triangles_)
        exceeded(list, "the scene's meshes would have more than " + std::to_string(limits_.triangles) + " triangles",
                 "triangles");
      triangles_ += list.value.size();
      std::vector<std::uint32_t> indices;
      indices.reserve(3 * list.value.size());
      for (std::size_t t = 0; t < list.value.size(); ++t) {
        const json_at tri = list[t];
        if (!tri.value.is_array() || tri.value.size() != 3) r_.fail_expected(tri, "three vertex indices [a, b, c]");
        for (std::size_t k = 0; k < 3; ++k)
          indices.push_back(std::uint32_t(r_.integer(tri[k], 0, std::int64_t(points.size()) - 1)));
      }
      std::shared_ptr<const scene_shape<T>> out;
      check(at, [&] { out = std::make_shared<const scene_shape<T>>(triangle_mesh<T>::make(points, indices)); });
      return out;
    }
    if (type == "heightfield") return heightfield_shape(at);
    if (type == "compound") return compound_shape(at);
    r_.fail(at["type"], "expected \"sphere\", \"box\", \"capsule\", \"plane\", \"convex_hull\", \"triangle_mesh\", "
                        "\"heightfield\" or \"compound\", got " + describe(at["type"].value));
  }

  /// columns × rows heights (row by row, counted as the scene's vertices),
  /// spacing [x, z], and holes as [i, k] cells.
  std::shared_ptr<const scene_shape<T>> heightfield_shape(const json_at& at) {
    r_.object(at, {"type", "columns", "rows", "spacing", "heights", "holes"});
    const auto columns = std::size_t(r_.integer(at["columns"], 2, 65536));
    const auto rows = std::size_t(r_.integer(at["rows"], 2, 65536));
    const json_at spacing = at["spacing"];
    if (!spacing.value.is_array() || spacing.value.size() != 2) r_.fail_expected(spacing, "[x, z] spacings");
    const T sx = r_.positive(spacing[0]), sz = r_.positive(spacing[1]);
    const json_at list = at["heights"];
    r_.array(list, 4);
    if (list.value.size() > limits_.vertices - vertices_)
      exceeded(list, "the scene's meshes, hulls and heightfields would have more than " +
                         std::to_string(limits_.vertices) + " vertices", "vertices");
    if (list.value.size() != columns * rows) r_.fail_expected(list, "columns x rows heights");
    vertices_ += list.value.size();
    std::vector<T> heights(list.value.size());
    for (std::size_t i = 0; i < heights.size(); ++i) heights[i] = r_.number(list[i]);
    std::vector<std::uint8_t> holes;
    if (at.has("holes")) {
      const json_at cells = at["holes"];
      r_.array(cells);
      holes.assign((columns - 1) * (rows - 1), 0);
      for (std::size_t h = 0; h < cells.value.size(); ++h) {
        const json_at cell = cells[h];
        if (!cell.value.is_array() || cell.value.size() != 2) r_.fail_expected(cell, "a cell [i, k]");
        const auto i = std::size_t(r_.integer(cell[0], 0, std::int64_t(columns) - 2));
        const auto k = std::size_t(r_.integer(cell[1], 0, std::int64_t(rows) - 2));
        holes[k * (columns - 1) + i] = 1;
      }
    }
    std::shared_ptr<const scene_shape<T>> out;
    check(at, [&] {
      out = std::make_shared<const scene_shape<T>>(heightfield<T>::make(columns, rows, sx, sz, heights, holes));
    });
    return out;
  }

  /// Convex children, in place or named in "shapes", each at a pose in the compound's frame and with a
  /// density relative to the body's material; they count over all compounds (compound_children).
  std::shared_ptr<const scene_shape<T>> compound_shape(const json_at& at) {
    r_.object(at, {"type", "children"});
    const json_at list = at["children"];
    r_.array(list, 1);
    if (list.value.size() > limits_.compound_children - children_)
      exceeded(list, "the scene's compounds would have more than " + std::to_string(limits_.compound_children) +
                         " children", "compound_children");
    children_ += list.value.size();
    const auto convex_child = [&](const json_at& shape_at, const std::string& type) {  // one of compound_part
      if (type == "plane" || type == "triangle_mesh" || type == "heightfield" || type == "compound")
        r_.fail(shape_at, "a compound's child must be a sphere, a box, a capsule or a convex_hull, not a " + type);
    };
    typename compound<T>::builder parts;
    for (std::size_t i = 0; i < list.value.size(); ++i) {
      const json_at child = list[i];
      r_.object(child, {"shape", "position", "rotation", "relative_density"});
      const json_at where = child["shape"];
      // By its written type, before it is read: a nested compound's own errors would hide this one.
      if (where.has("type")) convex_child(where, r_.string(where["type"]));
      const std::shared_ptr<const scene_shape<T>> part = shape(where);
      if (where.value.is_string()) convex_child(where, r_.string(root_["shapes"][r_.string(where)]["type"]));
      const auto* hull = where.value.is_string() ? std::get_if<convex_hull<T>>(part.get()) : nullptr;
      const std::size_t copied = hull ? hull->vertex_count() : 0;  // a named hull is copied into the child
      if (copied > limits_.vertices - vertices_)
        exceeded(where, "the scene's meshes and hulls would have more than " + std::to_string(limits_.vertices) +
                            " vertices", "vertices");
      vertices_ += copied;
      const transform<T> place = pose(child);
      const T density = child.has("relative_density") ? r_.positive(child["relative_density"]) : T(1);
      const auto add = [&](const auto& s) { if constexpr (requires { parts.add(s); }) parts.add(s, place, density); };
      check(child, [&] { std::visit(add, *part); });
    }
    std::shared_ptr<const scene_shape<T>> out;
    check(at, [&] { out = std::make_shared<const scene_shape<T>>(parts.build()); });
    return out;
  }

  template <class Shape>
  std::shared_ptr<const scene_shape<T>> make(const json_at& at, const Shape& s) {
    check(at, [&] { s.validate(); });
    return std::make_shared<const scene_shape<T>>(s);
  }

  /// The points of a hull or mesh, counted towards the scene's vertices.
  std::vector<vec3<T>> vertices(const json_at& at) {
    r_.array(at, 1);
    if (at.value.size() > limits_.vertices - vertices_)
      exceeded(at, "the scene's meshes and hulls would have more than " + std::to_string(limits_.vertices) + " vertices",
               "vertices");
    vertices_ += at.value.size();
    std::vector<vec3<T>> out;
    out.reserve(at.value.size());
    for (std::size_t i = 0; i < at.value.size(); ++i) out.push_back(r_.vector(at[i]));
    return out;
  }

  // ---- placement ----

  quat<T> rotation(const json_at& at) {
    if (at.has("quaternion")) {
      r_.object(at, {"quaternion"});
      const json_at q = at["quaternion"];
      if (!q.value.is_array() || q.value.size() != 4) r_.fail_expected(q, "[x, y, z, w]");
      const quat<T> raw{r_.number(q[0]), r_.number(q[1]), r_.number(q[2]), r_.number(q[3])};
      const T n = std::sqrt(raw.x * raw.x + raw.y * raw.y + raw.z * raw.z + raw.w * raw.w);
      if (!(n > T(0)) || !std::isfinite(n)) r_.fail_expected(q, "a quaternion of non-zero length");
      return normalize(raw);
    }
    r_.object(at, {"axis", "degrees", "radians"});
    const vec3<T> axis = r_.direction(at["axis"]);
    if (at.has("degrees") == at.has("radians")) r_.fail(at, "expected one of \"degrees\" or \"radians\"");
    const T angle = at.has("degrees") ? r_.number(at["degrees"]) * T(std::numbers::pi / 180) : r_.number(at["radians"]);
    return quat<T>::from_axis_angle(axis, angle);
  }

  transform<T> pose(const json_at& at) {
    transform<T> t = transform<T>::identity();
    if (at.has("position")) t.position = r_.vector(at["position"]);
    if (at.has("rotation")) t.rotation = rotation(at["rotation"]);
    return t;
  }

  repeat_plan<T> repeat(const json_at& at, bool for_joint) {
    repeat_plan<T> plan;
    if (!at.has("repeat")) return plan;
    const json_at rep = at["repeat"];
    const json_at count = rep["count"];
    if (count.value.is_array()) {
      r_.object(rep, {"count", "spacing"});
      if (for_joint) r_.fail(count, "a joint repeats along a path (\"count\": n), not a grid");
      if (count.value.size() != 3) r_.fail_expected(count, "[nx, ny, nz]");
      plan.grid = true;
      const auto most = std::int64_t(limits_.bodies);
      plan.nx = std::size_t(r_.integer(count[0], 1, most));
      plan.ny = std::size_t(r_.integer(count[1], 1, most));
      plan.nz = std::size_t(r_.integer(count[2], 1, most));
      // Each factor is at most `bodies`, so neither product can wrap.
      if (plan.nx * plan.ny > limits_.bodies || plan.nx * plan.ny * plan.nz > limits_.bodies)
        exceeded(count, "more than " + std::to_string(limits_.bodies) + " copies", "bodies");
      plan.spacing = r_.vector(rep["spacing"]);
    } else {
      if (for_joint) r_.object(rep, {"count", "index_step", "step"});
      else r_.object(rep, {"count", "step"});
      plan.nx = std::size_t(r_.integer(count, 1, std::int64_t(for_joint ? limits_.joints : limits_.bodies)));
      if (for_joint) {
        if (rep.has("index_step")) plan.index_step = std::size_t(r_.integer(rep["index_step"], 0, std::int64_t(limits_.bodies)));
        if (rep.has("step")) plan.spacing = r_.vector(rep["step"]);  // moves the world anchors
      } else {
        const json_at step = rep["step"];
        r_.object(step, {"position", "rotation"});
        plan.step = pose(step);
      }
    }
    return plan;
  }

  // ---- bodies ----

  void body(const json_at& at) {
    r_.object(at, {"name", "type", "shape", "position", "rotation", "velocity", "angular_velocity", "material",
                   "mass", "awake", "bullet", "filter", "sensor", "repeat"});
    body_def<T> def;
    if (at.has("type")) {
      const std::string& type = r_.string(at["type"]);
      if (type == "static") def.type = body_type::static_body;
      else if (type == "kinematic") def.type = body_type::kinematic;
      else if (type == "dynamic") def.type = body_type::dynamic;
      else r_.fail_expected(at["type"], "\"static\", \"kinematic\" or \"dynamic\"");
    }
    if (!at.has("shape")) r_.fail(at, "a body needs a \"shape\"");
    const std::shared_ptr<const scene_shape<T>> body_shape = shape(at["shape"]);
    const transform<T> first = pose(at);
    if (at.has("velocity")) def.linear_velocity = r_.vector(at["velocity"]);
    if (at.has("angular_velocity")) def.angular_velocity = r_.vector(at["angular_velocity"]);
    if (at.has("material")) def.material = material(at["material"], def.material);
    if (at.has("mass")) def.mass = r_.positive(at["mass"]);
    if (at.has("awake")) def.awake = r_.boolean(at["awake"]);
    if (at.has("bullet")) def.bullet = r_.boolean(at["bullet"]);
    if (at.has("sensor")) def.sensor = r_.boolean(at["sensor"]);
    if (at.has("filter")) {
      const json_at f = at["filter"];
      r_.object(f, {"category", "mask", "group"});
      constexpr std::int64_t bits = 0xffffffff, group = 0x7fffffff;
      if (f.has("category")) def.filter.category = std::uint32_t(r_.integer(f["category"], 0, bits));
      if (f.has("mask")) def.filter.mask = std::uint32_t(r_.integer(f["mask"], 0, bits));
      if (f.has("group")) def.filter.group = std::int32_t(r_.integer(f["group"], -group, group));
    }
    if (def.type == body_type::static_body && (def.linear_velocity != vec3<T>{} || def.angular_velocity != vec3<T>{}))
      r_.fail(at, "a static body cannot move: give it no velocity, or make it \"kinematic\"");
    if (def.type == body_type::dynamic &&
        (std::holds_alternative<plane<T>>(*body_shape) || std::holds_alternative<triangle_mesh<T>>(*body_shape) ||
         std::holds_alternative<heightfield<T>>(*body_shape)))
      r_.fail(at["shape"], "a plane, a triangle mesh or a heightfield has no volume: its body must be \"static\" or "
                           "\"kinematic\"");

    std::string name;
    if (at.has("name")) {
      name = r_.string(at["name"]);
      if (name.empty() || name.find('[') != std::string::npos)
        r_.fail_expected(at["name"], "a non-empty name without '['");
    }
    const repeat_plan<T> plan = repeat(at, false);
    if (plan.count() > limits_.bodies - out_.bodies.size())
      exceeded(at, "the scene would hold more than " + std::to_string(limits_.bodies) + " bodies", "bodies");
    const std::vector<transform<T>> poses = plan.poses(first);
    for (std::size_t k = 0; k < poses.size(); ++k) {
      scene_body<T> b;
      b.name = name.empty() ? std::string() : at.has("repeat") ? name + "[" + std::to_string(k) + "]" : name;
      b.path = at.path;
      b.def = def;
      b.def.pose = poses[k];
      b.shape = body_shape;
      if (!is_finite(b.def.pose.position)) r_.fail(at, "a copy's position is not finite", error_code::non_finite);
      if (!b.name.empty() && !names_.emplace(b.name, out_.bodies.size()).second)
        r_.fail(at.has("name") ? at["name"] : at, "a second body named \"" + b.name + "\"");
      out_.bodies.push_back(std::move(b));
    }
  }

  /// A body named in a joint; in copy k of a repeated joint, "link[i]"
  /// means "link[i + k·index_step]", and a name without brackets (a frame
  /// every copy hangs from) the same body.
  std::size_t body_reference(const json_at& at, std::size_t k, std::size_t index_step) {
    std::string name = r_.string(at);
    if (k > 0 && !name.empty() && name.back() == ']') {
      const std::size_t open = name.rfind('[');
      if (open == std::string::npos) r_.fail_expected(at, "\"name[i]\" with i a whole number");
      const json index = json::parse(name.substr(open + 1, name.size() - open - 2), nullptr, false);
      if (!index.is_number_unsigned()) r_.fail_expected(at, "\"name[i]\" with i a whole number");
      name = name.substr(0, open + 1) + std::to_string(index.get<std::uint64_t>() + k * index_step) + "]";
    }
    const auto it = names_.find(name);
    if (it == names_.end())
      r_.fail(at, k == 0 ? "no body named \"" + name + "\"" : "copy " + std::to_string(k) + " needs a body named \"" + name + "\", which there is not");
    return it->second;
  }

  // ---- joints ----

  void joint(const json_at& at) {
    r_.object(at, {"name", "type", "a", "b", "anchor", "anchor_on_a", "anchor_b", "anchor_on_b", "axis", "axis_on_a",
                   "limits", "limits_degrees", "motor", "length", "spring", "break_force", "break_torque",
                   "collide_connected", "repeat"});
    joint_def<T> def;
    const std::string& type = r_.string(at["type"]);
    if (type == "ball") def.type = joint_type::ball;
    else if (type == "hinge") def.type = joint_type::hinge;
    else if (type == "slider") def.type = joint_type::slider;
    else if (type == "fixed") def.type = joint_type::fixed;
    else if (type == "distance") def.type = joint_type::distance;
    else r_.fail_expected(at["type"], "\"ball\", \"hinge\", \"slider\", \"fixed\" or \"distance\"");
    const bool axial = def.type == joint_type::hinge || def.type == joint_type::slider;
    if (at.has("anchor") == at.has("anchor_on_a")) r_.fail(at, "expected one of \"anchor\" or \"anchor_on_a\"");
    if (axial && at.has("axis") == at.has("axis_on_a")) r_.fail(at, "expected one of \"axis\" or \"axis_on_a\"");
    if (!axial && (at.has("axis") || at.has("axis_on_a"))) r_.fail(at, "only a hinge or a slider has an axis");
    const bool two_ends = def.type == joint_type::distance;
    if (two_ends && at.has("anchor_b") == at.has("anchor_on_b"))
      r_.fail(at, "a distance joint needs one of \"anchor_b\" or \"anchor_on_b\"");
    if (!two_ends && (at.has("anchor_b") || at.has("anchor_on_b") || at.has("length") || at.has("spring")))
      r_.fail(at, "only a distance joint has a second anchor, a length or a spring");
    if (at.has("limits") && at.has("limits_degrees")) r_.fail(at, "expected \"limits\" or \"limits_degrees\", not both");
    if ((at.has("limits") || at.has("limits_degrees") || at.has("motor")) && !axial)
      r_.fail(at, "only a hinge or a slider has limits or a motor");
    if (at.has("limits_degrees") && def.type != joint_type::hinge) r_.fail(at["limits_degrees"], "degrees are for a hinge");
    for (const char* key : {"limits", "limits_degrees"}) {
      if (!at.has(key)) continue;
      const json_at l = at[key];
      if (!l.value.is_array() || l.value.size() != 2) r_.fail_expected(l, "[lower, upper]");
      const T scale = key[6] == '_' ? T(std::numbers::pi / 180) : T(1);
      def.enable_limit = true;
      def.lower = r_.number(l[0]) * scale;
      def.upper = r_.number(l[1]) * scale;
      if (def.lower > def.upper) r_.fail(l, "expected lower <= upper");
    }
    if (at.has("motor")) {
      const json_at m = at["motor"];
      r_.object(m, {"speed", "max_force"});
      def.enable_motor = true;
      def.motor_speed = r_.number(m["speed"]);
      def.max_motor_force = r_.non_negative(m["max_force"]);
    }
    if (at.has("spring")) {
      const json_at s = at["spring"];
      r_.object(s, {"hertz", "damping_ratio"});
      def.spring_hertz = r_.positive(s["hertz"]);
      if (s.has("damping_ratio")) def.spring_damping_ratio = r_.non_negative(s["damping_ratio"]);
    }
    if (at.has("break_force")) def.break_force = r_.positive(at["break_force"]);
    if (at.has("break_torque")) def.break_torque = r_.positive(at["break_torque"]);
    if (at.has("collide_connected")) def.collide_connected = r_.boolean(at["collide_connected"]);
    std::string name;
    if (at.has("name")) {
      name = r_.string(at["name"]);
      if (name.empty() || name.find('[') != std::string::npos) r_.fail_expected(at["name"], "a non-empty name without '['");
    }

    const repeat_plan<T> plan = repeat(at, true);
    if (plan.count() > limits_.joints - out_.joints.size())
      exceeded(at, "the scene would hold more than " + std::to_string(limits_.joints) + " joints", "joints");
    for (std::size_t k = 0; k < plan.count(); ++k) {
      scene_joint<T> j;
      j.path = at.path;
      j.name = name.empty() ? std::string() : at.has("repeat") ? name + "[" + std::to_string(k) + "]" : name;
      j.body_a = body_reference(at["a"], k, plan.index_step);
      j.body_b = body_reference(at["b"], k, plan.index_step);
      if (j.body_a == j.body_b) r_.fail(at["b"], "a joint needs two different bodies");
      const body_def<T>& a = out_.bodies[j.body_a].def;
      const body_def<T>& b = out_.bodies[j.body_b].def;
      if (a.type != body_type::dynamic && b.type != body_type::dynamic)
        r_.fail(at, "at least one of a joint's bodies must be dynamic");
      j.def = def;
      // World anchors of copy k move by k steps; anchors on a body move with it.
      const vec3<T> moved = plan.spacing * T(k);
      j.def.anchor_a = at.has("anchor") ? r_.vector(at["anchor"]) + moved : apply(a.pose, r_.vector(at["anchor_on_a"]));
      if (two_ends) {
        j.def.anchor_b =
            at.has("anchor_b") ? r_.vector(at["anchor_b"]) + moved : apply(b.pose, r_.vector(at["anchor_on_b"]));
        j.def.axis = j.def.anchor_b - j.def.anchor_a;
        j.def.length = at.has("length") ? r_.non_negative(at["length"]) : length(j.def.anchor_b - j.def.anchor_a);
      } else if (axial) {
        j.def.axis = at.has("axis") ? r_.direction(at["axis"]) : rotate(a.pose.rotation, r_.direction(at["axis_on_a"]));
      }
      if (!j.name.empty() && !joint_names_.emplace(j.name, out_.joints.size()).second)
        r_.fail(at["name"], "a second joint named \"" + j.name + "\"");
      check(at, [&] { j.def.validate(); });
      out_.joints.push_back(std::move(j));
    }
  }

  // ---- particles ----

  /// The capacities of all systems, summed against scene_limits::particles
  /// before any system's particles are made: a thousand systems of the
  /// largest capacity are refused at the second, not after the first is full.
  void check_particle_capacities(const json_at& all) const {
    std::size_t total = 0;
    for (std::size_t i = 0; i < all.value.size(); ++i) {
      const json_at capacity = all[i]["capacity"];
      const auto n = std::size_t(r_.integer(capacity, 1, std::int64_t(limits_.particles)));
      if (n > limits_.particles - total)
        exceeded(capacity, "the scene's particle systems would hold more than " + std::to_string(limits_.particles) +
                               " particles", "particles");
      total += n;
    }
  }

  /// A particle's mass: positive, and not so small that its inverse, which
  /// a step multiplies forces by, overflows.
  T particle_mass(const json_at& at) const {
    const T m = r_.positive(at);
    if (!(m >= particles::min_particle_mass<T>))
      r_.fail_expected(at, "a mass of at least " + describe(json(double(particles::min_particle_mass<T>))) +
                               " (particles::min_particle_mass, the smallest normal number)");
    return m;
  }

  particle_scene<T> particle_system(const json_at& at) {
    r_.object(at, {"name", "capacity", "forces", "planes", "emitters", "particles"});
    particle_scene<T> p;
    p.path = at.path;
    if (at.has("name")) p.name = r_.string(at["name"]);
    p.capacity = std::size_t(r_.integer(at["capacity"], 1, std::int64_t(limits_.particles)));
    if (at.has("forces")) forces(at["forces"], p);
    if (at.has("planes")) {
      const json_at list = at["planes"];
      r_.array(list);
      for (std::size_t i = 0; i < list.value.size(); ++i) p.planes.push_back(particle_plane(list[i]));
    }
    if (at.has("emitters")) {
      const json_at list = at["emitters"];
      r_.array(list);
      for (std::size_t i = 0; i < list.value.size(); ++i) p.emitters.push_back(emitter(list[i]));
    }
    if (at.has("particles")) {
      const json_at list = at["particles"];
      r_.array(list);
      for (std::size_t i = 0; i < list.value.size(); ++i) particles(list[i], p);
    }
    if (p.springs) check(at["forces"]["springs"], [&] { p.springs->validate(p.initial.size(), task_system{}); });
    return p;
  }

  void forces(const json_at& at, particle_scene<T>& p) {
    r_.object(at, {"gravity", "drag", "wind", "attractors", "springs"});
    if (at.has("gravity")) {
      const json_at g = at["gravity"];
      r_.object(g, {"acceleration"});
      p.gravity.emplace();
      if (g.has("acceleration")) p.gravity->acceleration = r_.vector(g["acceleration"]);
    }
    if (at.has("drag")) {
      const json_at d = at["drag"];
      r_.object(d, {"coefficient"});
      p.drag.emplace();
      if (d.has("coefficient")) p.drag->coefficient = r_.non_negative(d["coefficient"]);
    }
    if (at.has("wind")) {
      const json_at w = at["wind"];
      r_.object(w, {"velocity", "coefficient", "variation"});
      p.wind.emplace();
      if (w.has("velocity")) p.wind->velocity = r_.vector(w["velocity"]);
      if (w.has("coefficient")) p.wind->coefficient = r_.non_negative(w["coefficient"]);
      if (w.has("variation")) p.wind->variation = r_.within(w["variation"], T(0), T(1));
    }
    if (at.has("attractors")) {
      const json_at a = at["attractors"];
      r_.object(a, {"softening", "points"});
      p.attractors.emplace();
      if (a.has("softening")) p.attractors->softening = r_.positive(a["softening"]);
      if (a.has("points")) {
        const json_at list = a["points"];
        r_.array(list);
        if (list.value.size() > particles::point_forces<T>::max_points)
          r_.fail(list, "at most " + std::to_string(particles::point_forces<T>::max_points) + " points");
        for (std::size_t i = 0; i < list.value.size(); ++i) {
          const json_at point = list[i];
          r_.object(point, {"position", "strength", "enabled"});
          const std::size_t n = p.attractors->add(r_.vector(point["position"]), r_.number(point["strength"]));
          if (point.has("enabled")) p.attractors->points[n].enabled = r_.boolean(point["enabled"]);
        }
      }
    }
    if (at.has("springs")) {
      const json_at list = at["springs"];
      r_.array(list);
      p.springs.emplace();
      for (std::size_t i = 0; i < list.value.size(); ++i) {
        const json_at s = list[i];
        r_.object(s, {"a", "b", "rest_length", "stiffness", "damping"});
        const auto a = std::uint32_t(r_.integer(s["a"], 0, std::int64_t(p.capacity) - 1));
        const auto b = std::uint32_t(r_.integer(s["b"], 0, std::int64_t(p.capacity) - 1));
        const T rest = r_.non_negative(s["rest_length"]);
        const T k = r_.non_negative(s["stiffness"]);
        const T c = s.has("damping") ? r_.non_negative(s["damping"]) : T(0);
        check(s, [&] { p.springs->add(a, b, rest, k, c); });
      }
    }
  }

  particles::plane_collider<T> particle_plane(const json_at& at) {
    r_.object(at, {"normal", "offset", "center", "axis_u", "half_u", "half_v", "restitution", "friction"});
    const vec3<T> n = r_.direction(at["normal"]);
    const T e = at.has("restitution") ? r_.within(at["restitution"], T(0), T(1)) : T(0.5);
    const T mu = at.has("friction") ? r_.within(at["friction"], T(0), T(1)) : T(0.2);
    particles::plane_collider<T> plane;
    if (at.has("center")) {
      if (at.has("offset")) r_.fail(at, "a rectangle has a \"center\", a half-space an \"offset\": not both");
      plane = particles::plane_collider<T>::rectangle(r_.vector(at["center"]), n, r_.direction(at["axis_u"]),
                                                      r_.positive(at["half_u"]), r_.positive(at["half_v"]), e, mu);
    } else {
      if (at.has("axis_u") || at.has("half_u") || at.has("half_v")) r_.fail(at, "a half-space has no axis_u or half sizes; give a \"center\" for a rectangle");
      plane = particles::plane_collider<T>::half_space(n, at.has("offset") ? r_.number(at["offset"]) : T(0), e, mu);
    }
    check(at, [&] { plane.validate(); });
    return plane;
  }

  particles::emitter<T> emitter(const json_at& at) {
    r_.object(at, {"position", "half_extents", "velocity", "velocity_spread", "rate", "lifetime", "lifetime_spread",
                   "mass", "enabled", "seed"});
    particles::emitter<T> e;
    if (at.has("position")) e.position = r_.vector(at["position"]);
    if (at.has("half_extents")) e.half_extents = r_.vector(at["half_extents"]);
    if (at.has("velocity")) e.velocity = r_.vector(at["velocity"]);
    if (at.has("velocity_spread")) e.velocity_spread = r_.vector(at["velocity_spread"]);
    if (at.has("rate")) e.rate = r_.within(at["rate"], T(0), particles::emitter<T>::max_rate);
    if (at.has("lifetime")) e.lifetime = r_.positive(at["lifetime"]);
    if (at.has("lifetime_spread")) e.lifetime_spread = r_.non_negative(at["lifetime_spread"]);
    if (at.has("mass")) e.mass = particle_mass(at["mass"]);
    if (at.has("enabled")) e.enabled = r_.boolean(at["enabled"]);
    if (at.has("seed")) e.random.state = std::uint32_t(r_.integer(at["seed"], 0, 0xffffffffLL));
    check(at, [&] { e.validate(); });
    return e;
  }

  void particles(const json_at& at, particle_scene<T>& p) {
    r_.object(at, {"position", "velocity", "mass", "lifetime", "repeat"});
    typename particle_scene<T>::particle q;
    const vec3<T> first = r_.vector(at["position"]);
    if (at.has("velocity")) q.velocity = r_.vector(at["velocity"]);
    if (at.has("mass")) q.mass = particle_mass(at["mass"]);
    if (at.has("lifetime")) q.lifetime = r_.positive(at["lifetime"]);
    const repeat_plan<T> plan = repeat(at, false);
    if (plan.count() > p.capacity - p.initial.size())
      r_.fail(at, "more particles than the system's capacity, " + std::to_string(p.capacity));
    for (const transform<T>& pose : plan.poses({first, quat<T>::identity()})) {
      q.position = pose.position;
      if (!is_finite(q.position)) r_.fail(at, "a copy's position is not finite", error_code::non_finite);
      p.initial.push_back(q);
    }
  }

  /// Runs a library check; its complaint becomes an error at `at`.
  template <class F>
  void check(const json_at& at, F&& f) const {
    try {
      f();
    } catch (const scene_error&) {
      throw;
    } catch (const invalid_argument& e) {
      r_.fail(at, e.what(), e.code());
    }
  }

  json_reader<T> r_;
  json_at root_;
  scene_limits limits_;
  std::size_t vertices_ = 0, triangles_ = 0, children_ = 0;  ///< so far, over the whole document
  scene<T> out_;
  std::map<std::string, impulse::material<T>, std::less<>> materials_;
  std::map<std::string, std::shared_ptr<const scene_shape<T>>, std::less<>> shapes_;
  std::map<std::string, std::size_t, std::less<>> names_;
  std::map<std::string, std::size_t, std::less<>> joint_names_;
};

}  // namespace impulse::io::detail
