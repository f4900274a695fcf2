#pragma once
// Shards of one collection merged into one features file (io/hdf5_file.hpp), `aief merge`.
#include <string>
#include <vector>

namespace aief::io {

// Copies every image group of `inputs` (shard files) into `output` (created or extended); an
// image already in `output` is kept when its shard's group records the same making (source file
// size and time, option record), else replaced by the shard's (a rerun after an image changed or
// the shards were extracted again; `replaced` counts those); an image in two inputs is an error,
// and so is a group whose option record differs from the first group's in a field that changes the
// output (a group without a record and one with a record differ; groups without records all agree).
// Atomic: every input is checked before anything is written, the result is written to a temporary
// and renamed over `output`, so a failed merge (a bad input, a full disk) leaves `output` as it was
// (or absent). Linear in the images (hash sets). Returns the images copied, replaced ones included.
// Refused before anything is written: a matches file or another tool's features (SuperPoint) as
// an input or as the output, and an image whose shard group is of an older file of that name
// than the output's (another image of the same name, or an older shard: an older group never
// replaces a newer one). Said in `notes`: incomplete groups (a killed write's) left out. An output
// that is a symbolic link is written through (its target replaced, the link kept).
int merge_feature_files(const std::string& output, const std::vector<std::string>& inputs,
                        int* replaced = nullptr, std::vector<std::string>* notes = nullptr);

}  // namespace aief::io
