#pragma once
// Identity of text: the hash the campaign store, sweep and fit writer use for points, files and
// names. FNV-1a 64 (offset basis 14695981039346656037, prime 1099511628211) is stable across
// runs, machines and library versions, unlike std::hash / boost::hash.
#include <cstdint>
#include <string>
#include <string_view>

namespace asperity::io {

std::uint64_t fnv1a64(std::string_view bytes);
// The FNV-1a 64 of text given in pieces: fnv1a64_extend(fnv1a64(a), b) == fnv1a64(a + b).
std::uint64_t fnv1a64_extend(std::uint64_t h, std::string_view more);
std::string hex16(std::uint64_t h);  // 16 lowercase hex digits

}  // namespace asperity::io
