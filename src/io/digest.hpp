#pragma once
// Integrity of what asperity reads back as its own results (journal lines, points.csv): SHA-256
// (FIPS 180-4, OpenSSL's libcrypto). FNV-1a (io/hash.hpp) names things; it is not an integrity
// check, since anyone can make a line with any wanted FNV value in microseconds. SHA-256 cannot be
// matched by a damaged or spliced line; a deliberate forger can still recompute it, which is why
// a fit also re-runs its best point (fit/fit.cpp) and a store keeps points.csv equal to its
// journal (campaign/sweep_store_provenance.cpp).
#include <filesystem>
#include <string>
#include <string_view>

namespace asperity::io {

// SHA-256 of `bytes` as 64 lowercase hex digits.
std::string sha256_hex(std::string_view bytes);

// SHA-256 of a file's bytes, streamed (std::runtime_error naming it when it cannot be read).
std::string sha256_file_hex(const std::filesystem::path& file);

// The same over bytes given in pieces (a file streamed through it).
class Sha256 {
 public:
  Sha256();
  ~Sha256();
  Sha256(const Sha256&) = delete;
  Sha256& operator=(const Sha256&) = delete;
  void update(std::string_view bytes);
  std::string hex();  // finishes: 64 lowercase hex digits; the object is then spent

 private:
  void* ctx_;  // EVP_MD_CTX (kept out of this header)
};

}  // namespace asperity::io
