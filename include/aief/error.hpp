#pragma once
// The one exception type of the public API. Every message names the bad value, e.g.
// "scale_factor must be > 1, got 0.8" or "image 7x5 is smaller than the 19-pixel border".
#include <stdexcept>
#include <string>

namespace aief {

class Error : public std::invalid_argument {
 public:
  explicit Error(const std::string& message) : std::invalid_argument(message) {}
};

}  // namespace aief
