// The bandwidth and compute probes of `stagger bench scaling` (bench_probe.hpp,
// docs/parallel.md "Speed"). Each worker is a forked process (the bench's own process never
// starts OpenMP threads, which do not survive a fork); the processes of one probe allocate
// and touch their arrays, then wait on a pipe until all are ready, so that they stream at the
// same time, as two ranks do.
#include "bench_probe.hpp"

#include <omp.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <vector>

namespace stagger::cli::bench {

namespace {

using Clock = std::chrono::steady_clock;

struct WorkerReport {
  double seconds = 0;
  int ok = 0;
};

constexpr double kScale = 3.0;
constexpr int kChains = 32;  // independent chains of the compute probe: enough to fill the pipelines

// Waits for the go byte (a fork's siblings are ready), or returns at once without a pipe.
void wait_for_start(int go_fd) {
  if (go_fd < 0) return;
  char byte = 0;
  while (read(go_fd, &byte, 1) < 0) {
  }
}

// a = b + s c over n elements per array with `threads` OpenMP threads, each touching its own
// share first (so its pages are its own, as a rank's are).
WorkerReport triad(long n, int threads, int passes, int ready_fd, int go_fd) {
  WorkerReport report;
  const std::unique_ptr<double[]> a(new double[n]), b(new double[n]), c(new double[n]);
  double *pa = a.get(), *pb = b.get(), *pc = c.get();
#pragma omp parallel for schedule(static) num_threads(threads) if (threads > 1)
  for (long i = 0; i < n; ++i) {
    pa[i] = 0;
    pb[i] = static_cast<double>(i % 1000);
    pc[i] = static_cast<double>(i % 7);
  }
  // Ready, and this worker's end of the pipe closed: once every worker has written or died,
  // the parent's read sees the end of the pipe instead of waiting for a worker that is gone.
  if (ready_fd >= 0) (void)!write(ready_fd, "r", 1), close(ready_fd);
  wait_for_start(go_fd);
  auto pass = [&] {
#pragma omp parallel for schedule(static) num_threads(threads) if (threads > 1)
    for (long i = 0; i < n; ++i) pa[i] = pb[i] + kScale * pc[i];
  };
  pass();  // untimed: the first pass after the touch
  const auto start = Clock::now();
  for (int k = 0; k < passes; ++k) pass();
  report.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  // The stores happened and are right (every 4097th element).
  report.ok = 1;
  for (long i = 0; i < n; i += 4097)
    if (pa[i] != static_cast<double>(i % 1000) + kScale * static_cast<double>(i % 7)) report.ok = 0;
  return report;
}

// `iterations` updates of kChains independent chains x = x m + d in registers, per thread.
WorkerReport compute(long iterations, int threads, int ready_fd, int go_fd) {
  WorkerReport report;
  // Ready, and this worker's end of the pipe closed: once every worker has written or died,
  // the parent's read sees the end of the pipe instead of waiting for a worker that is gone.
  if (ready_fd >= 0) (void)!write(ready_fd, "r", 1), close(ready_fd);
  wait_for_start(go_fd);
  const auto start = Clock::now();
  int ok = 1;
#pragma omp parallel num_threads(threads) if (threads > 1) reduction(min : ok)
  {
    double x[kChains];
    for (int j = 0; j < kChains; ++j) x[j] = j;
    const long mine = iterations / omp_get_num_threads();
    for (long i = 0; i < mine; ++i)
      for (int j = 0; j < kChains; ++j) x[j] = x[j] * 0.999999 + 1e-3;
    // The chains converge to 1000 from below: finite and in (0, 1000] when they ran.
    for (int j = 0; j < kChains; ++j) ok = std::min(ok, std::isfinite(x[j]) && x[j] > 0 && x[j] <= 1000 ? 1 : 0);
  }
  report.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  report.ok = ok;
  return report;
}

WorkerReport work(ProbeKind kind, long share, int threads, int passes, int ready_fd, int go_fd) {
  return kind == ProbeKind::triad ? triad(share, threads, passes, ready_fd, go_fd)
                                  : compute(share, threads, ready_fd, go_fd);
}

}  // namespace

ProbeResult run_probe(ProbeKind kind, int workers, bool threads, long elements, int passes) {
  ProbeResult result;
  const int processes = threads ? 1 : workers;
  const int per_process_threads = threads ? workers : 1;
  const long share = elements / processes;
  int ready[2], go[2], reports[2];
  int* pipes[3] = {ready, go, reports};
  for (int i = 0; i < 3; ++i)
    if (pipe(pipes[i]) != 0) {
      for (int j = 0; j < i; ++j) close(pipes[j][0]), close(pipes[j][1]);
      result.message = "pipe failed";
      return result;
    }
  std::vector<pid_t> children;
  for (int w = 0; w < processes; ++w) {
    const pid_t child = fork();
    if (child == 0) {
      // A worker never returns into the bench (an exception, e.g. an allocation that fails,
      // would otherwise run the rest of the suite a second time in the child).
      try {
        close(ready[0]), close(go[1]), close(reports[0]);
        const WorkerReport report = work(kind, share, per_process_threads, passes, ready[1], go[0]);
        (void)!write(reports[1], &report, sizeof report);
      } catch (...) {
        _exit(1);
      }
      _exit(0);
    }
    if (child > 0) children.push_back(child);
  }
  close(ready[1]), close(go[0]), close(reports[1]);
  // Start them together once all have touched their memory.
  int started = 0;
  char byte;
  while (started < static_cast<int>(children.size()) && read(ready[0], &byte, 1) == 1) ++started;
  for (int w = 0; w < started; ++w) (void)!write(go[1], "g", 1);
  close(go[1]);
  int reported = 0;
  bool all_ok = static_cast<int>(children.size()) == processes;
  WorkerReport report;
  while (read(reports[0], &report, sizeof report) == static_cast<ssize_t>(sizeof report)) {
    ++reported;
    result.seconds = std::max(result.seconds, report.seconds);
    all_ok = all_ok && report.ok == 1;
  }
  close(ready[0]), close(reports[0]);
  for (pid_t child : children) {
    int status = 0;
    if (waitpid(child, &status, 0) != child || !WIFEXITED(status) || WEXITSTATUS(status) != 0) all_ok = false;
  }
  result.ok = all_ok && reported == processes && result.seconds > 0;
  if (!result.ok) result.message = "a probe worker failed or gave a wrong result";
  // STREAM's count for the triad: two arrays read and one written per element and pass
  // (the write's read for ownership, 8 more bytes, is not counted); compute: a multiply and an add.
  result.work = kind == ProbeKind::triad ? 24.0 * static_cast<double>(share) * processes * passes
                                         : 2.0 * kChains * static_cast<double>(share / per_process_threads) *
                                               per_process_threads * processes;
  return result;
}

}  // namespace stagger::cli::bench
