// impulse/io/gltf.hpp — a run recorded as glTF 2.0 binary (.glb), which any
// glTF viewer plays: one mesh per shape, one node per body, and an
// animation of each moving body's translation and rotation sampled at every
// recorded frame (Khronos, glTF 2.0 specification, 2021).
//
//   impulse::io::gltf_recorder recording(world);  // the bodies there now, frame 0
//   for (...) { world.step(dt); recording.record(world); }
//   recording.save("run.glb");
//
// The recorder takes the bodies present when it is made; a body destroyed
// later stays where it was last seen, one created later is not recorded.
// Bodies of the same shape, size and kind share a mesh (a domino chain
// stores one box). Static bodies are placed and not animated. Materials
// say the kind: static grey, dynamic orange, kinematic blue; all
// double-sided, as a triangle mesh has no inside. Rotations are kept on one
// side of the quaternion sphere from frame to frame, so that a viewer's
// interpolation turns the short way.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include "../dynamics/fwd.hpp"
#include "../dynamics/rigid_body.hpp"
#include "../math/transform.hpp"
#include "shape_mesh.hpp"

namespace impulse::io {

namespace detail {

/// What makes two primitive shapes draw the same: kind and sizes. Hulls,
/// meshes and planes have none, and get a mesh each.
template <class Shape>
std::optional<std::array<double, 4>> same_shape_key(const Shape&) noexcept {
  return std::nullopt;
}
template <scalar_type T>
std::optional<std::array<double, 4>> same_shape_key(const sphere<T>& s) noexcept {
  return std::array<double, 4>{0, double(s.radius), 0, 0};
}
template <scalar_type T>
std::optional<std::array<double, 4>> same_shape_key(const box<T>& b) noexcept {
  return std::array<double, 4>{1, double(b.half_extents.x), double(b.half_extents.y), double(b.half_extents.z)};
}
template <scalar_type T>
std::optional<std::array<double, 4>> same_shape_key(const capsule<T>& c) noexcept {
  return std::array<double, 4>{2, double(c.radius), double(c.half_height), 0};
}

/// A JSON number: the shortest text that reads back as the same float;
/// 0 for what JSON cannot hold.
inline void append_number(std::string& out, double x) {
  if (!std::isfinite(x)) x = 0;
  char text[32];
  const std::to_chars_result r = std::to_chars(text, text + sizeof text, float(x));
  out.append(text, r.ptr);
}
inline void append_numbers(std::string& out, const float* x, int n) {
  out += '[';
  for (int i = 0; i < n; ++i) {
    if (i > 0) out += ',';
    append_number(out, x[i]);
  }
  out += ']';
}

}  // namespace detail

/// What a gltf_recorder records besides the bodies.
struct gltf_options {
  /// Every touching contact point at each frame, in the root's extras
  /// (viewer/ draws them): 12 bytes a point a frame.
  bool contacts = false;
};

template <class World>
class gltf_recorder {
 public:
  using scalar = typename World::scalar;

  /// Takes every body of the world, and records frame 0.
  explicit gltf_recorder(const World& w, const gltf_options& choice = {}) : options_(choice) {
    for (const body_id id : w.body_ids()) {
      track t;
      t.id = id;
      t.kind = w.body(id).type;
      t.mesh = w.visit_shape(id, [&](const auto& shape) { return mesh_for(shape, t.kind); });
      tracks_.push_back(std::move(t));
    }
    record(w);
  }

