#include "coordinator/upload_table.h"

#include "common/protocol/wire.h"
#include "common/util/random_id.h"

namespace evoslam {

void CheckQuota(const std::string& name, std::uint64_t size, std::uint64_t stored,
                std::uint64_t quota) {
  if (quota == 0 || stored + size <= quota) return;
  throw ProtocolError(proto::ERROR_CODE_QUOTA_EXCEEDED,
                      "dataset " + name + " of " + std::to_string(size) +
                          " bytes would take this client's stored bytes to " +
                          std::to_string(stored + size) + ", over its quota of " +
                          std::to_string(quota) +
                          "; the coordinator drops datasets no job reads and old results "
                          "after its retention");
}

std::string UploadTable::Begin(const std::string& owner, const std::string& name,
                               std::uint64_t size, Clock::time_point now) {
  if (uploads_.size() >= max_uploads_) {
    throw ProtocolError(proto::ERROR_CODE_QUEUE_FULL,
                        std::to_string(uploads_.size()) +
                            " uploads are under way, the most this coordinator takes at once; "
                            "try again later");
  }
  std::string id = "upload-" + RandomHexId(16);
  uploads_.emplace(id, Upload{owner, name, size, 1, now});
  return id;
}

void UploadTable::Accept(const std::string& id, const std::string& owner, Clock::time_point now) {
  const auto it = uploads_.find(id);
  if (it == uploads_.end() || it->second.owner != owner) {
    throw ProtocolError(
        proto::ERROR_CODE_UNKNOWN_UPLOAD,
        "no upload " + id.substr(0, 64) + " is under way (it ended, or timed out); start it again");
  }
  if (it->second.waiting >= kUploadWindow) {
    const std::string name = it->second.name;
    uploads_.erase(it);
    throw ProtocolError(proto::ERROR_CODE_QUEUE_FULL,
                        id + " (dataset " + name + "): more than " + std::to_string(kUploadWindow) +
                            " chunks sent ahead of their answers; the upload is dropped");
  }
  ++it->second.waiting;
  it->second.heard = now;
}

void UploadTable::Answered(const std::string& id, Clock::time_point now) {
  const auto it = uploads_.find(id);
  if (it == uploads_.end()) return;
  if (it->second.waiting > 0) --it->second.waiting;
  it->second.heard = now;
}

void UploadTable::End(const std::string& id) { uploads_.erase(id); }

std::uint64_t UploadTable::Reserved(const std::string& owner) const {
  std::uint64_t bytes = 0;
  for (const auto& [id, upload] : uploads_) {
    if (upload.owner == owner) bytes += upload.size;
  }
  return bytes;
}

std::vector<std::string> UploadTable::Silent(Clock::time_point before) const {
  std::vector<std::string> silent;
  for (const auto& [id, upload] : uploads_) {
    if (upload.waiting == 0 && upload.heard < before) silent.push_back(id);
  }
  return silent;
}

std::string UploadTable::NameOf(const std::string& id) const {
  const auto it = uploads_.find(id);
  return it == uploads_.end() ? std::string() : it->second.name;
}

}  // namespace evoslam
