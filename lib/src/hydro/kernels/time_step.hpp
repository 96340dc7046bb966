#pragma once
// Time-step limits of one zone (docs/algorithm.md §9) and the reduction of the candidates.
#include <algorithm>
#include <cmath>

#include "stagger/mesh.hpp"

namespace stagger {

// dt candidate of a zone: CFL with the viscosity-augmented speed, cfl l / (qhat + sqrt(qhat^2
// + C^2)) with qhat = q1 l |div| + q2 C in compression, and the volume limit f_A / |div v|.
[[gnu::always_inline]] inline double zone_time_step(double cfl, double q1, double q2, double volume_limit, double l,
                                                    double C, double div) {
  const double qhat = div < 0 ? q1 * l * (-div) + q2 * C : 0.0;
  const double denom = qhat + std::sqrt(qhat * qhat + C * C);
  double dt = denom > 0 ? cfl * l / denom : 1e300;
  if (div != 0) dt = std::min(dt, volume_limit / std::abs(div));
  return dt;
}

// The step's dt from the smallest zone candidate: at most `growth` times the previous dt
// (after the first cycle), dt_init on the first cycle if smaller, never above dt_max (0 =
// none). `limit` says which bound was active.
enum class DtLimit { cfl, growth, initial, maximum };
struct DtControl {
  double dt;
  DtLimit limit;
};

inline DtControl control_time_step(double candidate, double previous, bool first_cycle, double growth, double dt_init,
                                   double dt_max) {
  DtControl c{candidate, DtLimit::cfl};
  if (!first_cycle && c.dt > growth * previous) c = {growth * previous, DtLimit::growth};
  if (first_cycle && dt_init > 0 && dt_init < c.dt) c = {dt_init, DtLimit::initial};
  if (dt_max > 0 && c.dt > dt_max) c = {dt_max, DtLimit::maximum};
  return c;
}

// The smallest candidate and its zone; ties go to the lowest zone (deterministic for any
// thread count).
struct DtChoice {
  double dt = 1e300;
  Index zone = -1;
};

// Merges one thread's choice into its range's.
inline void merge_thread_choice(DtChoice& range, const DtChoice& thread) {
  if (thread.dt < range.dt || (thread.dt == range.dt && thread.zone < range.zone && thread.zone >= 0)) range = thread;
}

// Merges one range's choice into the step's.
inline void merge_range_choice(DtChoice& step, const DtChoice& range) {
  if (range.dt < step.dt || (range.dt == step.dt && range.zone < step.zone)) step = range;
}

}  // namespace stagger
