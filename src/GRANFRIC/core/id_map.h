// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// GRANFRIC physics core: a map from particle IDs to slots, sized by the slots it holds.
//
// An array indexed by ID would be as long as the largest ID in the whole system on every MPI
// rank; this open-addressing hash table (linear probing, deletion by backward shift) holds only
// the IDs a rank has, at most half full.
#ifndef GRANFRIC_CORE_ID_MAP_H
#define GRANFRIC_CORE_ID_MAP_H

#include <cstddef>
#include <cstdint>
#include <vector>

namespace granfric {

class IdMap {
 public:
  // empty, with room for n IDs before it grows
  void reset(size_t n)
  {
    size_t cap = 16;
    while (cap < 2 * n) cap *= 2;
    keys.assign(cap, EMPTY);
    vals.assign(cap, -1);
    mask = cap - 1;
    count = 0;
  }
  // the value of ID key (>= 0), or -1
  int get(long key) const
  {
    for (size_t i = home(key);; i = (i + 1) & mask) {
      if (keys[i] == key) return vals[i];
      if (keys[i] == EMPTY) return -1;
    }
  }
  // ID key (>= 0) maps to value from now on
  void set(long key, int value)
  {
    if (2 * (count + 1) > keys.size()) grow();
    size_t i = home(key);
    while (keys[i] != EMPTY && keys[i] != key) i = (i + 1) & mask;
    if (keys[i] == EMPTY) count++;
    keys[i] = key;
    vals[i] = value;
  }
  // ID key maps to nothing from now on
  void erase(long key)
  {
    size_t i = home(key);
    while (keys[i] != key) {
      if (keys[i] == EMPTY) return;
      i = (i + 1) & mask;
    }
    count--;
    // the later entries of the run move back where their probe sequence allows
    for (size_t j = (i + 1) & mask; keys[j] != EMPTY; j = (j + 1) & mask) {
      const size_t h = home(keys[j]);
      const bool stays = i <= j ? (i < h && h <= j) : (i < h || h <= j);
      if (stays) continue;
      keys[i] = keys[j];
      vals[i] = vals[j];
      i = j;
    }
    keys[i] = EMPTY;
    vals[i] = -1;
  }
  size_t size() const { return count; }
  size_t memory_bytes() const { return keys.capacity() * sizeof(long) + vals.capacity() * sizeof(int); }

 private:
  static constexpr long EMPTY = -1;
  std::vector<long> keys{std::vector<long>(16, EMPTY)};
  std::vector<int> vals{std::vector<int>(16, -1)};
  size_t mask = 15, count = 0;
  size_t home(long key) const
  {
    return (size_t) (((uint64_t) key * 0x9e3779b97f4a7c15ULL) >> 32) & mask;
  }
  void grow()
  {
    std::vector<long> k;
    std::vector<int> v;
    k.swap(keys);
    v.swap(vals);
    reset(k.size());    // (twice the capacity: room for k.size() IDs)
    for (size_t i = 0; i < k.size(); i++)
      if (k[i] != EMPTY) set(k[i], v[i]);
  }
};

}    // namespace granfric

#endif
