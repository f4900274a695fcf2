// aief::io through the installed package: a BGR image in memory made gray (OpenCV), its features
// extracted and, when aief::io was built with HDF5 (AIEF_HAVE_HDF5), written to and read back
// from a features file in hloc's layout below the folder given as argument. Prints the counts.
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include <aief/aief.hpp>

#include "io/image_io.hpp"
#ifdef AIEF_HAVE_HDF5
#include "io/hdf5_file.hpp"
#endif

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: io_consumer FOLDER\n");
    return 2;
  }
  const int width = 320, height = 240;
  std::vector<unsigned char> bgr(static_cast<std::size_t>(width) * height * 3);
  std::mt19937 rng(1);
  for (std::size_t i = 0; i < bgr.size(); ++i)
    bgr[i] = static_cast<unsigned char>((((i / 3) % width / 8 + (i / 3) / width / 8) % 2) * 200 +
                                        rng() % 40);
  const aief::GrayImage gray =
      aief::io::gray_from_pixels(bgr.data(), width, height, 3, width * 3, "synthetic");
  aief::ExtractorOptions options;
  options.n_features = 300;
  const aief::Features features = aief::extract(gray.view(), options);
  std::size_t read_back = features.keypoints.size();
#ifdef AIEF_HAVE_HDF5
  const std::string path = std::string(argv[1]) + "/features.h5";
  {
    aief::io::Hdf5File file(path, aief::io::Hdf5File::Mode::read_write);
    file.write_features("synthetic.png", features);
    file.close();
  }
  read_back = aief::io::Hdf5File(path, aief::io::Hdf5File::Mode::read)
                  .read_features("synthetic.png")
                  .keypoints.size();
  std::printf("aief::io: %zu keypoints, %zu read back from %s\n", features.keypoints.size(),
              read_back, path.c_str());
#else
  std::printf("aief::io: %zu keypoints (no HDF5 in this build)\n", features.keypoints.size());
#endif
  return features.keypoints.empty() || read_back != features.keypoints.size() ? 1 : 0;
}
