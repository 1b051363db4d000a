// A program that uses impulse the way a downstream project would: it makes a
// world, drops a box on the ground, checks it comes to rest there, and writes
// the run as a glTF recording (the viewer's format). tests/consumer/run.sh
// builds it through find_package, pkg-config, add_subdirectory, a Meson
// subproject and the single headers alone; compiled with
// -DIMPULSE_CONSUMER_SINGLE_HEADER it includes the io single header
// (single_include/impulse/impulse_io.hpp, which includes impulse.hpp).
//
//   consumer [recording.glb]    (default: consumer.glb in the temp directory)
//
// Exits 0 only if the box rests on the ground and the file is a GLB.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>

#ifdef IMPULSE_CONSUMER_SINGLE_HEADER
#include "impulse/impulse_io.hpp"
#else
#include "impulse/impulse.hpp"
#include "impulse/io/gltf.hpp"
#endif

namespace {

int fail(const char* what) {
  std::fprintf(stderr, "consumer: %s\n", what);
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  using config = impulse::default_config;
  using T = config::scalar;
  static_assert(impulse::check_config<config>());

  impulse::world<config> world;
  impulse::body_def<T> ground;
  ground.type = impulse::body_type::static_body;
  ground.pose.position = {0, -1, 0};
  world.create_body(ground, impulse::box<T>::make({100, 1, 100}));
  impulse::body_def<T> falling;
  falling.pose.position = {0, 3, 0};
  const impulse::body_id box = world.create_body(falling, impulse::box<T>::make({T(0.5), T(0.5), T(0.5)}));

  impulse::io::gltf_recorder recording(world);
  for (int i = 0; i < 120; ++i) {
    world.step(T(1) / 60);
    recording.record(world);
  }

  const T y = world.shape_pose(box).position.y;
  std::printf("impulse %s: a box dropped from 3 m rests at y = %.4f m after 2 s\n", IMPULSE_VERSION_STRING,
              double(y));
  if (!(std::fabs(y - T(0.5)) <= T(0.01))) return fail("the box is not resting on the ground (y should be 0.5)");

  const std::string path =
      argc > 1 ? argv[1] : (std::filesystem::temp_directory_path() / "impulse_consumer.glb").string();
  if (!recording.save(path.c_str())) return fail("the recording could not be written");
  char magic[4] = {};
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (!file) return fail("the recording is not there");
  const bool read = std::fread(magic, 1, 4, file) == 4;
  std::fclose(file);
  if (!read || std::memcmp(magic, "glTF", 4) != 0) return fail("the recording does not start with \"glTF\"");
  std::printf("recorded 121 frames to %s (%ju bytes)\n", path.c_str(),
              static_cast<std::uintmax_t>(std::filesystem::file_size(path)));
  return 0;
}
