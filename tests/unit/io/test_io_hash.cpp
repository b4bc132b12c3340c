// io/hash.hpp: FNV-1a 64 against the published test vectors and a bitwise recomputation.
#include <catch2/catch.hpp>
#include <cstdint>
#include <string>

#include "io/hash.hpp"

using namespace asperity;

TEST_CASE("fnv1a64 gives the published FNV-1a 64 test vectors", "[io][hash]") {
  // From the reference test suite of Fowler/Noll/Vo (test_fnv.c, fnv1a_64 column).
  CHECK(io::fnv1a64("") == 0xcbf29ce484222325ull);
  CHECK(io::fnv1a64("a") == 0xaf63dc4c8601ec8cull);
  CHECK(io::fnv1a64("foobar") == 0x85944171f73967e8ull);
  // Bytes above 0x7f hash as unsigned bytes: the one-byte case by hand,
  // (basis ^ 0xff) * prime mod 2^64.
  const std::uint64_t by_hand = (0xcbf29ce484222325ull ^ 0xffull) * 1099511628211ull;
  CHECK(io::fnv1a64(std::string(1, '\xff')) == by_hand);
}

TEST_CASE("hex16 writes 16 lowercase hex digits, leading zeros kept", "[io][hash]") {
  CHECK(io::hex16(0) == "0000000000000000");
  CHECK(io::hex16(0xcbf29ce484222325ull) == "cbf29ce484222325");
  CHECK(io::hex16(0xabcull) == "0000000000000abc");
  CHECK(io::hex16(~0ull) == "ffffffffffffffff");
  CHECK(std::stoull(io::hex16(0x85944171f73967e8ull), nullptr, 16) == 0x85944171f73967e8ull);
}

TEST_CASE("fnv1a64 of text given in pieces equals that of the whole", "[io][hash]") {
  // FNV-1a 64 of "a" (published test vector: af63dc4c8601ec8c).
  CHECK(io::fnv1a64_extend(io::fnv1a64(""), "a") == 0xaf63dc4c8601ec8cull);
  const std::string text = "0,0.001,0.52\n0,0.002,0.53\n";
  for (std::size_t cut = 0; cut <= text.size(); ++cut)
    CHECK(io::fnv1a64_extend(io::fnv1a64(text.substr(0, cut)), std::string_view(text).substr(cut)) ==
          io::fnv1a64(text));
}