  /// Records a frame: the world's time and every recorded body's pose.
  void record(const World& w) {
    times_.push_back(float(w.time()));
    for (track& t : tracks_) {
      if (w.contains(t.id)) t.last = w.shape_pose(t.id);
      quat<scalar> q = t.last.rotation;
      if (!t.rotations.empty()) {
        const std::size_t k = t.rotations.size() - 4;
        const scalar previous = scalar(t.rotations[k]) * q.x + scalar(t.rotations[k + 1]) * q.y +
                                scalar(t.rotations[k + 2]) * q.z + scalar(t.rotations[k + 3]) * q.w;
        if (previous < scalar(0)) q = q * scalar(-1);
      }
      const vec3<scalar>& p = t.last.position;
      t.translations.insert(t.translations.end(), {float(p.x), float(p.y), float(p.z)});
      t.rotations.insert(t.rotations.end(), {float(q.x), float(q.y), float(q.z), float(q.w)});
    }
    if (options_.contacts) {
      if (contact_offsets_.empty()) contact_offsets_.push_back(0);
      w.for_each_contact([&](body_id, body_id, const auto& manifolds) {
        for (const auto& m : manifolds)
          for (const auto& c : m.contacts())
            contact_points_.push_back({float(c.position.x), float(c.position.y), float(c.position.z)});
      });
      contact_offsets_.push_back(std::uint32_t(contact_points_.size()));
    }
  }

  /// Contact points recorded so far (options::contacts).
  [[nodiscard]] std::size_t contact_point_count() const noexcept { return contact_points_.size(); }

  [[nodiscard]] std::size_t frame_count() const noexcept { return times_.size(); }
  [[nodiscard]] std::size_t body_count() const noexcept { return tracks_.size(); }
  [[nodiscard]] std::size_t mesh_count() const noexcept { return meshes_.size(); }

  /// The .glb file's bytes: a 12-byte header, the JSON chunk, and the
  /// binary chunk unless there is nothing to put in it.
  [[nodiscard]] std::vector<std::uint8_t> glb() const {
    static_assert(std::endian::native == std::endian::little, "gltf_recorder writes little-endian words");
    document d;
    std::string meshes, nodes, channels, samplers;
    for (std::size_t m = 0; m < meshes_.size(); ++m) {
      const shape_mesh& mesh = meshes_[m].mesh;
      const int positions = d.vec3_accessor(mesh.positions, true, 34962);
      const int normals = d.vec3_accessor(mesh.normals, false, 34962);
      const int indices = d.index_accessor(mesh.indices);
      if (m > 0) meshes += ',';
      meshes += "{\"primitives\":[{\"attributes\":{\"POSITION\":" + std::to_string(positions) +
                ",\"NORMAL\":" + std::to_string(normals) + "},\"indices\":" + std::to_string(indices) +
                ",\"material\":" + std::to_string(meshes_[m].material) + "}]}";
    }
    const bool animated = times_.size() > 1;
    int time = -1, sampler = 0;
    for (std::size_t n = 0; n < tracks_.size(); ++n) {
      const track& t = tracks_[n];
      if (n > 0) nodes += ',';
      nodes += "{\"name\":\"body " + std::to_string(t.id.index) + "\",\"mesh\":" + std::to_string(t.mesh) +
               ",\"translation\":";
      detail::append_numbers(nodes, t.translations.data(), 3);
      nodes += ",\"rotation\":";
      detail::append_numbers(nodes, t.rotations.data(), 4);
      nodes += '}';
      if (!animated || t.kind == body_type::static_body) continue;
      if (time < 0) time = d.time_accessor(times_);
      const int moved = d.float_accessor(t.translations, "VEC3");
      const int turned = d.float_accessor(t.rotations, "VEC4");
      for (const auto& [output, path] : {std::pair{moved, "translation"}, std::pair{turned, "rotation"}}) {
        if (sampler > 0) channels += ',', samplers += ',';
        channels += "{\"sampler\":" + std::to_string(sampler) + ",\"target\":{\"node\":" + std::to_string(n) +
                    ",\"path\":\"" + path + "\"}}";
        samplers += "{\"input\":" + std::to_string(time) + ",\"output\":" + std::to_string(output) +
                    ",\"interpolation\":\"LINEAR\"}";
        ++sampler;
      }
    }
    // Contacts (viewer/ reads them): the points of frame i are
    // points[offsets[i] .. offsets[i + 1]). None at all: no extras, as an
    // accessor may not be empty.
    std::string extras;
    if (!contact_points_.empty() && !tracks_.empty()) {
      const int points = d.vec3_accessor(contact_points_, false, 0);
      const int offsets = d.accessor(d.view(contact_offsets_.data(), contact_offsets_.size() * 4, 0), 5125,
                                     contact_offsets_.size(), "SCALAR", "");
      extras = ",\"extras\":{\"impulse\":{\"contacts\":{\"points\":" + std::to_string(points) +
               ",\"offsets\":" + std::to_string(offsets) + "}}}";
    }
    // glTF's arrays may not be empty: a world with no bodies is a scene
    // with no nodes and no buffer.
    std::string json = "{\"asset\":{\"version\":\"2.0\",\"generator\":\"impulse\"},\"scene\":0,\"scenes\":[{";
    if (!tracks_.empty()) {
      json += "\"nodes\":[";
      for (std::size_t n = 0; n < tracks_.size(); ++n) json += (n > 0 ? "," : "") + std::to_string(n);
      json += "]";
    }
    json += "}]";
    if (!tracks_.empty())
      json += ",\"nodes\":[" + nodes + "],\"meshes\":[" + meshes + "],\"materials\":[" + materials() +
              "],\"accessors\":[" + d.accessors + "],\"bufferViews\":[" + d.views +
              "],\"buffers\":[{\"byteLength\":" + std::to_string(d.bin.size()) + "}]";
    if (sampler > 0) json += ",\"animations\":[{\"name\":\"run\",\"channels\":[" + channels + "],\"samplers\":[" + samplers + "]}]";
    json += extras + '}';
    while (json.size() % 4 != 0) json += ' ';

    std::vector<std::uint8_t> out;
    const auto word = [&](std::uint32_t v) {
      std::uint8_t bytes[4];
      std::memcpy(bytes, &v, 4);
      out.insert(out.end(), bytes, bytes + 4);
    };
    word(0x46546C67u);  // "glTF"
    word(2);
    const bool has_bin = !d.bin.empty();
    word(std::uint32_t(12 + 8 + json.size() + (has_bin ? 8 + d.bin.size() : 0)));
    word(std::uint32_t(json.size()));
    word(0x4E4F534Au);  // "JSON"
    out.insert(out.end(), json.begin(), json.end());
    if (has_bin) {
      word(std::uint32_t(d.bin.size()));
      word(0x004E4942u);  // "BIN"
      out.insert(out.end(), d.bin.begin(), d.bin.end());
    }
    return out;
  }

