#ifndef EVOSLAM_COMMON_IMAGE_PGM_H_
#define EVOSLAM_COMMON_IMAGE_PGM_H_

#include <cstdint>
#include <filesystem>
#include <vector>

#include "common/image/image.h"

namespace evoslam {

// An 8-bit grayscale raster as a PGM file holds it: values 0 (black) to maxval (white), row 0 at
// the top, pixels row-major.
struct GrayImage {
  int width = 0;
  int height = 0;
  int maxval = 255;
  std::vector<std::uint8_t> pixels;

  std::uint8_t at(int x, int y) const {
    return pixels[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                  static_cast<std::size_t>(x)];
  }
};

// Reads a binary (P5) or plain (P2) PGM with maxval at most 255. '#' comments may appear
// wherever whitespace may. Throws evoslam::InputError naming the file (and the line, where it
// has lines) for a bad header, a value above maxval, or pixel data that is short of or longer
// than width x height, and for a header that states more than `max_pixels` pixels, before any
// pixel is decoded.
GrayImage ReadPgm(const std::filesystem::path& path,
                  std::uint64_t max_pixels = kMaxDecodedPixels);

// Writes a binary (P5) PGM; throws evoslam::Error naming the path on failure or when the pixel
// count does not match the size.
void WritePgm(const GrayImage& image, const std::filesystem::path& path);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_IMAGE_PGM_H_
