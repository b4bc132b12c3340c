// Wide console: Catch2 v2 wraps long test names when listing them, which would hide tests
// from CTest's discovery.
#define CATCH_CONFIG_CONSOLE_WIDTH 1000
#define CATCH_CONFIG_MAIN
#include <catch2/catch.hpp>
