// The one translation unit that compiles impulse's default configurations
// (impulse/instantiate.hpp): the examples and the tests, built with
// IMPULSE_EXTERN_TEMPLATES=1, link it and only parse the world, the way a
// program with many files keeps each of them fast to compile
// (hello_world_extern is hello_world.cpp built so).
#include "impulse/instantiate.hpp"
