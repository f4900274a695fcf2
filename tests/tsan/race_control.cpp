// Negative control for the ThreadSanitizer job (scripts/ci_sanitizers): a deliberate data race
// in a body run by aief's own scheduler (tbb::parallel_for underneath). TSan must report it;
// the job fails when this program exits cleanly, which is what a suppression broad enough to
// hide races in our parallel bodies (e.g. `race:tbb::detail::`, which matches every stack
// below parallel_for) would make it do. Not a test of the suite: a race is undefined behaviour,
// so it is built only on request (EXCLUDE_FROM_ALL) and run only by the TSan job.
//
// The two writes must not happen at the same instant: TSan checks and updates an address's
// shadow without a lock, so two threads writing at once can each miss the other (9 runs in 10
// did, when both pieces wrote the moment they met). Piece 0 writes first and says so through a
// relaxed atomic, which orders nothing for TSan; piece 1 writes after it has seen that.
#include <atomic>
#include <chrono>
#include <cstdio>
#include <thread>

#include <tbb/global_control.h>

#include "parallel/scheduler.hpp"

namespace {

int unsynchronised_total = 0;  // written by two threads with nothing ordering the writes

// Spins until ready() holds or 10 s have passed; says which.
template <class Ready>
bool wait_until(Ready ready) {
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (!ready()) {
    if (std::chrono::steady_clock::now() > give_up) return false;
    std::this_thread::yield();
  }
  return true;
}

struct Meeting {
  std::atomic<int> arrived{0};
  std::atomic<bool> first_written{false};  // relaxed only: no happens-before for TSan
  std::atomic<int> met{0};                 // pieces that saw the other one running
};

// Both pieces wait until both have started, so they run on two threads at once (the waiting
// orders nothing after it: each piece writes only after its own arrival).
__attribute__((noinline)) void racy_body(int piece, Meeting& meeting) {
  meeting.arrived.fetch_add(1);
  if (wait_until([&] { return meeting.arrived.load() >= 2; })) meeting.met.fetch_add(1);
  if (piece == 1) wait_until([&] { return meeting.first_written.load(std::memory_order_relaxed); });
  unsynchronised_total += piece + 1;  // the race
  if (piece == 0) meeting.first_written.store(true, std::memory_order_relaxed);
}

}  // namespace

int main() {
  const tbb::global_control parallelism(tbb::global_control::max_allowed_parallelism, 2);
  const aief::parallel::Scheduler scheduler(2);
  Meeting meeting;
  scheduler.for_each(2, [&](int piece) { racy_body(piece, meeting); });
  std::printf("race control ran: total %d, %s\n", unsynchronised_total,
              meeting.met.load() == 2 ? "the two pieces ran at once"
                                      : "the pieces never ran at once (no race happened)");
  return 0;
}
