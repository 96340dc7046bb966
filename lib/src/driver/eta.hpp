#pragma once
// The progress line's time to go (docs/output.md, "Progress"): from the recent trend of the
// time step, not from the average rate so far. A run whose dt shrinks (a Taylor anvil's foot
// crushing its first row) needs more cycles per unit time as it goes, and the average rate so
// far is then always optimistic. From the last kSamples progress samples (t, dt, cycle, wall
// seconds): the wall time per cycle, and a fit of ln dt against t, dt(t') = dt exp(k (t' - t)),
// which gives the cycles to go, the integral of 1 / dt(t') from t to t_end,
//     (1 - exp(-k T)) / (k dt),  T = t_end - t,
// with k T held within [-5, 5] (at most e^5 = 148 times the cycles of a constant dt). With fewer
// than three samples, or no wall time yet, the average rate so far.
#include <algorithm>
#include <array>
#include <cmath>

namespace stagger {

class EtaEstimate {
 public:
  static constexpr int kSamples = 64;

  // A progress sample: the simulated time, the last dt, the cycle and the wall seconds.
  void add(double t, double dt, long cycle, double wall) {
    if (!(dt > 0) || !std::isfinite(t) || !std::isfinite(wall)) return;
    samples_[next_] = {t, dt, cycle, wall};
    next_ = (next_ + 1) % kSamples;
    count_ = std::min(count_ + 1, kSamples);
  }

  // Wall seconds to reach t_end; negative when nothing can be said yet.
  double seconds_to(double t_end) const {
    if (count_ == 0) return -1;
    const Sample& last = at(count_ - 1);
    if (!(t_end > last.t)) return 0;
    const Sample& first = at(0);
    if (count_ < 3 || !(last.wall > first.wall) || last.cycle <= first.cycle) {
      // The average rate over the samples.
      return last.t > first.t && last.wall > first.wall
                 ? (last.wall - first.wall) * (t_end - last.t) / (last.t - first.t)
                 : -1;
    }
    const double wall_per_cycle = (last.wall - first.wall) / static_cast<double>(last.cycle - first.cycle);
    // Least squares of ln dt against t (centred, so that the sums do not cancel).
    double mt = 0, ml = 0;
    for (int i = 0; i < count_; ++i) mt += at(i).t, ml += std::log(at(i).dt);
    mt /= count_, ml /= count_;
    double stt = 0, stl = 0;
    for (int i = 0; i < count_; ++i) {
      const double dt_ = at(i).t - mt;
      stt += dt_ * dt_, stl += dt_ * (std::log(at(i).dt) - ml);
    }
    const double k = stt > 0 ? stl / stt : 0.0;
    const double span = t_end - last.t;
    const double kt = std::clamp(k * span, -5.0, 5.0);
    const double cycles = std::abs(kt) < 1e-8 ? span / last.dt : span * (1 - std::exp(-kt)) / (kt * last.dt);
    return cycles * wall_per_cycle;
  }

 private:
  struct Sample {
    double t = 0, dt = 0;
    long cycle = 0;
    double wall = 0;
  };
  // The i-th oldest sample held.
  const Sample& at(int i) const { return samples_[(next_ - count_ + i + kSamples) % kSamples]; }

  std::array<Sample, kSamples> samples_{};
  int next_ = 0, count_ = 0;
};

}  // namespace stagger
