// impulse/core/fwd.hpp — forward declarations of the core module.
#pragma once

#include <cstdint>

namespace impulse {

enum class error_code : std::uint8_t;
class invalid_argument;
enum class policy_kind;
template <template <class> class... Shapes>
struct shape_list;

}  // namespace impulse
