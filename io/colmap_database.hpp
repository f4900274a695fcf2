#pragma once
// COLMAP's database (SQLite, COLMAP 3.x schema) from hloc-layout files (io/hdf5_file.hpp),
// so `colmap matches_importer --match_type pairs` verifies the matches geometrically and
// `colmap mapper` reconstructs from them. Built when libsqlite3 and libhdf5 are found.
//
// - cameras: one per image, SIMPLE_RADIAL (model 2), f = 1.2 * max(width, height) as COLMAP
//   guesses without EXIF, principal point at the centre, k = 0;
// - images: ids 1..n in name order, named as the feature groups (paths relative to the image
//   folder that colmap's --image_path then names). A name is stored as its bytes, as COLMAP
//   stores it (TEXT bound as is): a name that is not UTF-8 reads back byte for byte in COLMAP,
//   and in Python's sqlite3 with `connection.text_factory = bytes` (its default str fails);
//   such names are listed in ColmapExport so the command can say so;
// - keypoints: N x 2 float32, shifted by +0.5: COLMAP's origin is the top-left pixel's corner,
//   aief's (OpenCV's) the top-left pixel's centre (hloc shifts the same way);
// - descriptors: N x 32 uint8 (COLMAP's own SIFT matchers expect 128 columns: match with aief);
// - matches: per pair of pairs.txt, pair_id = id1 * 2147483647 + id2 with id1 < id2, N x 2 uint32;
//   two_view_geometries is left to colmap's verification. Every match's two keypoint indices are
//   checked against the images' keypoint counts (matches from another run are refused).
#include <string>
#include <vector>

namespace aief::io {

struct ColmapExport {
  int images = 0;
  int pairs = 0;  // pairs written (pairs.txt lines with matches in matches.h5)
  long long matches = 0;
  std::vector<std::string> names_not_utf8;  // stored as their bytes (see above)
  std::vector<std::string> notes;           // pairs.txt lines left out, and why (io/pairs_file.hpp)
};

// Creates `database` (it must not exist; written to a temporary name, then renamed). Throws
// aief::Error naming the file, the image or the pair at fault.
ColmapExport export_colmap_database(const std::string& database, const std::string& features_h5,
                                    const std::string& matches_h5, const std::string& pairs_txt);

}  // namespace aief::io
