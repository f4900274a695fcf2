#pragma once
// Hand-offs between threads that ThreadSanitizer cannot see by itself. TBB synchronises the
// start of a task and the wait for its end inside libtbb, which Debian does not build with TSan,
// so without these marks every access of a parallel body to the caller's data (and the caller's
// stack, reused after the wait) looks like a race; scripts/tsan.supp then needed a suppression
// broad enough to hide real races in our bodies. With the marks, it suppresses only races whose
// innermost frame is TBB's own inline code (scripts/ci_sanitizers proves a race in a body is
// still reported, tests/tsan/race_control.cpp).
//
// handoff_release(tag) on one thread happens before handoff_acquire(tag) on another: mark what
// TBB already guarantees, never more (a mark that orders two bodies would hide their races).
// Outside a TSan build both are empty.
#if defined(__SANITIZE_THREAD__)
#define AIEF_TSAN_HANDOFF 1
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define AIEF_TSAN_HANDOFF 1
#endif
#endif

#if defined(AIEF_TSAN_HANDOFF)
#include <sanitizer/tsan_interface.h>
#endif

namespace aief::parallel {

// Tag of "TBB starts a parallel body after its caller's handoff_release": global, because a
// body must not read its closure (which TBB copies, unseen by TSan) before the acquire.
inline const char kBodyStartTag = 0;

inline void handoff_release([[maybe_unused]] const void* tag) {
#if defined(AIEF_TSAN_HANDOFF)
  __tsan_release(const_cast<void*>(tag));
#endif
}

inline void handoff_acquire([[maybe_unused]] const void* tag) {
#if defined(AIEF_TSAN_HANDOFF)
  __tsan_acquire(const_cast<void*>(tag));
#endif
}

}  // namespace aief::parallel
