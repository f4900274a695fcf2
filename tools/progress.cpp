#include "tools/progress.hpp"

#include <cstdio>

#include <unistd.h>

namespace aief::cli {

Progress::Progress(std::string label, int total)
    : label_(std::move(label)),
      total_(total),
      terminal_(isatty(fileno(stderr)) != 0),
      start_(std::chrono::steady_clock::now()) {}

void Progress::step(const std::string& what) {
  ++done_;
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double rate = seconds > 0 ? done_ / seconds : 0.0;
  const double eta = rate > 0 ? (total_ - done_) / rate : 0.0;
  const int percent = total_ > 0 ? 100 * done_ / total_ : 100;
  if (terminal_) {
    constexpr int kBar = 30;
    const int filled = total_ > 0 ? kBar * done_ / total_ : kBar;
    std::fprintf(stderr, "\r%s [%.*s%*s] %d/%d %3d%%  %.2f/s  ETA %3.0fs  %-24.24s", label_.c_str(),
                 filled, "##############################", kBar - filled, "", done_, total_,
                 percent, rate, eta, what.c_str());
    std::fflush(stderr);
  } else if (percent - last_percent_printed_ >= 10 || done_ == total_) {
    std::fprintf(stderr, "%s: %d/%d (%d%%), %.2f/s, ETA %.0f s, last %s\n", label_.c_str(), done_,
                 total_, percent, rate, eta, what.c_str());
    last_percent_printed_ = percent;
  }
}

void Progress::finish() {
  if (terminal_) std::fprintf(stderr, "\n");
}

}  // namespace aief::cli
