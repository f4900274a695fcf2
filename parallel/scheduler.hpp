#pragma once
// TBB scheduling of the pipeline's independent pieces (pyramid levels, thresholds of a sweep,
// rows of a match). Work is handed out largest first from a shared counter, each piece writes
// only its own slot, so the result never depends on which thread ran what (docs/design.md §12).
#include <memory>
#include <string>
#include <type_traits>

namespace aief::parallel {

// A non-owning reference to a callable taking the piece index (std::function may allocate; the
// pipeline allocates nothing per frame).
class IndexWork {
 public:
  template <class F, class = std::enable_if_t<!std::is_same_v<std::decay_t<F>, IndexWork>>>
  IndexWork(F& work)  // NOLINT: implicit on purpose, callers pass lambdas
      : object_(&work), call_([](void* object, int i) { (*static_cast<F*>(object))(i); }) {}
  void operator()(int i) const { call_(object_, i); }

 private:
  void* object_;
  void (*call_)(void*, int);
};

// More threads than this process may use (tbb::info::default_concurrency()) gain nothing (the
// output never depends on the count) and make TBB print its own warning to stderr: lowers
// `threads` to what there is and returns the note every front end gives, naming the option as it
// does (`named`: "--threads" -> "--threads 3 is more than the 2 hardware threads this process may
// use; using 2"); "" when `threads` is within.
std::string cap_threads(int& threads, const std::string& named);

class Scheduler {
 public:
  // threads == 0: run in the caller's task arena (TBB's default one, or the arena the caller
  // entered with tbb::task_arena::execute). threads >= 1: a private arena of that many threads.
  explicit Scheduler(int threads = 0);
  ~Scheduler();
  Scheduler(Scheduler&&) noexcept;
  Scheduler& operator=(Scheduler&&) noexcept;

  // Calls work(i) once for every i in [0, count). Pieces are taken in index order, so callers
  // put the largest first (level 0 before level 1). Exceptions propagate to the caller.
  void for_each(int count, IndexWork work) const;
  template <class F>
  void for_each(int count, F&& work) const {
    for_each(count, IndexWork(work));
  }

  // A chain of pieces, each made from the one before (pyramid level n from level n - 1), in
  // one parallel region: make(0), make(1), ... run in order, and work(i) runs once make(i) has
  // returned, beside the making of the later pieces and the work on the earlier ones. No
  // barrier between the stages; returns when every call has. Exceptions propagate.
  void for_each_in_chain(int count, IndexWork make, IndexWork work) const;
  template <class M, class W>
  void for_each_in_chain(int count, M&& make, W&& work) const {
    for_each_in_chain(count, IndexWork(make), IndexWork(work));
  }

  // Threads that may run pieces at once.
  int concurrency() const;

 private:
  struct Arena;  // a tbb::task_arena, kept out of this header
  std::unique_ptr<Arena> arena_;
};

}  // namespace aief::parallel
