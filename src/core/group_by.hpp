// Counting sorts over small integer keys: the world's grouping of bodies, joints and contacts
// by island, and its ordering of the broadphase's pairs by key.
#pragma once

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

namespace ragdoll_sim {

// Stable counting sort of items into groups (key(item) in [0, groups)); offsets gets the
// group boundaries (size groups + 1).
template <class T, class Key>
void groupBy(std::vector<T>& items, int groups, Key key, std::vector<T>& scratch,
             std::vector<int>& offsets, std::vector<int>& cursor) {
  offsets.assign(groups + 1, 0);
  for (const T& t : items) ++offsets[key(t) + 1];
  for (int g = 0; g < groups; ++g) offsets[g + 1] += offsets[g];
  scratch.resize(items.size());
  cursor.assign(offsets.begin(), offsets.end() - 1);
  for (T& t : items) scratch[cursor[key(t)]++] = std::move(t);
  items.swap(scratch);
}

// Sorts pair keys (first shape << 32 | second shape, first < shape_count) ascending: grouped by
// the first shape, then each group by insertion sort (a shape has few partners, and a plane's
// come from the broadphase in ascending order), or std::sort for a large unsorted group (a
// static box under many bodies), which is cheaper than one std::sort of all keys. Unique
// keys (pairs) come out in the same order as with std::sort. The grouping costs a pass over
// all shapes, so few keys among many shapes (a world of sleeping ragdolls with one awake: its
// pairs are found, the sleeping ones carried over) take std::sort instead.
inline void sortPairKeys(std::vector<uint64_t>& keys, int shape_count,
                         std::vector<uint64_t>& scratch, std::vector<int>& offsets,
                         std::vector<int>& cursor) {
  constexpr std::ptrdiff_t kInsertionMax = 32;
  if (keys.empty()) return;  // (data() may be null: no pointer arithmetic on it)
  if (8 * keys.size() < size_t(shape_count)) return std::sort(keys.begin(), keys.end());
  groupBy(keys, shape_count, [](uint64_t k) { return int(k >> 32); }, scratch, offsets, cursor);
  for (int g = 0; g < shape_count; ++g) {
    uint64_t *begin = keys.data() + offsets[g], *end = keys.data() + offsets[g + 1];
    if (end - begin < 2) continue;
    if (end - begin > kInsertionMax && !std::is_sorted(begin, end)) {
      std::sort(begin, end);
      continue;
    }
    for (uint64_t* i = begin + 1; i < end; ++i) {
      const uint64_t key = *i;
      uint64_t* j = i;
      for (; j > begin && j[-1] > key; --j) *j = j[-1];
      *j = key;
    }
  }
}

}  // namespace ragdoll_sim