  /// Writes glb() to `path`; false if the file could not be written.
  bool save(const char* path) const {
    const std::vector<std::uint8_t> bytes = glb();
    std::FILE* file = std::fopen(path, "wb");
    if (!file) return false;
    const bool written = std::fwrite(bytes.data(), 1, bytes.size(), file) == bytes.size();
    return std::fclose(file) == 0 && written;
  }

 private:
  struct track {
    body_id id{};
    body_type kind = body_type::dynamic;
    std::uint32_t mesh = 0;
    transform<scalar> last{};
    std::vector<float> translations, rotations;  ///< 3 and 4 per frame
  };
  struct mesh_entry {
    shape_mesh mesh;
    std::uint32_t material = 0;  ///< the body kind's
    std::optional<std::array<double, 4>> key;
  };

  /// The buffer as it fills, and the JSON of its views and accessors.
  struct document {
    std::vector<std::uint8_t> bin;
    std::string views, accessors;
    int view_count = 0, accessor_count = 0;

    int view(const void* data, std::size_t bytes, int target) {
      const std::size_t offset = bin.size();
      const auto* p = static_cast<const std::uint8_t*>(data);
      bin.insert(bin.end(), p, p + bytes);
      while (bin.size() % 4 != 0) bin.push_back(0);
      if (view_count > 0) views += ',';
      views += "{\"buffer\":0,\"byteOffset\":" + std::to_string(offset) + ",\"byteLength\":" + std::to_string(bytes);
      if (target != 0) views += ",\"target\":" + std::to_string(target);
      views += '}';
      return view_count++;
    }
    int accessor(int view_index, int component, std::size_t count, const char* type, const std::string& bounds) {
      if (accessor_count > 0) accessors += ',';
      accessors += "{\"bufferView\":" + std::to_string(view_index) + ",\"componentType\":" + std::to_string(component) +
                   ",\"count\":" + std::to_string(count) + ",\"type\":\"" + type + "\"" + bounds + '}';
      return accessor_count++;
    }
    int vec3_accessor(const std::vector<vec3<float>>& v, bool with_bounds, int target) {
      std::vector<float> flat;
      flat.reserve(v.size() * 3);
      float lower[3] = {0, 0, 0}, upper[3] = {0, 0, 0};
      for (std::size_t i = 0; i < v.size(); ++i)
        for (int c = 0; c < 3; ++c) {
          flat.push_back(v[i][c]);
          lower[c] = i == 0 ? v[i][c] : std::min(lower[c], v[i][c]);
          upper[c] = i == 0 ? v[i][c] : std::max(upper[c], v[i][c]);
        }
      std::string bounds;
      if (with_bounds) {
        bounds = ",\"min\":";
        detail::append_numbers(bounds, lower, 3);
        bounds += ",\"max\":";
        detail::append_numbers(bounds, upper, 3);
      }
      return accessor(view(flat.data(), flat.size() * sizeof(float), target), 5126, v.size(), "VEC3", bounds);
    }
    int index_accessor(const std::vector<std::uint32_t>& indices) {
      return accessor(view(indices.data(), indices.size() * 4, 34963), 5125, indices.size(), "SCALAR", "");
    }
    int float_accessor(const std::vector<float>& values, const char* type) {
      const std::size_t width = type[3] == '3' ? 3 : 4;
      return accessor(view(values.data(), values.size() * sizeof(float), 0), 5126, values.size() / width, type, "");
    }
    /// Animation inputs need their bounds.
    int time_accessor(const std::vector<float>& times) {
      std::string bounds = ",\"min\":[";
      detail::append_number(bounds, times.front());
      bounds += "],\"max\":[";
      detail::append_number(bounds, times.back());
      bounds += ']';
      return accessor(view(times.data(), times.size() * sizeof(float), 0), 5126, times.size(), "SCALAR", bounds);
    }
  };

