#include "io/hdf5_merge.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <unordered_set>
#include <utility>

#include <fcntl.h>
#include <hdf5.h>
#include <unistd.h>

#include "aief/error.hpp"
#include "io/hdf5_file.hpp"
#include "io/hdf5_guarded_write.hpp"
#include "io/hdf5_objects.hpp"
#include "io/json_writer.hpp"
#include "io/merge_option_check.hpp"
#include "io/output_lock.hpp"
#include "io/temporary_files.hpp"

namespace aief::io {

using namespace hdf5;

namespace {

// A hash of what the image group `name` records of its making: its source (size, modification
// time) and its option record.
std::uint64_t making_record_hash(const Hdf5File& file, const std::string& name) {
  const std::optional<std::string> options = file.option_record(name);
  const std::optional<SourceRecord> source = file.recorded_source(name);
  std::string record = options ? "1" + *options : "0";
  if (source)
    record.append("|")
        .append(std::to_string(source->bytes))
        .append("|")
        .append(std::to_string(source->mtime_ns));
  return std::hash<std::string>{}(record);
}

// The bytes the datasets of group `name` hold (what a copy of it writes besides metadata).
std::uint64_t group_storage_bytes(hid_t file, const std::string& name) {
  const Handle group(H5Gopen2(file, name.c_str(), H5P_DEFAULT), H5Gclose);
  if (!group.ok()) throw Error("'" + name + "' is not a group");
  const auto visit = [](hid_t parent, const char* link, const H5L_info_t*, void* data) -> herr_t {
    const Handle set(H5Dopen2(parent, link, H5P_DEFAULT), H5Dclose);
    if (set.ok()) *static_cast<std::uint64_t*>(data) += H5Dget_storage_size(set.get());
    return 0;
  };
  std::uint64_t bytes = 0;
  H5Literate(group.get(), H5_INDEX_NAME, H5_ITER_NATIVE, nullptr, visit, &bytes);
  return bytes;
}
// Copies the file `from` to `to` (created), throwing the system's reason (std::filesystem's
// copy reports a full disk as "Input/output error").
void copy_file(const std::string& from, const std::string& to) {
  const int in = ::open(from.c_str(), O_RDONLY | O_CLOEXEC);
  if (in < 0) throw Error("cannot read '" + from + "': " + std::strerror(errno));
  const int out = ::open(to.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (out < 0) {
    const int code = errno;
    ::close(in);
    throw Error("cannot create '" + to + "': " + std::strerror(code));
  }
  std::vector<char> buffer(1 << 20);
  int code = 0;
  for (ssize_t n; code == 0 && (n = ::read(in, buffer.data(), buffer.size())) != 0;) {
    if (n < 0) {
      if (errno != EINTR) code = errno;
      continue;
    }
    for (ssize_t done = 0; done < n;) {
      const ssize_t w = ::write(out, buffer.data() + done, static_cast<std::size_t>(n - done));
      if (w < 0 && errno == EINTR) continue;
      if (w < 0) {
        code = errno;
        break;
      }
      done += w;
    }
  }
  ::close(in);
  if (::close(out) != 0 && code == 0) code = errno;
  if (code != 0) throw Error(std::strerror(code) + std::string(" (copying '") + from + "')");
}

}  // namespace
void Hdf5File::copy_group_from(const Hdf5File& source, const std::string& image) {
  silence_hdf5();
  const std::string name = image_group(image);
  const std::uint64_t bytes = group_storage_bytes(source.file_, name);
  write_guarded(
      bytes, "'" + name + "' from '" + source.path_ + "'",
      [&] {
        if (may_hold(name)) remove_group(file_, name);  // an incomplete group of the same name
        if (H5Ocopy(source.file_, name.c_str(), file_, name.c_str(), H5P_DEFAULT, with_parents()) <
            0)
          throw Error(hdf5_reason());
        note_group(name);
      },
      Flush::at_close);
}
namespace {

// The names of the features file `file` (the merge's output when `is_output`), refusing what merge
// must not take or extend: a matches file, another tool's features (hloc's SuperPoint: 256 x N
// float32 descriptors, which aief's groups beside them would not match). Incomplete groups (a
// killed write's) are left out with a note.
std::vector<std::string> merged_names(const Hdf5File& file, bool is_output,
                                      std::vector<std::string>* notes) {
  Hdf5File::Listing listing = file.listing();
  const std::string role = is_output ? "the output '" + file.path() + "'" : "'" + file.path() + "'";
  if (listing.holds_pairs)
    throw Error(role +
                " holds matches (pair groups with matches0), not features: merge joins "
                "the feature files of aief extract --batch --format h5; nothing was written");
  if (!listing.names.empty())
    if (const std::string other = file.foreign_descriptors(image_group(listing.names.front()));
        !other.empty())
      throw Error(role + " holds another tool's features (image '" + listing.names.front() +
                  "': " + other +
                  " descriptors; aief writes 32 x N uint8): merge joins aief's feature files; "
                  "nothing was written");
  if (!listing.incomplete.empty() && notes)
    notes->push_back(role + " holds " + std::to_string(listing.incomplete.size()) +
                     " incomplete image group(s) (a write killed halfway; the first: '" +
                     listing.incomplete.front() + "'), " +
                     (is_output ? "left as they are" : "not merged") +
                     ": run that shard's aief extract --batch again to complete them");
  return std::move(listing.names);
}

}  // namespace

int merge_feature_files(const std::string& output, const std::vector<std::string>& inputs,
                        int* replaced, std::vector<std::string>* notes) {
  namespace fs = std::filesystem;
  std::error_code ec;
  // Every input checked first: each opens, no image is in two of them (a hash set: linear), and
  // every image of the result, those the output keeps included, was extracted with the same
  // options.
  SameOptionsCheck same_options;
  // The output's lock for the whole merge, from reading what the output holds to the rename: a
  // second merge into it waits, then adds its shards to this one's output (io/output_lock.hpp).
  const OutputLock lock(output);
  // Images already in the output, from an earlier merge, each with the hash of what it records of
  // its making (source and options): a shard's image whose record differs (its image changed, or
  // the shards were extracted again with other options) replaces it; an equal one is kept.
  std::vector<std::string> previous_names;  // sorted
  // Keyed by those names: the hash of each one's making, and its image file's time (-1: none).
  struct Making {
    std::uint64_t hash;
    long long mtime_ns;
  };
  std::unordered_map<std::string_view, Making> previous_records;
  std::unique_ptr<Hdf5File> previous;
  const bool extending = fs::exists(output, ec);
  if (extending) {
    previous = std::make_unique<Hdf5File>(output, Hdf5File::Mode::read_in_name_order);
    previous_names = merged_names(*previous, true, notes);
    for (const std::string& name : previous_names) {
      const std::optional<SourceRecord> source = previous->recorded_source(name);
      previous_records.emplace(
          name, Making{making_record_hash(*previous, name), source ? source->mtime_ns : -1});
    }
  }
  std::unordered_set<std::string_view> kept, stale;  // of previous_names
  std::vector<std::unique_ptr<Hdf5File>> shards;
  std::vector<std::vector<std::string>> names;  // each shard's, kept for the copy
  names.reserve(inputs.size());
  // Each image's shard, keyed by the names above (not copies of them: 48 bytes less an image).
  std::unordered_map<std::string_view, std::size_t> first_shard;
  for (const std::string& input : inputs) {
    shards.push_back(std::make_unique<Hdf5File>(input, Hdf5File::Mode::read_in_name_order));
    names.push_back(merged_names(*shards.back(), false, notes));
    for (const std::string& name : names.back()) {
      const auto [at, inserted] = first_shard.emplace(name, shards.size() - 1);
      if (!inserted)
        throw Error("image '" + name + "' is in two of the files merged, '" + inputs[at->second] +
                    "' and '" + input + "'; nothing was written");
      const auto found = previous_records.find(name);
      if (found == previous_records.end()) continue;
      if (found->second.hash == making_record_hash(*shards.back(), name)) {
        kept.insert(found->first);
        continue;
      }
      // A group of an older file of that name than the output's: another image of the same name
      // (or an older shard), refused as an image in two of the files merged is: merged over the
      // newer, it would lose it; kept, the output would not hold what the shard does.
      const std::optional<SourceRecord> source = shards.back()->recorded_source(name);
      if (source && found->second.mtime_ns >= 0 && source->mtime_ns < found->second.mtime_ns)
        throw Error("image '" + name + "' of '" + input + "' is of another file than the one '" +
                    output + "' holds (its image file is older: modified at " +
                    std::to_string(source->mtime_ns) + " ns, the output's at " +
                    std::to_string(found->second.mtime_ns) +
                    " ns): two images of one name, or an older shard; merge it into another "
                    "output, or extract that shard again; nothing was written");
      stale.insert(found->first);
    }
  }
  // Options: the output's images it keeps first, then the shards' images it takes.
  for (const std::string& name : previous_names)
    if (!stale.count(name)) same_options.check(previous->option_record(name), output, name);
  previous.reset();
  for (std::size_t s = 0; s < shards.size(); ++s)
    for (const std::string& name : names[s])
      if (!kept.count(name)) same_options.check(shards[s]->option_record(name), inputs[s], name);
  if (const fs::path folder = fs::path(output).parent_path();
      !extending && !folder.empty() && !fs::is_directory(folder, ec))
    throw Error("cannot create '" + output + "': the folder '" + folder.string() +
                "' does not exist");

  // Then written to a temporary beside the output (a copy of it when extending), renamed over it
  // only when complete: a failed merge leaves the output as it was. The temporary is this
  // merge's own: two merges into one output each rename a whole file.
  // Beside the file the output names and renamed onto it: an output that is a link is written
  // through, never replaced by a file while its target keeps the old images.
  const std::string target = resolved_path(output);
  remove_stale_temporaries_of(target);
  const std::string temporary = unique_temporary_path_of(target);
  int copied = 0;
  try {
    if (extending) copy_file(output, temporary);
    Hdf5File out(temporary, Hdf5File::Mode::write_temporary);
    for (std::size_t s = 0; s < shards.size(); ++s)
      for (const std::string& name : names[s]) {
        if (kept.count(name)) continue;
        out.copy_group_from(*shards[s], name);  // replacing a stale group of that name
        ++copied;
      }
    out.close();
  } catch (const fs::filesystem_error& e) {
    fs::remove(temporary, ec);
    throw Error("cannot merge into '" + output + "' (left as it was): " + e.code().message());
  } catch (const std::exception& e) {
    fs::remove(temporary, ec);
    // The temporary's own note on what it keeps is not the output's: the output is left as it
    // was, the temporary removed. The note ends the message.
    std::string why = e.what();
    for (const char* note : {kCompleteBeforeIsKept, kKeepsTheFlushedWrites})
      if (const std::size_t at = why.rfind(note); at != std::string::npos) why.erase(at);
    throw Error("cannot merge into '" + output + "' (left as it was): " + why);
  }
  if (fs::rename(temporary, target, ec); ec) {
    // The rename's own error (a later call would overwrite it: "Success"); a temporary gone
    // missing was removed by another program meanwhile (a cleaner of old files?).
    const std::string why = ec == std::errc::no_such_file_or_directory
                                ? "its temporary '" + temporary +
                                      "' was removed by another program while the merge ran (a "
                                      "cleaner of temporary files?); run the merge again"
                                : ec.message();
    fs::remove(temporary, ec);
    throw Error("cannot merge into '" + output + "' (left as it was): " + why);
  }
  if (replaced) *replaced = static_cast<int>(stale.size());
  return copied;
}

}  // namespace aief::io
