#include "io/merge_option_check.hpp"

#include <algorithm>

#include "aief/error.hpp"
#include "io/option_record.hpp"

namespace aief::io {

void SameOptionsCheck::check(const std::optional<std::string>& record, const std::string& path,
                             const std::string& name) {
  if (!any_checked_) {
    any_checked_ = true;
    first_record_ = record;
    first_file_ = path;
    first_name_ = name;
    return;
  }
  if (record == first_record_ ||
      (record && std::find(agreeing_.begin(), agreeing_.end(), *record) != agreeing_.end()))
    return;
  const std::string here = "'" + path + "' (image '" + name + "')",
                    first = "'" + first_file_ + "' (image '" + first_name_ + "')";
  const std::string refusal =
      "; merge the shards of one run, or extract again with the same "
      "options; nothing was written";
  if (!record)
    throw Error(here + " records no options (an older aief's output) while " + first + " does" +
                refusal);
  if (!first_record_)
    throw Error(here + " records its options while " + first +
                " records none (an older aief's output)" + refusal);
  const std::vector<std::string> changes = option_changes(*first_record_, *record);
  if (changes.empty()) {
    agreeing_.push_back(*record);
    return;
  }
  throw Error("the options differ between " + first + " and " + here + ": " + listed(changes) +
              refusal);
}

}  // namespace aief::io
