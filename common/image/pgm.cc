#include "common/image/pgm.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <utility>

#include "common/image/image.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

// Walks the text parts of a PGM: whitespace-separated decimal numbers with '#' comments,
// keeping the line number for messages.
class Scanner {
 public:
  Scanner(const std::string& data, std::string source) : data_(data), source_(std::move(source)) {}

  std::size_t pos() const { return pos_; }
  void Skip(std::size_t n) { pos_ += n; }
  std::size_t line() const { return line_; }
  bool at_end() const { return pos_ >= data_.size(); }

  void SkipSpaceAndComments() {
    while (pos_ < data_.size()) {
      const char c = data_[pos_];
      if (c == '#') {
        while (pos_ < data_.size() && data_[pos_] != '\n') ++pos_;
      } else if (std::isspace(static_cast<unsigned char>(c))) {
        if (c == '\n') ++line_;
        ++pos_;
      } else {
        break;
      }
    }
  }

  // Reads an unsigned decimal number no larger than `limit`; `what` names it in errors.
  std::uint64_t Number(const std::string& what, std::uint64_t limit) {
    SkipSpaceAndComments();
    if (at_end()) Fail("unexpected end of file; expected " + what);
    const std::size_t start = pos_;
    std::uint64_t value = 0;
    while (pos_ < data_.size() && std::isdigit(static_cast<unsigned char>(data_[pos_]))) {
      value = value * 10 + static_cast<std::uint64_t>(data_[pos_] - '0');
      if (value > limit) {
        Fail(what + " exceeds " + std::to_string(limit));
      }
      ++pos_;
    }
    if (pos_ == start ||
        (pos_ < data_.size() && !std::isspace(static_cast<unsigned char>(data_[pos_])) &&
         data_[pos_] != '#')) {
      Fail("expected " + what + " (a non-negative integer)");
    }
    return value;
  }

  // Consumes the single whitespace character that ends a binary PGM's header.
  void HeaderEnd() {
    if (at_end() || !std::isspace(static_cast<unsigned char>(data_[pos_]))) {
      Fail("expected a whitespace character after maxval");
    }
    ++pos_;
  }

  [[noreturn]] void Fail(const std::string& message) const {
    throw InputError(source_, line_, message);
  }

 private:
  const std::string& data_;
  std::string source_;
  std::size_t pos_ = 0;
  std::size_t line_ = 1;
};

// Reads the magic number, width and height, refusing an image of more than `max_pixels`.
void ReadSize(Scanner& scan, const std::string& data, std::uint64_t max_pixels, GrayImage& image) {
  if (data.size() < 2 || data[0] != 'P' || (data[1] != '5' && data[1] != '2')) {
    scan.Fail("expected a PGM file starting with P5 or P2");
  }
  if (data.size() > 2 && !std::isspace(static_cast<unsigned char>(data[2])) && data[2] != '#') {
    scan.Fail("expected whitespace after the PGM magic number");
  }
  scan.Skip(2);
  constexpr std::uint64_t kMaxSide = std::numeric_limits<int>::max();
  image.width = static_cast<int>(scan.Number("width", kMaxSide));
  image.height = static_cast<int>(scan.Number("height", kMaxSide));
  if (image.width == 0 || image.height == 0) scan.Fail("width and height must be positive");
  const std::uint64_t pixels = static_cast<std::uint64_t>(image.width) * image.height;
  if (pixels > std::min(max_pixels, kMaxDecodedPixels)) {
    scan.Fail("image of " + std::to_string(image.width) + " x " + std::to_string(image.height) +
              " pixels, more than the " + std::to_string(std::min(max_pixels, kMaxDecodedPixels)) +
              " allowed");
  }
}

// A header is a few dozen bytes; this much also holds one with long comments.
constexpr std::size_t kHeaderBytes = 64 * 1024;

}  // namespace

