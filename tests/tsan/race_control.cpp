// Negative control for the ThreadSanitizer job (scripts/ci_sanitizers): a deliberate data race
// in a body run by aief's own scheduler (tbb::parallel_for underneath). TSan must report it;
// the job fails when this program exits cleanly, which is what a suppression broad enough to
// hide races in our parallel bodies (e.g. `race:tbb::detail::`, which matches every stack
// below parallel_for) would make it do. Not a test of the suite: a race is undefined behaviour,
// so it is built only on request (EXCLUDE_FROM_ALL) and run only by the TSan job.
#include <atomic>
#include <chrono>
#include <cstdio>
#include <thread>

#include <tbb/global_control.h>

#include "parallel/scheduler.hpp"

namespace {

int unsynchronised_total = 0;  // written by two threads with nothing ordering the writes

// Both pieces wait until both have started, so they run on two threads at once (the waiting
// orders nothing after it: each piece writes only after its own arrival). Gives up after 10 s,
// in which case no race happens and the job reports the control as failed.
void wait_for_each_other(std::atomic<int>& arrived) {
  arrived.fetch_add(1);
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (arrived.load() < 2 && std::chrono::steady_clock::now() < give_up)
    std::this_thread::yield();
}

__attribute__((noinline)) void racy_body(int piece, std::atomic<int>& arrived) {
  wait_for_each_other(arrived);
  unsynchronised_total += piece + 1;  // the race
}

}  // namespace

int main() {
  const tbb::global_control parallelism(tbb::global_control::max_allowed_parallelism, 2);
  const aief::parallel::Scheduler scheduler(2);
  std::atomic<int> arrived{0};
  scheduler.for_each(2, [&](int piece) { racy_body(piece, arrived); });
  std::printf("race control ran: total %d, %s\n", unsynchronised_total,
              arrived.load() >= 2 ? "both pieces met" : "the pieces never ran at once");
  return 0;
}
