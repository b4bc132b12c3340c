// io/digest.hpp: SHA-256 against the FIPS 180-2 test vectors (appendix B), whole and in pieces.
#include <catch2/catch.hpp>
#include <string>

#include "io/digest.hpp"

using namespace asperity;

TEST_CASE("sha256_hex gives the FIPS 180-2 test vectors", "[io][digest]") {
  CHECK(io::sha256_hex("abc") == "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  CHECK(io::sha256_hex("") == "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  CHECK(io::sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq") ==
        "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  CHECK(io::sha256_hex(std::string(1000000, 'a')) ==
        "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

TEST_CASE("Sha256 over pieces equals sha256_hex of the whole", "[io][digest]") {
  const std::string text = "index,hash\n0,5c1c16e6ef7a4261\n1,\xff\x00x\n";
  for (std::size_t cut = 0; cut <= text.size(); ++cut) {
    io::Sha256 h;
    h.update(std::string_view(text).substr(0, cut));
    h.update(std::string_view(text).substr(cut));
    CHECK(h.hex() == io::sha256_hex(text));
  }
  // One flipped bit anywhere changes the digest.
  std::string flipped = text;
  flipped[5] ^= 1;
  CHECK(io::sha256_hex(flipped) != io::sha256_hex(text));
}
