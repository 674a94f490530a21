#include "coordinator/upload_assembler.h"

#include <cerrno>
#include <system_error>
#include <utility>

#include "common/protocol/wire.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

std::string ErrnoText() { return std::generic_category().message(errno); }

}  // namespace

void CheckChunkSize(std::size_t bytes, std::size_t max_chunk_bytes, const std::string& upload_id) {
  if (bytes > max_chunk_bytes) {
    throw ProtocolError(proto::ERROR_CODE_TOO_LARGE,
                        upload_id + ": a chunk of " + std::to_string(bytes) +
                            " bytes is over the limit of " + std::to_string(max_chunk_bytes));
  }
}

UploadAssembler::UploadAssembler(std::filesystem::path spool, std::string upload_id,
                                 std::string name, std::string sha256, std::uint64_t size,
                                 std::size_t max_chunk_bytes)
    : spool_(std::move(spool)),
      upload_id_(std::move(upload_id)),
      name_(std::move(name)),
      sha256_(std::move(sha256)),
      size_(size),
      max_chunk_bytes_(max_chunk_bytes),
      file_(std::fopen(spool_.c_str(), "w+b")) {
  if (!file_)
    throw Error("cannot create the upload spool file " + spool_.string() + ": " + ErrnoText());
}

UploadAssembler::~UploadAssembler() {
  file_.reset();
  std::error_code ignored;  // nothing to do about a file that will not go
  std::filesystem::remove(spool_, ignored);
}

void UploadAssembler::Refuse(proto::ErrorCode code, const std::string& why) {
  spoiled_ = true;
  throw ProtocolError(code, upload_id_ + " (dataset " + name_ + "): " + why);
}

bool UploadAssembler::Append(std::uint64_t offset, std::string_view bytes) {
  if (spoiled_) Refuse(proto::ERROR_CODE_INVALID, "a chunk was refused; start the upload again");
  if (complete_) Refuse(proto::ERROR_CODE_INVALID, "a chunk after the last");
  if (bytes.size() > max_chunk_bytes_) {
    spoiled_ = true;
    CheckChunkSize(bytes.size(), max_chunk_bytes_, upload_id_);
  }
  if (offset != received_) {
    Refuse(proto::ERROR_CODE_INVALID, "a chunk at byte " + std::to_string(offset) + " after " +
                                          std::to_string(received_) +
                                          " bytes: chunks go in order, each where the last ended");
  }
  if (bytes.empty() && size_ > 0) Refuse(proto::ERROR_CODE_INVALID, "an empty chunk");
  if (bytes.size() > size_ - received_) {
    Refuse(proto::ERROR_CODE_INVALID, "a chunk of " + std::to_string(bytes.size()) +
                                          " bytes at byte " + std::to_string(offset) +
                                          " goes past the announced size of " +
                                          std::to_string(size_) + " bytes");
  }
  if (std::fwrite(bytes.data(), 1, bytes.size(), file_.get()) != bytes.size()) {
    spoiled_ = true;
    throw Error("cannot write the upload spool file " + spool_.string() + ": " + ErrnoText());
  }
  hasher_.Update(bytes);
  received_ += bytes.size();
  if (received_ < size_) return false;
  const std::string sha = hasher_.FinishHex();
  if (sha != sha256_) {
    Refuse(proto::ERROR_CODE_INVALID,
           "announced SHA-256 " + sha256_.substr(0, 64) + " but its bytes hash to " + sha);
  }
  // Written whole; read back from the start from now on.
  if (std::fflush(file_.get()) != 0 || std::fseek(file_.get(), 0, SEEK_SET) != 0) {
    spoiled_ = true;
    throw Error("cannot write the upload spool file " + spool_.string() + ": " + ErrnoText());
  }
  complete_ = true;
  return true;
}

void UploadAssembler::ReadBack(std::span<char> piece) {
  if (!complete_) throw Error(upload_id_ + ": read back before all its bytes arrived");
  if (std::fread(piece.data(), 1, piece.size(), file_.get()) != piece.size()) {
    throw Error("cannot read back the upload spool file " + spool_.string() + ": " +
                (std::ferror(file_.get()) ? ErrnoText() : "it ended early"));
  }
}

}  // namespace evoslam
