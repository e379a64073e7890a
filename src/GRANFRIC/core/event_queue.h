// GRANFRIC physics core: indexed 4-ary min-heap of particle event times. The keys live in the
// heap itself (no indirection into particle records on every comparison); ties break by
// particle index, so the order of events is deterministic.
#ifndef GRANFRIC_CORE_EVENT_QUEUE_H
#define GRANFRIC_CORE_EVENT_QUEUE_H

#include <vector>

namespace granfric {

class EventQueue {
 public:
  // n particles with their event times; O(n) heapify
  void build(const std::vector<double> &times)
  {
    const int n = (int) times.size();
    heap.resize(n);
    pos.resize(n);
    for (int i = 0; i < n; i++) {
      heap[i] = {times[i], i};
      pos[i] = i;
    }
    for (int k = (n - 2) / 4; k >= 0 && n > 1; k--) down(k);
  }
  bool empty() const { return heap.empty(); }
  int top() const { return heap[0].id; }
  double top_time() const { return heap[0].t; }
  // particle i now has event time t
  void update(int i, double t)
  {
    const int k = pos[i];
    const double old = heap[k].t;
    heap[k].t = t;
    if (t < old)
      up(k);
    else
      down(k);
  }
  // every key minus dt (monotone, so the heap stays ordered)
  void shift(double dt)
  {
    for (auto &e : heap) e.t -= dt;
  }

 private:
  struct Entry {
    double t;
    int id;
  };
  std::vector<Entry> heap;
  std::vector<int> pos;

 public:
  size_t memory_bytes() const { return heap.capacity() * sizeof(Entry) + pos.capacity() * sizeof(int); }

  static bool less(const Entry &a, const Entry &b) { return a.t < b.t || (a.t == b.t && a.id < b.id); }
  void place(int k, const Entry &e)
  {
    heap[k] = e;
    pos[e.id] = k;
  }
  void up(int k)
  {
    const Entry e = heap[k];
    while (k > 0) {
      const int parent = (k - 1) / 4;
      if (!less(e, heap[parent])) break;
      place(k, heap[parent]);
      k = parent;
    }
    place(k, e);
  }
  void down(int k)
  {
    const int n = (int) heap.size();
    const Entry e = heap[k];
    while (true) {
      const int first = 4 * k + 1;
      if (first >= n) break;
      int best = first;
      const int last = first + 4 < n ? first + 4 : n;
      for (int c = first + 1; c < last; c++)
        if (less(heap[c], heap[best])) best = c;
      if (!less(heap[best], e)) break;
      place(k, heap[best]);
      k = best;
    }
    place(k, e);
  }
};

}    // namespace granfric

#endif