  template <class Shape>
  std::uint32_t mesh_for(const Shape& shape, body_type kind) {
    const std::uint32_t material = std::uint32_t(kind);
    const std::optional<std::array<double, 4>> key = detail::same_shape_key(shape);
    if (key)
      for (std::size_t m = 0; m < meshes_.size(); ++m)
        if (meshes_[m].key == key && meshes_[m].material == material) return std::uint32_t(m);
    meshes_.push_back({mesh_of(shape), material, key});
    return std::uint32_t(meshes_.size() - 1);
  }

  /// One per body_type, in its order: static, kinematic, dynamic.
  static std::string materials() {
    const char* names[] = {"static", "kinematic", "dynamic"};
    const float colors[3][3] = {{0.55f, 0.56f, 0.6f}, {0.3f, 0.55f, 0.9f}, {0.92f, 0.55f, 0.25f}};
    std::string out;
    for (int k = 0; k < 3; ++k) {
      if (k > 0) out += ',';
      const float rgba[4] = {colors[k][0], colors[k][1], colors[k][2], 1};
      out += std::string("{\"name\":\"") + names[k] + "\",\"doubleSided\":true,\"pbrMetallicRoughness\":{\"baseColorFactor\":";
      detail::append_numbers(out, rgba, 4);
      out += ",\"metallicFactor\":0,\"roughnessFactor\":0.8}}";
    }
    return out;
  }

  gltf_options options_;
  std::vector<vec3<float>> contact_points_;
  std::vector<std::uint32_t> contact_offsets_;
  std::vector<float> times_;
  std::vector<track> tracks_;
  std::vector<mesh_entry> meshes_;
};

}  // namespace impulse::io
