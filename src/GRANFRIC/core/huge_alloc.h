// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// GRANFRIC physics core: allocator for the large per-particle arrays. Blocks of 4 MiB and more
// are aligned to 2 MiB and, on Linux, marked for transparent huge pages: with millions of
// particles the event loop touches records scattered over hundreds of MiB, and with 4 KiB pages
// nearly every such touch also misses the TLB. Elsewhere (or if the kernel declines) it is a
// plain aligned allocation.
#ifndef GRANFRIC_CORE_HUGE_ALLOC_H
#define GRANFRIC_CORE_HUGE_ALLOC_H

#include <cstddef>
#include <cstdlib>
#include <new>
#include <vector>
#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace granfric {

template <class T> struct HugeAllocator {
  using value_type = T;
  HugeAllocator() = default;
  template <class U> HugeAllocator(const HugeAllocator<U> &) {}
  static constexpr std::size_t HUGE = std::size_t(2) << 20;
  T *allocate(std::size_t n)
  {
    const std::size_t bytes = n * sizeof(T);
    if (bytes < 2 * HUGE) {
      const std::size_t al = alignof(T) > alignof(std::max_align_t) ? alignof(T) : 0;
      void *p = al ? std::aligned_alloc(al, (bytes + al - 1) / al * al) : std::malloc(bytes);
      if (!p) throw std::bad_alloc();
      return static_cast<T *>(p);
    }
    const std::size_t rounded = (bytes + HUGE - 1) / HUGE * HUGE;
    void *p = std::aligned_alloc(HUGE, rounded);
    if (!p) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    madvise(p, rounded, MADV_HUGEPAGE);
#endif
    return static_cast<T *>(p);
  }
  void deallocate(T *p, std::size_t) { std::free(p); }
  template <class U> bool operator==(const HugeAllocator<U> &) const { return true; }
  template <class U> bool operator!=(const HugeAllocator<U> &) const { return false; }
};

template <class T> using big_vector = std::vector<T, HugeAllocator<T>>;

}    // namespace granfric

#endif
