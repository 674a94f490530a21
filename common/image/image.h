#ifndef EVOSLAM_COMMON_IMAGE_IMAGE_H_
#define EVOSLAM_COMMON_IMAGE_IMAGE_H_

#include <cstdint>
#include <filesystem>
#include <vector>

namespace evoslam {

// The readers refuse larger images before allocating, so that a corrupt header cannot exhaust
// memory.
inline constexpr std::uint64_t kMaxDecodedPixels = std::uint64_t{1} << 28;

struct Rgb {
  std::uint8_t r = 0;
  std::uint8_t g = 0;
  std::uint8_t b = 0;
  bool operator==(const Rgb&) const = default;
};

inline constexpr Rgb kWhite{255, 255, 255};

// The colour `t` of the way from `from` to `to` (t in [0, 1], clamped), each channel rounded.
Rgb Blend(Rgb from, Rgb to, double t);

// An 8-bit RGB raster, row 0 at the top. Drawing clips to the image. Drawing coordinates are in
// pixels, pixel (x, y) being the unit square centred on (x, y).
class Image {
 public:
  Image() = default;
  Image(int width, int height, Rgb fill = kWhite);

  int width() const { return width_; }
  int height() const { return height_; }
  Rgb& at(int x, int y) { return pixels_[static_cast<std::size_t>(y) * width_ + x]; }
  const Rgb& at(int x, int y) const { return pixels_[static_cast<std::size_t>(y) * width_ + x]; }
  bool contains(int x, int y) const { return x >= 0 && y >= 0 && x < width_ && y < height_; }

  void SetPixel(int x, int y, Rgb color);  // ignored outside the image
  // Stamps a thickness x thickness square brush along the line; thickness < 1 draws nothing.
  void DrawLine(double x0, double y0, double x1, double y1, Rgb color, int thickness = 1);
  // Fills the pixels whose centres lie within radius of (cx, cy).
  void DrawDisc(double cx, double cy, double radius, Rgb color);
  // Fills the width x height pixels whose top-left one is (x, y).
  void FillRect(int x, int y, int width, int height, Rgb color);
  // Copies `source` with its top-left pixel at (x, y).
  void Paste(const Image& source, int x, int y);

 private:
  int width_ = 0;
  int height_ = 0;
  std::vector<Rgb> pixels_;
};

// How many of the image's pixels have exactly this colour.
int CountPixels(const Image& image, Rgb color);

// Writes an 8-bit PNG, with a palette when the image has at most 256 colours (far smaller for
// drawings), else RGB; throws evoslam::Error naming the path on failure.
void WritePng(const Image& image, const std::filesystem::path& path);
// Reads an 8-bit (gray, gray+alpha, RGB or RGBA) PNG; throws evoslam::InputError, also for a
// header that states more than `max_pixels` pixels, before any pixel is decoded.
Image ReadPng(const std::filesystem::path& path, std::uint64_t max_pixels = kMaxDecodedPixels);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_IMAGE_IMAGE_H_
