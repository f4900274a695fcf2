#include "parallel/scheduler.hpp"

#include <algorithm>
#include <atomic>

#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <tbb/task_group.h>

#include "parallel/tsan_handoff.hpp"

namespace aief::parallel {

std::string cap_threads(int& threads, const std::string& named) {
  const int available = tbb::info::default_concurrency();
  if (threads <= available) return "";
  const std::string note =
      named + " " + std::to_string(threads) + " is more than the " + std::to_string(available) +
      " hardware threads this process may use; using " + std::to_string(available);
  threads = available;
  return note;
}

struct Scheduler::Arena {
  tbb::task_arena arena;
};

Scheduler::Scheduler(int threads) {
  if (threads > 0) arena_ = std::make_unique<Arena>(Arena{tbb::task_arena(threads)});
}

Scheduler::~Scheduler() = default;
Scheduler::Scheduler(Scheduler&&) noexcept = default;
Scheduler& Scheduler::operator=(Scheduler&&) noexcept = default;

int Scheduler::concurrency() const {
  return arena_ ? arena_->arena.max_concurrency() : tbb::this_task_arena::max_concurrency();
}

void Scheduler::for_each(int count, IndexWork work) const {
  if (count <= 0) return;
  const int workers = std::min(count, concurrency());
  if (workers <= 1) {
    for (int i = 0; i < count; ++i) work(i);
    return;
  }
  // A shared counter instead of TBB's range splitting: pieces of very different sizes (levels
  // shrink by 1.44x each) balance best when every free thread takes the next largest.
  const auto run = [&] {
    std::atomic<int> next{0};
    // TBB starts every body after this point and returns only after every body has ended
    // (parallel/tsan_handoff.hpp); the bodies themselves are not ordered with each other.
    const char ended = 0;
    handoff_release(&kBodyStartTag);
    tbb::parallel_for(
        0, workers,
        [&](int) {
          handoff_acquire(&kBodyStartTag);
          for (int i = next.fetch_add(1); i < count; i = next.fetch_add(1)) work(i);
          handoff_release(&ended);
        },
        tbb::simple_partitioner{});
    handoff_acquire(&ended);
  };
  if (arena_)
    arena_->arena.execute(run);
  else
    run();
}

void Scheduler::for_each_in_chain(int count, IndexWork make, IndexWork work) const {
  if (count <= 0) return;
  if (std::min(count, concurrency()) <= 1) {
    for (int i = 0; i < count; ++i) {
      make(i);
      work(i);
    }
    return;
  }
  const auto run = [&] {
    tbb::task_group group;
    // Step i makes piece i, offers step i + 1 to a free thread, then works on piece i: the
    // chain moves on while the large early pieces are worked on.
    struct Step {
      tbb::task_group& group;
      IndexWork make, work;
      int count;
      const char ended = 0;  // TSan tag: every step's end happens before the wait returns
      void operator()(int i) const {
        make(i);
        if (i + 1 < count) {
          handoff_release(this);  // TBB starts step i + 1 after this spawn (tsan_handoff.hpp)
          group.run([this, i] {
            handoff_acquire(this);
            (*this)(i + 1);
          });
        }
        work(i);
        handoff_release(&ended);
      }
    };
    const Step step{group, make, work, count};
    step(0);
    group.wait();
    handoff_acquire(&step.ended);
  };
  if (arena_)
    arena_->arena.execute(run);
  else
    run();
}

}  // namespace aief::parallel
