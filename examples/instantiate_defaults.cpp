// The one translation unit of hello_world_extern that compiles impulse's
// default configurations (impulse/instantiate.hpp). hello_world.cpp, built
// beside it with IMPULSE_EXTERN_TEMPLATES=1, then only parses the world: the
// way a program with many files keeps each of them fast to compile.
#include "impulse/instantiate.hpp"
