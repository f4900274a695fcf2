#include "python/extraction_rendezvous.hpp"

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>

#include "aief/error.hpp"

namespace aief::python {

namespace {

struct Rendezvous {
  std::mutex mutex;
  std::condition_variable all_arrived;
  int parties = 0;
  int arrived = 0;
  double timeout_s = 0;
};

Rendezvous& rendezvous() {
  static Rendezvous instance;
  return instance;
}

}  // namespace

void arm_extraction_rendezvous(int parties, double timeout_s) {
  if (parties < 0) throw Error("parties must be >= 0, got " + std::to_string(parties));
  Rendezvous& r = rendezvous();
  const std::lock_guard lock(r.mutex);
  r.parties = parties;
  r.arrived = 0;
  r.timeout_s = timeout_s;
}

void extraction_rendezvous() {
  Rendezvous& r = rendezvous();
  std::unique_lock lock(r.mutex);
  if (r.parties == 0) return;
  const int parties = r.parties;
  if (++r.arrived >= parties) {
    r.all_arrived.notify_all();
    return;
  }
  const auto timeout = std::chrono::duration<double>(r.timeout_s);
  if (!r.all_arrived.wait_for(lock, timeout, [&] { return r.arrived >= parties; }))
    throw Error("extraction rendezvous: " + std::to_string(r.arrived) + " of " +
                std::to_string(parties) + " extractions inside the GIL-free section within " +
                std::to_string(r.timeout_s) + " s");
}

}  // namespace aief::python
