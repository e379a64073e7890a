// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// GRANFRIC physics core: the queue of particle event times (one pending event per particle).
//
// A calendar queue (cf. G. Paul, J. Comput. Phys. 221, 615 (2007)): time is cut into buckets
// of width w; a particle whose event lies in one of the next nb buckets sits in that bucket's
// unsorted list (circular array of nb lists), a later (or never) event in an overflow list. Only
// the current bucket is ordered, as a small indexed binary heap (the "front"). Updating an event
// is O(1) on average (unlink, link) instead of O(log N) cache-missing heap levels, so the cost
// per event stays flat with N. w is set at build() from the spread of the event times (about two
// pending events per bucket near the front).
//
// The order is exactly that of (time, particle index): buckets are a monotone function of time,
// so an earlier bucket holds only earlier events, and the front heap breaks ties by index. The
// trajectory is therefore bit-for-bit the one of any other exact priority queue.
//
// With many buckets (WAIT_FROM and more: their heads then take 1 MiB and more, more than a
// second-level cache holds) a link to a later bucket waits a few updates (WAIT of them, and
// never beyond the moment the front empties, before the calendar moves on): the bucket's head
// is asked for from the memory when the time is given and read when the link is made. That
// head is then mostly a miss, which linking at once would wait for. No waiting
// event can be the next one: it lies in a later bucket than the front's, and the front moves on
// only after every waiting link is made.
#ifndef GRANFRIC_CORE_EVENT_QUEUE_H
#define GRANFRIC_CORE_EVENT_QUEUE_H

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "huge_alloc.h"

namespace granfric {

class EventQueue {
 public:
  // n particles with their event times (infinite: no event); O(n)
  void build(const std::vector<double> &times)
  {
    const int n = (int) times.size();
    node.assign(n, Node{});
    for (int i = 0; i < n; i++) node[i].key = times[i];
    front.clear();
    // origin at the earliest event, width from the mean lead of the finite ones
    double tmin = INF, sum = 0.0;
    long finite = 0;
    for (double t : times)
      if (t < INF) {
        tmin = t < tmin ? t : tmin;
        finite++;
      }
    for (double t : times)
      if (t < INF) sum += t - tmin;
    origin = finite ? tmin : 0.0;
    nb = 16;
    while (2 * nb < n) nb *= 2;
    const double lead = finite ? sum / (double) finite : 0.0;
    w = lead > 0.0 ? 2.0 * lead / (double) nb : 1.0;
    // a width below the resolution of the times would put everything in one bucket; harmless
    if (!(w > 0.0) || !std::isfinite(w)) w = 1.0;
    inv_w = 1.0 / w;
    head.assign(nb, -1);
    overflow = -1;
    nbucketed = 0;
    nwait = wfirst = 0;
    waits = nb >= wait_from;
    cur = 0;
    for (Walk &k : walk) k = Walk{};
    for (int i = 0; i < n; i++) insert(i);
    settle();
  }
  bool empty() const { return node.empty(); }
  // from how many buckets on links wait (WAIT_FROM; 0: always, for tests); at the next build()
  void set_wait_from(int buckets) { wait_from = buckets; }
  // the particle with the earliest event (ties: the smallest index); with no finite event left,
  // some particle whose event time is infinite
  int top() const { return front.empty() ? overflow : front[0]; }
  double top_time() const { return node[top()].key; }
  // Performance only (no effect on the order): ask the memory for the records that the next
  // calls will read. In a queue far larger than the cache every record is a miss, and the list
  // of a bucket, which settle() walks when the bucket comes to the front, a chain of them.
  //   prefetch_ahead(also) one step further along the list of each of the next AHEAD buckets
  //                        (called once per event: the step asked for at the last call has
  //                        arrived, so reading it does not wait), and also(i) for each particle
  //                        i stepped to, so that the caller can ask for its own records of
  //                        events to come. A particle linked to a bucket since its walk began
  //                        was touched then.
  //   prefetch(i)          what update(i) reads first: particle i's record
  //   prefetch_time(t)     the head of the bucket that update(i, t) links i to (the caller
  //                        asks as soon as it knows a time the event may get)
  // (GCC counts a prefetch as touching no memory, so it takes a function that does nothing
  // else for one without effects and drops its calls; the empty volatile asm is an effect)
  template <class F>
  void prefetch_ahead(F &&also)
  {
    asm volatile("");
    for (int64_t b = cur + 1; b <= cur + AHEAD; b++) {
      Walk &k = walk[b & (AHEAD - 1)];
      const int s = (int) (b & (nb - 1));
      int p;
      if (k.b != b || k.p < 0 || node[k.p].where != s) {
        k.b = b;
        p = head[s];
      } else {
        p = node[k.p].nxt;
        if (p < 0) continue;    // (the end of the list: stay there)
      }
      k.p = p;
      if (p < 0) continue;
      __builtin_prefetch(&node[p]);
      also(p);
    }
  }
  void prefetch(int i) const
  {
    asm volatile("");
    __builtin_prefetch(&node[i]);
  }
  // where insert() would link an event at time t: its bucket's head
  void prefetch_time(double t) const
  {
    asm volatile("");
    const double u = (t - origin) * inv_w;
    if (!(u < (double) (cur + nb))) return;    // (beyond the calendar, or never)
    const int64_t b = (int64_t) u;
    __builtin_prefetch(&head[(b > cur ? b : cur) & (nb - 1)]);
  }
  double time(int i) const { return node[i].key; }
  // particle i now has event time t
  void update(int i, double t)
  {
    remove(i);
    node[i].key = t;
    insert(i);
    settle();
  }
  // every time minus dt (a window restarts at 0). The calendar's origin moves with the times,
  // so each stays in its bucket, except where rounding of the two subtractions differs: every
  // particle's bucket is recomputed and the few misplaced ones are moved; the front heap is
  // re-ordered (rounding can make two times equal, and ties go by index). The order is then
  // exactly (time, index) again, as after a rebuild, at a fraction of its cost.
  void shift(double dt)
  {
    origin -= dt;
    const int n = (int) node.size();
    for (int i = 0; i < n; i++) {
      node[i].key -= dt;
      const int64_t b = bucket(node[i].key);
      const int s = node[i].where;
      const bool right = b == BEYOND ? s == OVER : b == cur ? s <= FRONT : s == (int) (b & (nb - 1));
      if (right) continue;
      remove(i);
      insert(i);
    }
    for (int k = (int) front.size() / 2 - 1; k >= 0; k--) down(k);
    settle();
  }
  size_t memory_bytes() const
  {
    return node.capacity() * sizeof(Node) + (front.capacity() + head.capacity()) * sizeof(int);
  }

