#pragma once
// Where a batch writes the output of each input (io/batch_inputs.hpp names them): the file
// OUTDIR/<name>.<format>, the name's folders mirrored (`sub/x.png` -> `OUTDIR/sub/x.png.json`).
// The only rewrites keep the name inside OUTDIR and stay one-to-one: '%' -> "%25", a ".." part
// -> "%2E%2E", a leading '/' -> a first folder "%2F". So no two inputs share an output.
#include <string>
#include <vector>

#include "io/batch_inputs.hpp"

namespace aief::io {

// The output file of the input named `name`. One function for every file-per-image format.
std::string batch_output_path(const std::string& output_dir, const std::string& name,
                              const std::string& format);

// Distinct names give distinct files, but one can still be the folder of another (an image
// `a.png` beside a folder `a.png.json/`; in one HDF5 file, a name `a` beside `a/x.png`, whose
// groups would nest): throws aief::Error naming both before any work.
void check_batch_outputs_do_not_nest(const std::vector<BatchInput>& inputs,
                                     const std::string& output_dir, const std::string& format);

}  // namespace aief::io
