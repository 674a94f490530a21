#include "common/io/line_reader.h"

#include <bzlib.h>
#include <zlib.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstring>
#include <span>
#include <stdexcept>
#include <system_error>

#include "common/util/error.h"

namespace evoslam {
namespace {

constexpr std::size_t kChunkBytes = std::size_t{1} << 20;
// A line this long is not text a log reader should accept; stops a binary file with no newline
// from being read into memory whole.
constexpr std::size_t kMaxLineBytes = std::size_t{64} << 20;

// A failure inside a decompressor; LineReader adds the file and line.
class StreamError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

std::string ErrnoText(int error) { return std::generic_category().message(error); }

struct FileCloser {
  void operator()(std::FILE* file) const { std::fclose(file); }
};
using FilePtr = std::unique_ptr<std::FILE, FileCloser>;

struct GzCloser {
  void operator()(gzFile file) const { gzclose(file); }
};
using GzPtr = std::unique_ptr<gzFile_s, GzCloser>;

struct BzReadCloser {
  void operator()(BZFILE* file) const {
    int error = BZ_OK;
    BZ2_bzReadClose(&error, file);
  }
};
using BzPtr = std::unique_ptr<BZFILE, BzReadCloser>;

// Reads at most this much per call so that sizes fit the C libraries' int parameters.
std::span<char> Capped(std::span<char> out) {
  return out.first(std::min<std::size_t>(out.size(), INT_MAX / 2));
}

}  // namespace

class LineReader::ByteSource {
 public:
  virtual ~ByteSource() = default;
  // Fills a prefix of out; returns its length, 0 only at the end of the data. Throws StreamError.
  virtual std::size_t Read(std::span<char> out) = 0;
};

namespace {

class PlainSource : public LineReader::ByteSource {
 public:
  explicit PlainSource(FilePtr file) : file_(std::move(file)) {}

  std::size_t Read(std::span<char> out) override {
    const std::size_t n = std::fread(out.data(), 1, out.size(), file_.get());
    if (n == 0 && std::ferror(file_.get())) throw StreamError("read error: " + ErrnoText(errno));
    return n;
  }

 private:
  FilePtr file_;
};

class GzipSource : public LineReader::ByteSource {
 public:
  explicit GzipSource(const std::filesystem::path& path) : file_(gzopen(path.c_str(), "rb")) {
    if (!file_) throw StreamError("cannot open gzip stream: " + ErrnoText(errno));
    gzbuffer(file_.get(), kChunkBytes / 4);
  }

  std::size_t Read(std::span<char> out) override {
    out = Capped(out);
    const int n = gzread(file_.get(), out.data(), static_cast<unsigned>(out.size()));
    int code = Z_OK;
    const char* message = gzerror(file_.get(), &code);
    // zlib reports a stream cut off mid-member as Z_BUF_ERROR once the input is exhausted.
    if (n <= 0 && code == Z_BUF_ERROR) {
      throw StreamError("truncated gzip stream (unexpected end of file)");
    }
    if (n < 0 || (code != Z_OK && code != Z_BUF_ERROR)) {
      throw StreamError(std::string("corrupt gzip stream (") + message + ")");
    }
    return static_cast<std::size_t>(n);
  }

 private:
  GzPtr file_;
};

class Bzip2Source : public LineReader::ByteSource {
 public:
  explicit Bzip2Source(FilePtr file) : file_(std::move(file)) { Open({}); }

  std::size_t Read(std::span<char> out) override {
    out = Capped(out);
    while (stream_) {
      int error = BZ_OK;
      const int n = BZ2_bzRead(&error, stream_.get(), out.data(), static_cast<int>(out.size()));
      if (error == BZ_OK) {
        stream_bytes_ += static_cast<std::size_t>(n);
        if (n > 0) return static_cast<std::size_t>(n);
        continue;
      }
      if (error == BZ_STREAM_END) {
        NextStream();
        if (n > 0) return static_cast<std::size_t>(n);
        continue;
      }
      // bzip2 itself ignores trailing bytes after a complete stream that do not start another.
      if (error == BZ_DATA_ERROR_MAGIC && streams_ > 1 && stream_bytes_ == 0) {
        stream_.reset();
        return 0;
      }
      throw StreamError(Describe(error));
    }
    return 0;
  }

 private:
  static std::string Describe(int error) {
    switch (error) {
      case BZ_UNEXPECTED_EOF:
        return "truncated bzip2 stream (unexpected end of file)";
      case BZ_DATA_ERROR:
        return "corrupt bzip2 stream (data error)";
      case BZ_DATA_ERROR_MAGIC:
        return "corrupt bzip2 stream (bad magic)";
      case BZ_MEM_ERROR:
        return "bzip2: out of memory";
      case BZ_IO_ERROR:
        return "read error: " + ErrnoText(errno);
      default:
        return "bzip2 error " + std::to_string(error);
    }
  }

  void Open(std::span<const char> unused) {
    // libbz2 wants a mutable pointer although it only copies the bytes.
    std::vector<char> carried(unused.begin(), unused.end());
    int error = BZ_OK;
    stream_.reset(BZ2_bzReadOpen(&error, file_.get(), 0, 0, carried.data(),
                                 static_cast<int>(carried.size())));
    if (error != BZ_OK) {
      stream_.reset();
      throw StreamError(Describe(error));
    }
    ++streams_;
    stream_bytes_ = 0;
  }

