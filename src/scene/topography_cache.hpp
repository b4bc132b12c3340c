#pragma once
// The contact solves of topography scenes, once per distinct (surface, sphere, E, ν, load,
// contact settings) for the life of the object: a sweep whose axes are model keys, or whose
// surface axes repeat, solves each surface once. Owned by whoever runs many scenes (a campaign
// holds one for its load, its probes and its points); not a global.
//
// Key: the SHA-256 of the recipe's canonical text without name and slider
// (topography_section_yaml(recipe, false)); a measured map is named by its path, so its bytes
// must not change during the object's life. The first caller of a key solves it outside the
// lock; others asking for the same key meanwhile wait for that result (or its InputError, which
// is kept too: the same recipe fails the same way). Thread-safe.
//
// Memory: at most `capacity` results are kept (default 64; the oldest is dropped first), each a
// junction population of 24 bytes a junction (a 512² map gives a few thousand junctions: ~0.1
// MB; at most n²/2 junctions for an n² map), so the bound is capacity × 12 n_max² bytes.
#include <cstddef>
#include <cstdint>
#include <deque>
#include <future>
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "scene/topography_junctions.hpp"

namespace asperity {

class TopographyCache {
 public:
  explicit TopographyCache(std::size_t capacity = 64) : capacity_(capacity ? capacity : 1) {}

  // The contact of `recipe`, solved now (once per key) or found. InputError as
  // solve_topography_contact throws.
  std::shared_ptr<const TopographyContact> contact(const TopographyRecipe& recipe);

  std::uint64_t solves() const;  // contact solves run so far (the cache's misses)

 private:
  using Result = std::shared_future<std::shared_ptr<const TopographyContact>>;
  std::size_t capacity_;
  mutable std::mutex mutex_;
  std::map<std::string, Result> by_key_;
  std::deque<std::string> order_;  // keys, oldest first (eviction)
  std::uint64_t solves_ = 0;
};

// The contact of `recipe` through `cache` when given, else solved now.
std::shared_ptr<const TopographyContact> topography_contact(const TopographyRecipe& recipe, TopographyCache* cache);

}  // namespace asperity
