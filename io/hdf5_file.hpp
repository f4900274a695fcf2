#pragma once
// Feature and match files in hloc's HDF5 layout (libhdf5's C API; built when libhdf5 is found,
// AIEF_HAVE_HDF5). hloc (github.com/cvg/Hierarchical-Localization) reads them as its own:
//
//   features.h5: one group per image, named by its path relative to the image folder (slashes
//   make nested groups, as h5py's create_group does; a name that begins with '/' gets a first
//   group "%2F", as the JSON layout's folder does, and a leading '%' becomes "%25": libhdf5 would
//   read "/data/x.png" as "data/x.png", another image), holding
//     keypoints    N x 2 float32, (x, y) with the centre of the top-left pixel at (0, 0): the
//                  OpenCV convention hloc uses in its files (hloc adds 0.5 when it writes COLMAP's
//                  database, whose origin is the top-left pixel's corner; io/colmap_database does
//                  too)
//     descriptors  32 x N uint8 (hloc stores descriptors dimension-first)
//     scores       N float32, the FAST response
//     image_size   2 int64, (width, height)
//   and, for aief's own readers, size, angle (degrees) and octave, N each, and source: 2 int64,
//   the image file's size in bytes and its modification time in nanoseconds (a batch resume
//   re-extracts an image whose file changed); the group's string attribute options is the option
//   record (io/option_record.hpp: the options it was extracted with, as JSON text).
//   matches.h5: one group per pair, hloc's names_to_pair (io/pairs_file.hpp: name0 and name1 with
//   '/' replaced by '-', joined by '/'), holding matches0 (N0 int32, the index in image 1 or -1)
//   and matching_scores0 (N0 float32, 1 - distance / 256, 0 when unmatched); hloc writes int16 /
//   float16, its readers take any width, and int32 holds more than 32767 keypoints. The group's
//   string attributes name0 and name1 (fixed length, UTF-8; variable-length ones are read too)
//   record the pair's own names, since two pairs can share a group name ("a/b.png c.png" and
//   "a-b.png c.png"): a pair never reads or keeps another's. The string attributes matcher,
//   options0, options1, source0 and source1 record the matcher options and the features matched
//   (io/match_record.hpp), so a resumed run redoes a pair whose matcher or features changed.
//
// One class, defined by job: io/hdf5_file.cpp opens and closes the file and keeps its space
// policy (reservation, fence, batched flushes); io/hdf5_features.cpp the image groups;
// io/hdf5_matches.cpp the pair groups; io/hdf5_merge.cpp the copy of groups between files
// (merge, io/hdf5_merge.hpp). libhdf5's objects they share are io/hdf5_objects.hpp.
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <unordered_set>
#include <utility>
#include <vector>

#include "aief/features.hpp"
#include "aief/match.hpp"
#include "aief/options.hpp"
#include "io/match_record.hpp"
#include "io/output_lock.hpp"
#include "io/pairs_file.hpp"
#include "io/source_record.hpp"

