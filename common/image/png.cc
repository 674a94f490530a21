// PNG I/O through libpng's simplified API, which reports failures through a message in the
// png_image rather than through longjmp, so no C++ object ever lives across a setjmp.
#include <png.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "common/image/image.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

// Releases libpng's read state however the read ends; png_image_free is a no-op once
// png_image_finish_read has already released it.
class PngImage {
 public:
  PngImage() {
    image_.version = PNG_IMAGE_VERSION;
    image_.opaque = nullptr;
  }
  ~PngImage() { png_image_free(&image_); }
  PngImage(const PngImage&) = delete;
  PngImage& operator=(const PngImage&) = delete;

  png_image* get() { return &image_; }
  std::string message() const { return image_.message; }

 private:
  png_image image_{};
};

// An image of at most 256 colours as indices into a table of them, in the order they first
// appear, so that the same image always gives the same bytes.
struct Palette {
  std::vector<std::uint8_t> colors;  // r, g, b of each entry
  std::vector<std::uint8_t> indices;
};

std::optional<Palette> PaletteOf(const Image& image) {
  constexpr std::size_t kMaxEntries = 256;
  Palette palette;
  palette.indices.reserve(static_cast<std::size_t>(image.width()) * image.height());
  std::map<std::uint32_t, std::uint8_t> index_of;
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) {
      const Rgb& p = image.at(x, y);
      const std::uint32_t key = (std::uint32_t{p.r} << 16) | (std::uint32_t{p.g} << 8) | p.b;
      auto it = index_of.find(key);
      if (it == index_of.end()) {
        if (index_of.size() == kMaxEntries) return std::nullopt;
        it = index_of.emplace(key, static_cast<std::uint8_t>(index_of.size())).first;
        palette.colors.insert(palette.colors.end(), {p.r, p.g, p.b});
      }
      palette.indices.push_back(it->second);
    }
  }
  return palette;
}

}  // namespace

void WritePng(const Image& image, const std::filesystem::path& path) {
  if (image.width() == 0 || image.height() == 0) {
    throw Error(path.string() + ": cannot write an empty (" + std::to_string(image.width()) +
                " x " + std::to_string(image.height()) + ") image as PNG");
  }
  PngImage png;
  png.get()->width = static_cast<png_uint_32>(image.width());
  png.get()->height = static_cast<png_uint_32>(image.height());
  const std::optional<Palette> palette = PaletteOf(image);
  std::vector<std::uint8_t> buffer;
  if (palette) {
    png.get()->format = PNG_FORMAT_RGB_COLORMAP;
    png.get()->colormap_entries = static_cast<png_uint_32>(palette->colors.size() / 3);
    buffer = palette->indices;
  } else {
    png.get()->format = PNG_FORMAT_RGB;
    buffer.reserve(static_cast<std::size_t>(image.width()) * image.height() * 3);
    for (int y = 0; y < image.height(); ++y) {
      for (int x = 0; x < image.width(); ++x) {
        const Rgb& p = image.at(x, y);
        buffer.insert(buffer.end(), {p.r, p.g, p.b});
      }
    }
  }
  const void* colormap = palette ? palette->colors.data() : nullptr;
  if (png_image_write_to_file(png.get(), path.c_str(), 0, buffer.data(), 0, colormap) == 0) {
    throw Error(path.string() + ": cannot write PNG: " + png.message());
  }
}

Image ReadPng(const std::filesystem::path& path, std::uint64_t max_pixels) {
  PngImage png;
  if (png_image_begin_read_from_file(png.get(), path.c_str()) == 0) {
    throw InputError(path.string(), 0, "cannot read PNG: " + png.message());
  }
  const std::uint64_t width = png.get()->width;
  const std::uint64_t height = png.get()->height;
  const std::uint64_t allowed = std::min(max_pixels, kMaxDecodedPixels);
  if (width * height > allowed || width > std::numeric_limits<int>::max() ||
      height > std::numeric_limits<int>::max()) {
    throw InputError(path.string(), 0,
                     "PNG of " + std::to_string(width) + " x " + std::to_string(height) +
                         " pixels, more than the " + std::to_string(allowed) + " allowed");
  }
  png.get()->format = PNG_FORMAT_RGB;
  std::vector<std::uint8_t> buffer(width * height * 3);
  // Transparent pixels are composited onto white, the colour of an empty canvas.
  const png_color white{255, 255, 255};
  if (png_image_finish_read(png.get(), &white, buffer.data(), 0, nullptr) == 0) {
    throw InputError(path.string(), 0, "cannot read PNG: " + png.message());
  }
  Image image(static_cast<int>(width), static_cast<int>(height));
  std::size_t i = 0;
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x, i += 3) {
      image.at(x, y) = {buffer[i], buffer[i + 1], buffer[i + 2]};
    }
  }
  return image;
}

}  // namespace evoslam
