// Hdf5File's pair groups (the matches.h5 layout, io/hdf5_file.hpp).
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "aief/error.hpp"
#include "io/hdf5_file.hpp"
#include "io/hdf5_guarded_write.hpp"
#include "io/hdf5_objects.hpp"
#include "io/pairs_file.hpp"

namespace aief::io {

using namespace hdf5;

namespace {

// Throws when the pair group `group` (named `group_name`) records names other than the pair's.
void check_recorded_names(hid_t group, const std::string& group_name, const std::string& name0,
                          const std::string& name1, const std::string& path) {
  const std::string stored0 = string_attribute(group, "name0"),
                    stored1 = string_attribute(group, "name1");
  if (stored0.empty() && stored1.empty()) return;  // written before names were recorded
  if (stored0 != name0 || stored1 != name1)
    throw Error("pair '" + name0 + " " + name1 + "' and pair '" + stored0 + " " + stored1 +
                "' share the group '" + group_name + "' in '" + path +
                "' (hloc's names: '/' becomes '-'), which holds the second's matches");
}

// The matches a pair group holds (query = index in image 0); distance from matching_scores0.
std::vector<Match> read_pair_group(hid_t group, const std::string& group_name,
                                   const std::string& path, std::size_t* queries = nullptr) {
  silence_hdf5();
  {
    // hloc's matches0 are signed (-1: unmatched); an unsigned one would read 255 as an index.
    const Handle set(H5Dopen2(group, "matches0", H5P_DEFAULT), H5Dclose);
    const Handle type(set.ok() ? H5Dget_type(set.get()) : -1, H5Tclose);
    if (type.ok() &&
        (H5Tget_class(type.get()) != H5T_INTEGER || H5Tget_sign(type.get()) != H5T_SGN_2))
      throw Error("'" + group_name + "/matches0' in '" + path + "' is " +
                  (H5Tget_class(type.get()) == H5T_INTEGER
                       ? "unsigned uint" + std::to_string(8 * H5Tget_size(type.get()))
                       : std::string("not an integer")) +
                  ": hloc's matches0 are signed integers, -1 for an unmatched keypoint (written "
                  "by another tool?)");
  }
  std::vector<hsize_t> dims;
  const std::vector<std::int32_t> matches0 =
      read_dataset<std::int32_t>(group, "matches0", dims, group_name);
  std::vector<float> scores0(matches0.size(), 1.0f);
  if (H5Lexists(group, "matching_scores0", H5P_DEFAULT) > 0)
    scores0 = read_dataset<float>(group, "matching_scores0", dims, group_name);
  if (scores0.size() != matches0.size())
    throw Error("'" + group_name + "' in '" + path +
                "': matches0 and matching_scores0 differ in length");
  if (queries) *queries = matches0.size();
  std::vector<Match> matches;
  for (std::size_t i = 0; i < matches0.size(); ++i)
    if (matches0[i] >= 0)
      matches.push_back({static_cast<int>(i), matches0[i],
                         static_cast<int>(std::lround((1.0f - scores0[i]) * 256.0f))});
  return matches;
}

// The pair group `group_name` when it is complete (its last dataset written), else none.
Handle open_complete_pair_group(hid_t file, const std::string& group_name) {
  Handle group = open_group_if_any(file, group_name);
  if (group.ok() && H5Lexists(group.get(), "matching_scores0", H5P_DEFAULT) <= 0)
    return Handle(-1, H5Gclose);
  return group;
}

}  // namespace

void Hdf5File::check_pair_owner(const std::string& group_name, const std::string& name0,
                                const std::string& name1) const {
  const Handle group = open_group_if_any(file_, group_name);
  if (group.ok()) check_recorded_names(group.get(), group_name, name0, name1, path_);
}

bool Hdf5File::has_matches(const std::string& name0, const std::string& name1) const {
  const std::string group_name = hloc_pair_name(name0, name1);
  if (!may_hold(group_name)) return false;
  const Handle group = open_complete_pair_group(file_, group_name);
  if (!group.ok()) return false;
  check_recorded_names(group.get(), group_name, name0, name1, path_);
  return true;
}

std::vector<Match> Hdf5File::read_matches(const std::string& name0,
                                          const std::string& name1) const {
  const std::string group_name = hloc_pair_name(name0, name1);
  const Handle group = open_group_if_any(file_, group_name);
  if (!group.ok()) throw Error("no pair '" + name0 + " " + name1 + "' in '" + path_ + "'");
  check_recorded_names(group.get(), group_name, name0, name1, path_);
  return read_pair_group(group.get(), group_name, path_);
}

std::optional<std::vector<Match>> Hdf5File::find_matches(const std::string& name0,
                                                         const std::string& name1,
                                                         std::size_t* queries) const {
  const std::string group_name = hloc_pair_name(name0, name1);
  if (!may_hold(group_name)) return std::nullopt;
  const Handle group = open_complete_pair_group(file_, group_name);
  if (!group.ok()) return std::nullopt;
  check_recorded_names(group.get(), group_name, name0, name1, path_);
  return read_pair_group(group.get(), group_name, path_, queries);
}

std::optional<PairRecord> Hdf5File::pair_record(const std::string& name0,
                                                const std::string& name1) const {
  const std::string group_name = hloc_pair_name(name0, name1);
  if (!may_hold(group_name)) return std::nullopt;
  const Handle group = open_complete_pair_group(file_, group_name);
  if (!group.ok()) return std::nullopt;
  PairRecord record;
  for_each_field(record, [&](std::string_view key, std::string& value) {
    value = string_attribute(group.get(), std::string(key).c_str());
  });
  if (record.matcher.empty()) return std::nullopt;
  return record;
}

void Hdf5File::write_matches(const std::string& name0, const std::string& name1, int keypoints0,
                             const std::vector<Match>& matches, const PairRecord* record) {
  silence_hdf5();
  const std::string pair_name = hloc_pair_name(name0, name1);
  if (may_hold(pair_name) && exists(file_, pair_name)) {
    check_pair_owner(pair_name, name0, name1);
    write_guarded(
        0, "the removal of '" + pair_name + "'", [&] { remove_group(file_, pair_name); },
        Flush::now);
  }
  std::vector<std::int32_t> matches0(static_cast<std::size_t>(keypoints0), -1);
  std::vector<float> scores0(static_cast<std::size_t>(keypoints0), 0.0f);
  for (const Match& m : matches) {
    matches0[static_cast<std::size_t>(m.query)] = m.train;
    scores0[static_cast<std::size_t>(m.query)] = 1.0f - static_cast<float>(m.distance) / 256.0f;
  }
  const hsize_t n = matches0.size();
  std::uint64_t record_bytes = 0;
  if (record)
    for_each_field(
        *record, [&](std::string_view, const std::string& value) { record_bytes += value.size(); });
  write_guarded(n * (sizeof(std::int32_t) + sizeof(float)) + record_bytes,
                "pair '" + pair_name + "'", [&] {
                  const Handle group = create_group(file_, pair_name, path_);
                  note_group(pair_name);
                  write_string_attribute(group.get(), "name0", name0, StringLength::fixed);
                  write_string_attribute(group.get(), "name1", name1, StringLength::fixed);
                  if (record)
                    for_each_field(*record, [&](std::string_view key, const std::string& value) {
                      write_string_attribute(group.get(), std::string(key).c_str(), value);
                    });
                  write_dataset(group.get(), "matches0", {n}, matches0, pair_name);
                  write_dataset(group.get(), "matching_scores0", {n}, scores0,
                                pair_name);  // last: marks the pair complete
                });
}
}  // namespace aief::io
