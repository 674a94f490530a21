#ifndef EVOSLAM_COMMON_IO_LINE_READER_H_
#define EVOSLAM_COMMON_IO_LINE_READER_H_

#include <cstddef>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace evoslam {

enum class Compression { kNone, kGzip, kBzip2 };

// Reads a text file line by line, holding only a window of it in memory. Plain, gzip and bzip2
// files are read alike; the format is recognised by the file's first bytes, since logs are often
// renamed or served without their extension. Every failure (missing file, unsupported
// compression, corrupt or truncated stream, overlong line) is an InputError naming the file and
// the line being read.
class LineReader {
 public:
  explicit LineReader(const std::filesystem::path& path);
  ~LineReader();
  LineReader(LineReader&&) noexcept;
  LineReader& operator=(LineReader&&) noexcept;

  // The next line without its "\n" or "\r\n"; the view stays valid until the next call.
  // nullopt at the end of the file. A last line without a terminator is still a line.
  std::optional<std::string_view> Next();

  // 1-based number of the line Next() returned last; 0 before the first.
  std::size_t line_number() const { return line_number_; }
  // The path as given, for messages.
  const std::string& source() const { return source_; }
  Compression compression() const { return compression_; }

  class ByteSource;  // a decompressor; defined in the .cc

 private:
  void Fill();

  std::string source_;
  Compression compression_ = Compression::kNone;
  std::unique_ptr<ByteSource> bytes_;
  // buffer_[begin_, end_) holds read but unreturned text; [begin_, scanned_) has no '\n'.
  std::vector<char> buffer_;
  std::size_t begin_ = 0;
  std::size_t scanned_ = 0;
  std::size_t end_ = 0;
  bool eof_ = false;
  std::size_t line_number_ = 0;
};

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_IO_LINE_READER_H_
