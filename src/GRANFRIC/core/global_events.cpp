// SPDX-License-Identifier: GPL-2.0-or-later
// Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
// GRANFRIC physics core: global events (see event_driven.h), instants at which every particle
// may change at once (random kicks), after which every prediction is made afresh.
#include "event_driven.h"

namespace granfric {

void EventDriven::set_global_events(const std::vector<double> &times, std::function<void(int)> apply)
{
  gtimes = times;
  gapply = std::move(apply);
}

void EDCore::global_event(int k)
{
  now = gtimes[k];
  const int n = (int) flights.size();
  auto energy = [&]() {
    double e = 0.0;
    for (int i = 0; i < n; i++) {
      const Collider &p = colliders[i];
      const Flight &h = flights[i];
      if (counted(i)) e += 0.5 * p.m * (norm2(h.v) + qt[schedules[i].type] * h.a * h.a * norm2(p.w));
    }
    return e;
  };
  for (int i = 0; i < n; i++) advance(i, now);
  const double before = energy();
  gapply(k);
  stats.injected += energy() - before;
  stats.global_events++;
  for (int i = 0; i < n; i++) {
    Flight &h = flights[i];
    Collider &p = colliders[i];
    turned(i);    // every trajectory changed: all stored predictions are stale
    p.last_partner = -1;
    if (opt.dim == 2) {
      h.v.z = 0.0;
      p.w.x = p.w.y = 0.0;
    }
    if (tracking_fast()) note_speed(i, h.v);
  }
  predict_all();
  std::vector<double> times(n);
  for (int i = 0; i < n; i++) times[i] = schedule(i);
  queue.build(times);
}

}    // namespace granfric
