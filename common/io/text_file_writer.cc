#include "common/io/text_file_writer.h"

#include <cerrno>
#include <system_error>

#include "common/util/error.h"

namespace evoslam {

TextFileWriter::TextFileWriter(const std::filesystem::path& path)
    : path_(path.string()), file_(std::fopen(path.c_str(), "wb")) {
  if (!file_) Fail(errno);
}

void TextFileWriter::Write(std::string_view text) {
  if (!file_) throw Error("cannot write " + path_ + ": already closed");
  if (std::fwrite(text.data(), 1, text.size(), file_.get()) != text.size()) Fail(errno);
}

void TextFileWriter::Close() {
  if (!file_) return;
  const bool flushed = std::fflush(file_.get()) == 0 && !std::ferror(file_.get());
  const int error = errno;
  const bool closed = std::fclose(file_.release()) == 0;
  if (!flushed || !closed) Fail(flushed ? errno : error);
}

void TextFileWriter::Fail(int error) const {
  throw Error("cannot write " + path_ + ": " + std::generic_category().message(error));
}

}  // namespace evoslam