namespace aief::io {

// An HDF5 file opened for reading and writing (created when missing). Writes are flushed in
// batches (kWritesPerFlush groups, and at close), and a group counts as complete only once its
// last dataset exists, so a killed run keeps every group up to its last flush and resumes from
// there. Written files never reuse space freed during a run (no free-space manager), so nothing a
// flushed state still refers to is overwritten before the next flush. Throws aief::Error naming
// the file.
//
// A failed write (a full disk, an I/O error) never damages what was complete before: the disk
// space a write needs is reserved (fallocate) before libhdf5 touches the file, and everything
// below libhdf5's end of allocation is reserved before a flush, so a full disk fails the
// reservation with nothing written, and the writes before it are flushed. Should a write fail
// anyway, the file's descriptor is diverted to a scratch file in memory: nothing more reaches the
// file, which stays as of its last flush, libhdf5 closes it cleanly, and every later write is
// refused with the first reason.
// File systems without fallocate (NFSv3, FUSE, older ZFS), and copy-on-write ones such as btrfs,
// get the diversion only; since a file is flushed when created and after its first write, a full
// disk in its first images there too leaves it readable as of its first image.
//
// A file is readable from its creation on: it is flushed when created and after its first write,
// so a run killed (kill -9, Ctrl-C, SIGTERM, SIGHUP) before its first batch of writes leaves a
// file that opens and resumes.
// The group of the image named `image` ("/data/x.png" -> "%2F/data/x.png", "%x" -> "%25x", any
// other name itself), and back.
std::string image_group(const std::string& image);
std::string image_of_group(const std::string& group);

// The note a failed write's message ends with (Hdf5File::write_guarded): the file keeps what was
// complete before it. A merge, whose file is a temporary it removes, leaves it out.
inline constexpr const char* kCompleteBeforeIsKept = " (what was complete before is kept)";
// Its form when writes since the last flush are lost with the failed one: this text, the count
// flushed, then the count lost (io/hdf5_guarded_write.hpp).
inline constexpr const char* kKeepsTheFlushedWrites = " (the file keeps the ";

class Hdf5File {
 public:
  // read_in_name_order: for a reader that goes through the file once, image after image in name
  // order (merge's passes), which needs only a small metadata cache (io/hdf5_file.cpp,
  // read_access); read: for any order of reads. read_write holds the file's OutputLock
  // (io/output_lock.hpp) while open: a second writer waits; write_temporary is read_write on a
  // temporary its caller holds the output's lock for (merge).
  enum class Mode { read, read_in_name_order, read_write, write_temporary };
  Hdf5File(const std::string& path, Mode mode);
  ~Hdf5File();
  Hdf5File(const Hdf5File&) = delete;
  Hdf5File& operator=(const Hdf5File&) = delete;

  const std::string& path() const { return path_; }
  long long id() const { return file_; }
  // Whether `name` is a complete image group (features) or pair group (matches).
  bool has_features(const std::string& name) const;
  // Whether the pair has a complete group. Throws aief::Error naming both pairs when its group
  // holds another pair's matches (recorded names differ; a group without names is taken as its).
  bool has_matches(const std::string& name0, const std::string& name1) const;
  // Whether `name` is a complete image group written from the file `source` describes (same
  // size and modification time; a group written without a source never is).
  bool features_belong_to(const std::string& name, const SourceRecord& source) const;
  // The source record of the complete image group `name` (bytes and mtime_ns; the name is
  // `name`); nullopt when it has none.
  std::optional<SourceRecord> recorded_source(const std::string& name) const;
  // The option record of the image group `name` (its JSON text); nullopt when it has none.
  std::optional<std::string> option_record(const std::string& name) const;
  // Writes one image's group, replacing any group of that name; with `source` and `options`,
  // records them.
  void write_features(const std::string& name, const Features& features,
                      const SourceRecord* source = nullptr,
                      const ExtractorOptions* options = nullptr);
  // Throws, before anything is written (a bad name is no failure of the file: later writes go
  // on), when `image` cannot have a group here: an empty name, or one nesting with another
  // image's group ("a" and "a/x.png": the group of one would hold or replace the other's).
  void check_image_name(const std::string& image) const;
  // Removes an image's group, if there is one.
  void remove_features(const std::string& name);
  // Reads back what write_features wrote (keypoints, size, angle, octave, response, descriptors,
  // image size; info is not stored).
  Features read_features(const std::string& name) const;
  // Only the descriptors of an image (what matching needs).
  std::vector<Descriptor> read_descriptors(const std::string& name) const;
  // Writes one pair's group, replacing any group of the pair; with `record`, records it
  // (io/match_record.hpp).
  void write_matches(const std::string& name0, const std::string& name1, int keypoints0,
                     const std::vector<Match>& matches, const PairRecord* record = nullptr);
  // The record of the pair's complete group; nullopt when it has none (or no complete group).
  std::optional<PairRecord> pair_record(const std::string& name0, const std::string& name1) const;
  // The matches of a pair (query = index in image 0); distance from matching_scores0. Throws as
  // has_matches does for another pair's group.
  std::vector<Match> read_matches(const std::string& name0, const std::string& name1) const;
  // What has_matches and read_matches answer together, with one lookup of the pair's group: its
  // matches, or nullopt when the file holds no complete group for the pair. Throws as they do.
  // `queries`, when given, gets the length of matches0 (image 0's keypoints when written).
  std::optional<std::vector<Match>> find_matches(const std::string& name0, const std::string& name1,
                                                 std::size_t* queries = nullptr) const;
  // The image names of a features file: every group holding an image_size dataset, sorted.
  std::vector<std::string> feature_names() const;
  // What a file holds, in one pass: its complete image groups (feature_names), the images whose
  // group a killed write left incomplete (keypoints but no image_size), whether it holds pair
  // groups (matches0: a matches file).
  struct Listing {
    std::vector<std::string> names, incomplete;
    bool holds_pairs = false;
  };
  Listing listing() const;
  // Copies the group `name` of `source` here (replacing an incomplete one), not flushed: for a
  // file written whole and then renamed (merge_feature_files).
  void copy_group_from(const Hdf5File& source, const std::string& name);
  // What a file opened read_write held when opened: an image group (one of them, by its group
  // name; empty when none) and any pair group. Commands refuse to write matches into a features
  // file and features into a matches file.
  const std::string& first_image_group() const { return first_image_; }
  bool holds_pairs() const { return holds_pairs_; }
  // When the image group `group` holds descriptors aief cannot have written (another tool's:
  // hloc's SuperPoint writes 256 x N float32), what they are ("256 x 1000 float32"); else "".
  std::string foreign_descriptors(const std::string& group) const;

