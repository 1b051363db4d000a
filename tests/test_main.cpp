// The doctest runner for every test file; doctest comes from Debian's doctest-dev.
#define DOCTEST_CONFIG_IMPLEMENT_WITH_MAIN
#include <doctest/doctest.h>