 private:
  static constexpr double INF = std::numeric_limits<double>::infinity();
  // where: slot of its bucket list (>= 0; the bucket is the one of the next nb with that
  // slot), nb + that slot while its link waits, OVER (overflow list), or FRONT - k at position
  // k of the front heap
  static constexpr int NOWHERE = -1, OVER = -2, FRONT = -3;
  static constexpr int64_t BEYOND = -1;
  // a particle's event time, where it is, and its links in a bucket or the overflow list
  // (doubly linked): one 20-byte record, so that touching a particle of the queue (its unlink
  // and link, its move to the front) reads one cache line, not four
  struct __attribute__((packed)) Node {
    double key = INF;
    int where = NOWHERE;
    int nxt = -1, prv = -1;
  };
  static_assert(sizeof(Node) == 20, "a queue record holds 20 bytes");
  big_vector<Node> node;
  big_vector<int> head;             // nb circular bucket lists
  int overflow = -1;                // overflow list
  long nbucketed = 0;               // particles in bucket lists
  std::vector<int> front;           // heap of the current bucket
  double origin = 0.0, w = 1.0, inv_w = 1.0;
  int64_t cur = 0;                  // absolute index of the current bucket
  int nb = 16;
  // prefetch_ahead()'s walks: bucket b's (absolute index) at AHEAD's b modulo, at particle p
  static constexpr int AHEAD = 4;
  struct Walk {
    int64_t b = -1;
    int p = -1;
  };
  Walk walk[AHEAD];
  // the particles whose links wait, oldest first from wfirst (circular; -1: removed since)
  static constexpr int WAIT = 8, WAIT_FROM = 1 << 18;
  static_assert((WAIT & (WAIT - 1)) == 0, "WAIT is a power of 2");
  int waiting[WAIT];
  int wfirst = 0, nwait = 0;
  int wait_from = WAIT_FROM;
  bool waits = false;    // (nb >= wait_from)

