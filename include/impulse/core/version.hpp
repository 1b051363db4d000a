// impulse/core/version.hpp — the library version, one place for it.
//
// CMake and Meson read the version from VERSION at the repository root; a test
// checks that these macros agree with it, so a release bumps both together.
#pragma once

#define IMPULSE_VERSION_MAJOR 0
#define IMPULSE_VERSION_MINOR 1
#define IMPULSE_VERSION_PATCH 0
#define IMPULSE_VERSION_STRING "0.1.0"

namespace impulse {

struct version_info {
  int major;
  int minor;
  int patch;
};

inline constexpr version_info version{IMPULSE_VERSION_MAJOR, IMPULSE_VERSION_MINOR,
                                      IMPULSE_VERSION_PATCH};

}  // namespace impulse