  // Closes the file now (flushing what is pending), throwing when libhdf5 cannot (its last writes
  // failed); the destructor closes a file still open and ignores a failure, so a writer calls
  // close() to know that its writes are on disk.
  void close();

  // Groups written (write_features, write_matches, copy_group_from) and flushed: what the file on
  // disk holds of this object's writes. After a failed write, fewer than were written when the
  // failure came at a flush (a file system without fallocate).
  int groups_on_disk() const { return flushed_groups_; }

  // Groups written between flushes: a flush costs about as much as writing a small pair group.
  static constexpr int kWritesPerFlush = 64;

 private:
  // Throws when the group of (name0, name1) records other names.
  void check_pair_owner(const std::string& group, const std::string& name0,
                        const std::string& name1) const;
  // Room for a group's object headers and index entries beside its data; a flush's own growth is
  // reserved separately before it.
  static constexpr std::uint64_t kMetadataAllowance = 64 * 1024;
  // Reserves disk blocks up to libhdf5's end of allocation plus `extra` bytes; throws on ENOSPC.
  void reserve(std::uint64_t extra);
  // Diverts the file's descriptor to a scratch file: nothing more reaches the file.
  void fence();
  // Reserves and flushes; throws on failure.
  void flush_now();
  // Flushes a file just created, or removes it and throws "cannot create".
  void flush_created_file();
  // Whether the file may hold a group named `group`: false only when it certainly does not (a
  // written file keeps the hashes of its groups, so a new name costs no lookup in libhdf5).
  bool may_hold(const std::string& group) const;
  void note_group(const std::string& group);
  // When a write reaches the disk: with the next batch, at once, or only at close (a file written
  // whole and renamed).
  enum class Flush { batched, now, at_close };
  // Runs `write` (about `bytes` of data), reserved before and fenced on failure, and flushes it
  // as told.
  template <class Write>
  void write_guarded(std::uint64_t bytes, const std::string& what, Write&& write,
                     Flush flush = Flush::batched, bool adds_a_group = true);

  std::unique_ptr<OutputLock> lock_;     // read_write: held from before opening until destroyed
  std::unique_ptr<ReadLock> read_lock_;  // read modes: a writer's lock refuses the file
  std::string path_;
  std::string creating_as_;  // the temporary a new file is created as, until its first flush
  std::string creating_at_;  // where it is renamed to: the file path_ names (a link followed)
  long long file_ = -1;      // hid_t
  int descriptor_ = -1;      // libhdf5's POSIX descriptor of the file (sec2 driver), when writing
  std::uint64_t reserved_until_ = 0;
  int unflushed_writes_ = 0;
  int written_groups_ = 0, flushed_groups_ = 0;  // groups_on_disk()
  bool flushed_a_write_ = false;
  std::string first_image_;    // read_write: an image group's name, as the file was opened
  bool holds_pairs_ = false;   // read_write: the file held a pair group when opened
  bool groups_known_ = false;  // read_write: groups_ holds the hash of every group's name
  std::unordered_set<std::uint64_t> groups_;
  std::mutex failure_mutex_;  // writes come from one thread at a time; the lock orders the record
  std::string failure_;       // the first failed write's reason; later writes are refused
};

}  // namespace aief::io