  // Files made by pbzip2 or by concatenation hold several streams back to back.
  void NextStream() {
    int error = BZ_OK;
    void* unused = nullptr;
    int unused_size = 0;
    BZ2_bzReadGetUnused(&error, stream_.get(), &unused, &unused_size);
    if (error != BZ_OK) throw StreamError(Describe(error));
    const std::vector<char> carried(static_cast<const char*>(unused),
                                    static_cast<const char*>(unused) + unused_size);
    stream_.reset();
    if (carried.empty()) {
      const int c = std::fgetc(file_.get());
      if (c == EOF) {
        if (std::ferror(file_.get())) throw StreamError("read error: " + ErrnoText(errno));
        return;
      }
      std::ungetc(c, file_.get());
    }
    Open(carried);
  }

  // Declared before stream_ so that the stream is closed before its file.
  FilePtr file_;
  BzPtr stream_;
  int streams_ = 0;
  std::size_t stream_bytes_ = 0;
};

// Names a compression that is recognised but not supported, or "" for none.
std::string_view UnsupportedCompression(std::span<const unsigned char> magic) {
  auto starts_with = [&](std::initializer_list<unsigned char> prefix) {
    return magic.size() >= prefix.size() && std::equal(prefix.begin(), prefix.end(), magic.begin());
  };
  if (starts_with({0xFD, '7', 'z', 'X', 'Z', 0x00})) return "xz";
  if (starts_with({0x28, 0xB5, 0x2F, 0xFD})) return "zstd";
  if (starts_with({0x5D, 0x00, 0x00})) return "lzma";
  if (starts_with({'P', 'K', 0x03, 0x04})) return "zip";
  if (starts_with({'7', 'z', 0xBC, 0xAF, 0x27, 0x1C})) return "7z";
  if (starts_with({0x04, 0x22, 0x4D, 0x18})) return "lz4";
  return "";
}

}  // namespace

LineReader::LineReader(const std::filesystem::path& path) : source_(path.string()) {
  FilePtr file(std::fopen(path.c_str(), "rb"));
  if (!file) throw InputError(source_, 0, "cannot open: " + ErrnoText(errno));
  std::array<unsigned char, 6> magic{};
  const std::size_t got = std::fread(magic.data(), 1, magic.size(), file.get());
  if (std::ferror(file.get())) throw InputError(source_, 0, "cannot read: " + ErrnoText(errno));
  const std::span<const unsigned char> head(magic.data(), got);
  if (const std::string_view name = UnsupportedCompression(head); !name.empty()) {
    throw InputError(source_, 0,
                     "unsupported compression (" + std::string(name) +
                         "); decompress it first or use plain text, gzip or bzip2");
  }
  if (std::fseek(file.get(), 0, SEEK_SET) != 0) {
    throw InputError(source_, 0, "cannot rewind: " + ErrnoText(errno));
  }
  try {
    if (got >= 2 && head[0] == 0x1F && head[1] == 0x8B) {
      compression_ = Compression::kGzip;
      file.reset();
      bytes_ = std::make_unique<GzipSource>(path);
    } else if (got >= 4 && head[0] == 'B' && head[1] == 'Z' && head[2] == 'h' && head[3] >= '1' &&
               head[3] <= '9') {
      compression_ = Compression::kBzip2;
      bytes_ = std::make_unique<Bzip2Source>(std::move(file));
    } else {
      bytes_ = std::make_unique<PlainSource>(std::move(file));
    }
  } catch (const StreamError& e) {
    throw InputError(source_, 0, e.what());
  }
  buffer_.resize(kChunkBytes);
}

LineReader::~LineReader() = default;
LineReader::LineReader(LineReader&&) noexcept = default;
LineReader& LineReader::operator=(LineReader&&) noexcept = default;

std::optional<std::string_view> LineReader::Next() {
  for (;;) {
    const char* base = buffer_.data();
    std::size_t line_end = end_;
    std::size_t next_begin = end_;
    if (const void* newline = std::memchr(base + scanned_, '\n', end_ - scanned_)) {
      line_end = static_cast<std::size_t>(static_cast<const char*>(newline) - base);
      next_begin = line_end + 1;
    } else if (!eof_) {
      scanned_ = end_;
      Fill();
      continue;
    } else if (begin_ == end_) {
      return std::nullopt;
    }
    std::string_view line(base + begin_, line_end - begin_);
    begin_ = scanned_ = next_begin;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    ++line_number_;
    return line;
  }
}

void LineReader::Fill() {
  if (begin_ > 0) {
    std::memmove(buffer_.data(), buffer_.data() + begin_, end_ - begin_);
    end_ -= begin_;
    scanned_ -= begin_;
    begin_ = 0;
  }
  if (end_ == buffer_.size()) {
    if (buffer_.size() >= kMaxLineBytes) {
      throw InputError(
          source_, line_number_ + 1,
          "line longer than " + std::to_string(kMaxLineBytes >> 20) + " MiB; is this a text file?");
    }
    buffer_.resize(std::min(buffer_.size() * 2, kMaxLineBytes));
  }
  std::size_t n = 0;
  try {
    n = bytes_->Read(std::span<char>(buffer_).subspan(end_));
  } catch (const StreamError& e) {
    throw InputError(source_, line_number_ + 1, e.what());
  }
  if (n == 0) eof_ = true;
  end_ += n;
}

}  // namespace evoslam