  bool less(int a, int b) const
  {
    const double ka = node[a].key, kb = node[b].key;
    return ka < kb || (ka == kb && a < b);
  }
  // absolute bucket of time t; beyond the horizon (or infinite): BEYOND
  int64_t bucket(double t) const
  {
    const double u = (t - origin) * inv_w;
    if (!(u < (double) (cur + nb))) return BEYOND;
    // truncation differs from floor only for u in (-1, 0), and both give cur (>= 0) then
    const int64_t b = (int64_t) u;
    return b > cur ? b : cur;
  }
  void link(int &h, int i)
  {
    node[i].nxt = h;
    node[i].prv = -1;
    if (h >= 0) node[h].prv = i;
    h = i;
  }
  void unlink(int &h, int i)
  {
    const int p = node[i].prv, q = node[i].nxt;
    if (p >= 0)
      node[p].nxt = q;
    else
      h = q;
    if (q >= 0) node[q].prv = p;
  }
  void insert(int i)
  {
    const int64_t b = bucket(node[i].key);
    if (b == BEYOND) {
      node[i].where = OVER;
      link(overflow, i);
    } else if (b == cur) {
      push_front(i);
    } else {
      const int s = (int) (b & (nb - 1));
      nbucketed++;
      if (!waits) {
        node[i].where = s;
        link(head[s], i);
        return;
      }
      __builtin_prefetch(&head[s], 1);
      if (nwait == WAIT) link_oldest();
      node[i].where = nb + s;
      waiting[(wfirst + nwait++) & (WAIT - 1)] = i;
    }
  }
  // the oldest waiting link made (removed ones skipped)
  void link_oldest()
  {
    while (nwait > 0) {
      const int i = waiting[wfirst];
      wfirst = (wfirst + 1) & (WAIT - 1);
      nwait--;
      if (i < 0) continue;
      const int s = node[i].where - nb;
      node[i].where = s;
      link(head[s], i);
      return;
    }
  }
  void link_waiting()
  {
    while (nwait > 0) link_oldest();
  }
  void push_front(int i)
  {
    front.push_back(i);
    up((int) front.size() - 1);
  }
  void remove(int i)
  {
    const int s = node[i].where;
    if (s <= FRONT) {
      const int k = FRONT - s;
      const int last = front.back();
      front.pop_back();
      if (last != i) {
        place(k, last);
        up(k);
        down(FRONT - node[last].where);
      }
    } else if (s == OVER) {
      unlink(overflow, i);
    } else if (s >= nb) {
      for (int k = 0; k < nwait; k++) {
        int &w = waiting[(wfirst + k) & (WAIT - 1)];
        if (w == i) w = -1;
      }
      nbucketed--;
    } else {
      unlink(head[s], i);
      nbucketed--;
    }
    node[i].where = NOWHERE;
  }
  // make the front non-empty if any finite event is left: advance to the next occupied bucket,
  // pulling overflow events into range at each turn of the calendar
  void settle()
  {
    while (front.empty()) {
      link_waiting();    // (before the calendar moves on)
      if (nbucketed == 0) {
        // nothing within the horizon: jump to the earliest finite overflow event
        double tmin = INF;
        for (int i = overflow; i >= 0; i = node[i].nxt) tmin = node[i].key < tmin ? node[i].key : tmin;
        if (!(tmin < INF)) return;
        const double u = (tmin - origin) * inv_w;
        if (u > 1e15) {
          // far beyond the calendar's resolution: restart it there
          std::vector<double> k(node.size());
          for (size_t i = 0; i < node.size(); i++) k[i] = node[i].key;
          build(k);
          return;
        }
        cur = (int64_t) std::floor(u);
        if (cur < 0) cur = 0;
        pull_overflow();
        continue;
      }
      cur++;
      if ((cur & (nb - 1)) == 0) pull_overflow();
      int &h = head[cur & (nb - 1)];
      while (h >= 0) {
        const int i = h;
        unlink(h, i);
        nbucketed--;
        push_front(i);
      }
    }
  }
  void pull_overflow()
  {
    int i = overflow;
    while (i >= 0) {
      const int nexti = node[i].nxt;
      if (bucket(node[i].key) != BEYOND) {
        unlink(overflow, i);
        insert(i);
      }
      i = nexti;
    }
  }
  void place(int k, int i)
  {
    front[k] = i;
    node[i].where = FRONT - k;
  }
  void up(int k)
  {
    const int e = front[k];
    while (k > 0) {
      const int parent = (k - 1) / 2;
      if (!less(e, front[parent])) break;
      place(k, front[parent]);
      k = parent;
    }
    place(k, e);
  }
  void down(int k)
  {
    const int n = (int) front.size();
    const int e = front[k];
    while (true) {
      int c = 2 * k + 1;
      if (c >= n) break;
      if (c + 1 < n && less(front[c + 1], front[c])) c++;
      if (!less(front[c], e)) break;
      place(k, front[c]);
      k = c;
    }
    place(k, e);
  }
};

}    // namespace granfric

#endif
