#ifndef EVOSLAM_COMMON_IO_TEXT_FILE_WRITER_H_
#define EVOSLAM_COMMON_IO_TEXT_FILE_WRITER_H_

#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>

namespace evoslam {

// Writes a text file, turning every failure (cannot create, disk full, close error) into an
// Error naming the file. Close() must be called to learn whether the file is complete; a writer
// destroyed without it (e.g. while an exception unwinds) closes the file silently.
class TextFileWriter {
 public:
  explicit TextFileWriter(const std::filesystem::path& path);

  void Write(std::string_view text);
  void Close();

 private:
  struct Closer {
    void operator()(std::FILE* file) const { std::fclose(file); }
  };

  [[noreturn]] void Fail(int error) const;

  std::string path_;
  std::unique_ptr<std::FILE, Closer> file_;
};

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_IO_TEXT_FILE_WRITER_H_
