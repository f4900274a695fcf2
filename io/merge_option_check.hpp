#pragma once
// Merge's rule on options (io/hdf5_merge.hpp, merge_feature_files): every image group merged
// was extracted with the same options, as far as they change the output (io/option_record.hpp).
// Shards of one run agree; a shard extracted with other options, or by an aief that recorded none
// beside one that did, would mix features that cannot be compared.
#include <optional>
#include <string>
#include <vector>

namespace aief::io {

class SameOptionsCheck {
 public:
  // Throws aief::Error naming both files, both images and the fields that differ when the image
  // `name` of the file `path`, recording `record` (its option record, nullopt when it has none),
  // records other options than the first image checked.
  void check(const std::optional<std::string>& record, const std::string& path,
             const std::string& name);

 private:
  bool any_checked_ = false;
  std::optional<std::string> first_record_;
  std::string first_file_, first_name_;
  // Records that differ from the first only in fields that leave the output alone (threads).
  std::vector<std::string> agreeing_;
};

}  // namespace aief::io