GrayImage ReadPgm(const std::filesystem::path& path, std::uint64_t max_pixels) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), 0, "cannot open PGM file");
  // The header first, so that an image over the limit is refused before its pixels are read.
  std::string data(kHeaderBytes, '\0');
  in.read(data.data(), static_cast<std::streamsize>(data.size()));
  data.resize(static_cast<std::size_t>(in.gcount()));
  if (in.bad()) throw InputError(path.string(), 0, "cannot read PGM file");
  if (data.size() == kHeaderBytes) {
    GrayImage head;
    Scanner scan(data, path.string());
    try {
      ReadSize(scan, data, max_pixels, head);
    } catch (const InputError&) {
      if (!scan.at_end()) throw;  // else the prefix cut the header short: read on
    }
    data.append(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    if (in.bad()) throw InputError(path.string(), 0, "cannot read PGM file");
  }

  const bool binary = data.size() > 1 && data[1] == '5';
  Scanner scan(data, path.string());
  GrayImage image;
  ReadSize(scan, data, max_pixels, image);
  const std::uint64_t pixels = static_cast<std::uint64_t>(image.width) * image.height;
  scan.SkipSpaceAndComments();
  const std::size_t maxval_line = scan.line();
  const std::uint64_t maxval = scan.Number("maxval", 65535);
  if (maxval == 0 || maxval > 255) {
    throw InputError(path.string(), maxval_line,
                     "maxval " + std::to_string(maxval) + " unsupported; expected 1 to 255");
  }
  image.maxval = static_cast<int>(maxval);
  const std::string size_text = std::to_string(image.width) + " x " + std::to_string(image.height) +
                                " = " + std::to_string(pixels);
  image.pixels.resize(pixels);

  if (binary) {
    scan.HeaderEnd();
    const std::size_t available = data.size() - scan.pos();
    if (available < pixels) {
      throw InputError(path.string(), 0,
                       "truncated pixel data: expected " + size_text + " bytes, found " +
                           std::to_string(available));
    }
    if (available > pixels) {
      throw InputError(path.string(), 0,
                       std::to_string(available - pixels) + " bytes follow the " + size_text +
                           " pixels; the header's size looks wrong");
    }
    for (std::size_t i = 0; i < pixels; ++i) {
      const auto v = static_cast<std::uint8_t>(data[scan.pos() + i]);
      if (v > maxval) {
        throw InputError(path.string(), 0,
                         "pixel " + std::to_string(i) + " value " + std::to_string(v) +
                             " exceeds maxval " + std::to_string(maxval));
      }
      image.pixels[i] = v;
    }
    return image;
  }

  for (std::size_t i = 0; i < pixels; ++i) {
    scan.SkipSpaceAndComments();
    if (scan.at_end()) {
      scan.Fail("truncated pixel data: expected " + size_text + " values, found " +
                std::to_string(i));
    }
    image.pixels[i] = static_cast<std::uint8_t>(scan.Number("a pixel value", maxval));
  }
  scan.SkipSpaceAndComments();
  if (!scan.at_end()) {
    scan.Fail("more than the " + size_text + " pixel values; the header's size looks wrong");
  }
  return image;
}

void WritePgm(const GrayImage& image, const std::filesystem::path& path) {
  if (image.width <= 0 || image.height <= 0 || image.maxval < 1 || image.maxval > 255 ||
      image.pixels.size() != static_cast<std::size_t>(image.width) * image.height) {
    throw Error(path.string() + ": cannot write a PGM of " + std::to_string(image.width) + " x " +
                std::to_string(image.height) + " with " + std::to_string(image.pixels.size()) +
                " pixels and maxval " + std::to_string(image.maxval));
  }
  std::ofstream out(path, std::ios::binary);
  if (!out) throw Error(path.string() + ": cannot open for writing");
  out << "P5\n" << image.width << ' ' << image.height << '\n' << image.maxval << '\n';
  out.write(reinterpret_cast<const char*>(image.pixels.data()),
            static_cast<std::streamsize>(image.pixels.size()));
  out.close();
  if (!out) throw Error(path.string() + ": write failed");
}

}  // namespace evoslam
