#pragma once
// A progress line on stderr: a bar with rate and ETA redrawn in place on a terminal, plain
// "done/total" lines every few percent when stderr is a file or pipe (CI logs stay readable).
#include <chrono>
#include <string>

namespace aief::cli {

class Progress {
 public:
  Progress(std::string label, int total);
  // One more item done; `what` names it (e.g. "graf 1-3").
  void step(const std::string& what);
  // Ends the line on a terminal.
  void finish();

 private:
  std::string label_;
  int total_, done_ = 0, last_percent_printed_ = -100;
  bool terminal_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace aief::cli
