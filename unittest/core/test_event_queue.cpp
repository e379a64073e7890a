// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// The event queue against an ordered set: the same (time, index) order under random updates,
// ties, infinite times, far-future events and time shifts, with links to later buckets made at
// once and made a few updates later; the two following events where known.
#include "core/event_queue.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iterator>
#include <limits>
#include <random>
#include <set>
#include <utility>
#include <vector>

using granfric::EventQueue;

namespace {

constexpr double INF = std::numeric_limits<double>::infinity();

// Simulates an event loop: pop the earliest, give it a later time, sometimes change others.
// p_shift: chance per step of a new window, whose shift is the current time (odd = false) or
// an arbitrary fraction of it (odd = true: times and the calendar's origin then round apart)
// wait: links to later buckets wait (EventQueue::set_wait_from(0)), as in large queues
void run_against_set(int n, unsigned seed, double spread, double p_inf, double p_far, int steps,
                     double p_shift = 0.001, bool odd = false, bool wait = false)
{
  std::mt19937_64 gen(seed);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  auto draw = [&](double now) {
    const double u = U(gen);
    if (u < p_inf) return INF;
    if (u < p_inf + p_far) return now + 1e6 * spread * U(gen);
    if (u < p_inf + p_far + 0.05) return now;    // ties at the current time
    // coarse grid: many exact ties
    return now + std::floor(U(gen) * 64.0) * spread / 16.0;
  };
  std::vector<double> t(n);
  for (auto &x : t) x = draw(0.0);
  EventQueue q;
  if (wait) q.set_wait_from(0);
  q.build(t);
  std::set<std::pair<double, int>> ref;
  for (int i = 0; i < n; i++) ref.insert({t[i], i});
  double now = 0.0;
  for (int s = 0; s < steps; s++) {
    const auto best = *ref.begin();
    ASSERT_EQ(q.top_time(), best.first) << "step " << s;
    if (best.first == INF) {
      ASSERT_EQ(t[q.top()], INF);
      break;
    }
    ASSERT_EQ(q.top(), best.second) << "step " << s;
    now = best.first;
    auto set_time = [&](int i, double x) {
      ref.erase({t[i], i});
      t[i] = x;
      ref.insert({x, i});
      q.update(i, x);
    };
    set_time(best.second, draw(now));
    // a partner's prediction changes too
    if (U(gen) < 0.5) set_time((int) (U(gen) * n), draw(now));
    if (U(gen) < p_shift) {
      // a new window: every time shifted
      const double dt = odd ? now * (0.3 + 0.7 * U(gen)) + 1e-3 * spread * U(gen) : now;
      q.shift(dt);
      std::set<std::pair<double, int>> r2;
      for (int i = 0; i < n; i++) {
        t[i] -= dt;
        r2.insert({t[i], i});
      }
      ref.swap(r2);
      now -= dt;
    }
  }
}

}    // namespace

TEST(EventQueue, OrderEqualsSortedSet)
{
  run_against_set(1000, 1, 1.0, 0.0, 0.0, 200000);
}

TEST(EventQueue, FrequentArbitraryShifts)
{
  // the calendar's origin moves with the times: rounding may put a shifted time into the next
  // or previous bucket, or make two times equal; the order must stay exactly (time, index)
  run_against_set(1000, 5, 1.0, 0.05, 0.01, 200000, 0.02, true);
  run_against_set(200, 6, 1e-7, 0.0, 0.0, 100000, 0.05, true);
}

TEST(EventQueue, WaitingLinksKeepTheOrder)
{
  // every link to a later bucket waits a few updates, with removals of waiting events, the
  // front emptying (which makes the waiting links first) and shifts
  run_against_set(1000, 7, 1.0, 0.0, 0.0, 200000, 0.001, false, true);
  run_against_set(1000, 8, 1.0, 0.05, 0.01, 200000, 0.02, true, true);
  run_against_set(500, 9, 1.0, 0.2, 0.02, 100000, 0.001, false, true);
  run_against_set(3, 10, 1.0, 0.1, 0.1, 10000, 0.001, false, true);
}

TEST(EventQueue, InfiniteAndFarEvents)
{
  run_against_set(500, 2, 1.0, 0.2, 0.02, 100000);
}

TEST(EventQueue, SmallAndSingle)
{
  run_against_set(1, 3, 1.0, 0.1, 0.1, 1000);
  run_against_set(3, 4, 1.0, 0.1, 0.1, 10000);
}

TEST(EventQueue, AllInfiniteThenFinite)
{
  EventQueue q;
  q.build(std::vector<double>(10, INF));
  EXPECT_EQ(q.top_time(), INF);
  q.update(7, 3.0);
  EXPECT_EQ(q.top(), 7);
  q.update(2, 1e300);
  q.update(7, INF);
  EXPECT_EQ(q.top(), 2);
  EXPECT_EQ(q.top_time(), 1e300);
}
