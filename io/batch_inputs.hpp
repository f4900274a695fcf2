#pragma once
// Which images a batch takes, and the name each one gets: one rule for `aief extract --batch`,
// the Python module's `aief.batch_inputs` and the Dask recipe (python/aief/dask_batch.py), so
// every way of running a batch makes the same groups.
//
// A folder: its files with an extension of a format aief reads (io/image_formats.hpp, the list
// the single-image reader uses, any case), recursively. Folder symlinks
// are followed, except one leading back to a folder being listed (a cycle). Symlinks are never
// resolved for the name: two links to one file are two inputs. A broken link or a FIFO with an
// image name is listed too, so that reading it reports it (io/image_io.hpp refuses anything that
// is not a regular file before opening it), never dropped without a word.
//
// A list file (io/text_list.hpp: a folder, a binary file or a line longer than a path is
// refused): one path per line, trailing blanks and '\r' dropped, blank lines and lines starting
// with '#' skipped.
//
// Names: an input's name is its key (hloc's and COLMAP's convention): its path below the folder
// as listed, or its list line with "." parts and doubled '/' dropped (name_of_listed_path).
// Inputs are sorted by name (byte order: the order shards split); a name listed twice is taken
// once. The frames of one video (--entropy-threshold carried, where each frame's F depends on the
// frames before it) are taken in frame order instead: a list file's lines as listed, a folder's
// names in natural order, numbers by value (frame_2.png before frame_10.png, as ffmpeg's
// frame_%d.png are numbered), a decimal fraction after a number too (frames named by seconds:
// 0.033333.png before 0.1.png, 1500000000.05.png before 1500000000.1.png).
#include <cstddef>
#include <string>
#include <vector>

namespace aief::io {

struct BatchInput {
  std::string path;  // where it is read: FOLDER/name, or the list line as written
  std::string name;  // its key (see above)
};

// A list line as a name: "." parts and empty parts (doubled '/') dropped, nothing else changed.
std::string name_of_listed_path(const std::string& line);

enum class InputOrder { by_name, frames };

// The inputs of a folder or a list file, in `order`. Throws aief::Error.
std::vector<BatchInput> list_batch_inputs(const std::string& folder_or_list,
                                          InputOrder order = InputOrder::by_name);

// Whether `a` comes before `b` in natural order: runs of digits compared as numbers, with the
// decimal fraction right after one ("." and digits) by its value (a number without one is .0;
// so 1.10 comes before 1.9: names are read as seconds, not as versions); equal values by their
// spelling (fewer leading zeros, then fewer fraction digits, first); everything else byte by byte.
bool natural_less(const std::string& a, const std::string& b);

// How list_batch_inputs ordered the frames of `folder_or_list`, for a note: "in the list's
// order" or "in natural order of their names (numbers by value, decimal fractions too: ...)".
std::string frame_order_of(const std::string& folder_or_list);

// Shard `index` of `count`: inputs index, index + count, index + 2 count, ... (0 <= index < count).
std::vector<BatchInput> shard_of(const std::vector<BatchInput>& inputs, int index, int count);

}  // namespace aief::io
