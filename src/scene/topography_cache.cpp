#include "scene/topography_cache.hpp"

#include "io/digest.hpp"

namespace asperity {

std::shared_ptr<const TopographyContact> TopographyCache::contact(const TopographyRecipe& recipe) {
  const std::string key = io::sha256_hex(topography_section_yaml(recipe, false));
  std::promise<std::shared_ptr<const TopographyContact>> mine;
  const Result own = mine.get_future().share();
  Result found;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (const auto it = by_key_.find(key); it != by_key_.end()) {
      found = it->second;
    } else {
      by_key_.emplace(key, own);
      order_.push_back(key);
      ++solves_;
      // Dropping an entry someone still waits on is safe: the waiter holds its shared_future.
      while (order_.size() > capacity_) {
        by_key_.erase(order_.front());
        order_.pop_front();
      }
    }
  }
  if (found.valid()) return found.get();  // found, or being solved by another caller: wait outside the lock
  try {                                   // the solve, outside the lock: other keys proceed meanwhile
    mine.set_value(std::make_shared<const TopographyContact>(solve_topography_contact(recipe, 1)));
  } catch (...) {
    mine.set_exception(std::current_exception());
  }
  return own.get();
}

std::uint64_t TopographyCache::solves() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return solves_;
}

std::shared_ptr<const TopographyContact> topography_contact(const TopographyRecipe& recipe, TopographyCache* cache) {
  if (cache) return cache->contact(recipe);
  return std::make_shared<const TopographyContact>(solve_topography_contact(recipe, 1));
}

}  // namespace asperity
