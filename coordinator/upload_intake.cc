#include "coordinator/upload_intake.h"

#include <spdlog/spdlog.h>

#include <chrono>
#include <exception>
#include <system_error>
#include <utility>

#include "common/protocol/wire.h"
#include "common/util/error.h"

namespace evoslam {

UploadIntake::SpoolDir::SpoolDir(std::filesystem::path path) : path_(std::move(path)) {
  std::error_code error;
  std::filesystem::remove_all(path_, error);
  if (!error) std::filesystem::create_directories(path_, error);
  if (error) {
    throw Error("cannot make the upload spool folder " + path_.string() + ": " + error.message());
  }
}

UploadIntake::SpoolDir::~SpoolDir() {
  std::error_code ignored;  // nothing more to do about a folder that will not go
  std::filesystem::remove_all(path_, ignored);
}

UploadIntake::UploadIntake(const std::filesystem::path& db, std::filesystem::path spool_dir,
                           Options options, Deliver deliver)
    : store_(db),
      spool_dir_(std::move(spool_dir)),
      options_(options),
      deliver_(std::move(deliver)),
      storer_([this](DatabaseWork& work, const std::stop_token& stop) {
        if (auto* start = std::get_if<StartWork>(&work)) return Begin(*start);
        Store(std::get<StoreWork>(work), stop);
      }),
      spooler_([this](Work& work, const std::stop_token&) { Spool(work); }) {}

UploadIntake::~UploadIntake() {
  spooler_.Stop();
  storer_.Stop();
}

void UploadIntake::Start(std::string identity, std::uint64_t request_id, std::string upload_id,
                         std::string name, std::string sha256, std::optional<std::uint64_t> size,
                         std::string owner, std::uint64_t reserved, double now_unix_s) {
  storer_.Post(StartWork{std::move(identity), request_id, std::move(upload_id), std::move(name),
                         std::move(sha256), size, std::move(owner), reserved, now_unix_s});
}

void UploadIntake::Append(std::string identity, std::uint64_t request_id,
                          proto::UploadChunk chunk) {
  spooler_.Post(ChunkWork{std::move(identity), request_id, std::move(chunk)});
}

void UploadIntake::Drop(std::string upload_id) { spooler_.Post(DropWork{std::move(upload_id)}); }

void UploadIntake::Spool(Work& work) {
  std::visit([&](auto& w) { Do(w); }, work);
}

void UploadIntake::Begin(StartWork& work) {
  Answer answer{work.identity, {}, work.upload_id, true};
  try {
    // Only the client's own uploads count: whether another client has some bytes stays its own
    // business, and bytes uploaded once are the uploader's from then on.
    if (store_.ClaimDataset(work.sha256, work.owner, work.started)) {
      proto::DatasetStored& stored = *answer.reply.mutable_stored();
      stored.mutable_dataset()->set_sha256(work.sha256);
      stored.mutable_dataset()->set_size_bytes(work.size.value_or(0));
      stored.mutable_dataset()->set_name(work.name);
      stored.set_already_present(true);
    } else if (!work.size) {
      throw ProtocolError(proto::ERROR_CODE_UNKNOWN_DATASET,
                          "dataset " + work.sha256 + " is not here; upload its bytes");
    } else {
      if (options_.quota_bytes > 0) {
        CheckQuota(work.name, *work.size, store_.StoredBytes(work.owner) + work.reserved,
                   options_.quota_bytes);
      }
      spooler_.Post(std::move(work));  // the spool thread makes its spool and answers
      return;
    }
  } catch (const ProtocolError& e) {
    answer.reply = ErrorReplyFor(work.request_id, e.code(), e.what());
  } catch (const std::exception& e) {
    answer.reply = ErrorReplyFor(work.request_id, proto::ERROR_CODE_INTERNAL, e.what());
  }
  answer.reply.set_request_id(work.request_id);
  deliver_(std::move(answer));
}

void UploadIntake::Do(StartWork& work) {
  Answer answer{work.identity, {}, work.upload_id, false};
  answer.reply.set_request_id(work.request_id);
  try {
    uploads_.try_emplace(work.upload_id, spool_dir_.path() / work.upload_id, work,
                         options_.chunk_bytes);
    proto::UploadStarted& started = *answer.reply.mutable_upload_started();
    started.set_upload_id(work.upload_id);
    started.set_chunk_bytes(options_.chunk_bytes);
    started.set_window(options_.window);
  } catch (const std::exception& e) {
    answer.reply = ErrorReplyFor(work.request_id, proto::ERROR_CODE_INTERNAL, e.what());
    answer.ended = true;
  }
  deliver_(std::move(answer));
}

void UploadIntake::Do(ChunkWork& work) {
  const std::string id = work.chunk.upload_id();
  Answer answer{work.identity, {}, id, true};
  answer.reply.set_request_id(work.request_id);
  const auto it = uploads_.find(id);
  try {
    if (it == uploads_.end()) {
      throw ProtocolError(proto::ERROR_CODE_UNKNOWN_UPLOAD,
                          "no upload " + id.substr(0, 64) + " is under way; start it again");
    }
    UploadAssembler& assembler = it->second.assembler;
    if (assembler.Append(work.chunk.offset(), work.chunk.content())) {
      StoreWork store{work.identity, work.request_id, uploads_.extract(it)};
      storer_.Post(DatabaseWork(std::move(store)));
      return;  // answered once stored
    }
    answer.reply.mutable_chunk_stored()->set_upload_id(id);
    answer.reply.mutable_chunk_stored()->set_received_bytes(assembler.received());
    answer.ended = false;
  } catch (const ProtocolError& e) {
    answer.reply = ErrorReplyFor(work.request_id, e.code(), e.what());
  } catch (const std::exception& e) {
    // The coordinator's own trouble (its disk), not the client's.
    answer.reply = ErrorReplyFor(work.request_id, proto::ERROR_CODE_INTERNAL, e.what());
  }
  if (answer.ended) uploads_.erase(id);
  // The chunk's bytes go before the answer does: the broker may take the next chunk at once.
  work.chunk.Clear();
  deliver_(std::move(answer));
}

void UploadIntake::Do(DropWork& work) { uploads_.erase(work.upload_id); }

void UploadIntake::Store(StoreWork& work, const std::stop_token& stop) {
  Upload& upload = work.upload.mapped();
  UploadAssembler& assembler = upload.assembler;
  Answer answer{work.identity, {}, assembler.upload_id(), true};
  const auto began = std::chrono::steady_clock::now();
  try {
    if (options_.quota_bytes > 0 && !store_.OwnsDataset(assembler.sha256(), upload.owner)) {
      CheckQuota(assembler.name(), assembler.size(), store_.StoredBytes(upload.owner),
                 options_.quota_bytes);
    }
    const JobStore::ReadBytes read = [&](std::span<char> piece) {
      // Undone when cut short: one store of many pieces must not hold up the coordinator's end.
      if (stop.stop_requested()) throw Error("the coordinator is stopping");
      assembler.ReadBack(piece);
    };
    const bool added = store_.PutDataset(assembler.sha256(), assembler.name(), assembler.size(),
                                         read, options_.chunk_bytes, upload.owner, upload.started);
    proto::DatasetStored& stored = *answer.reply.mutable_stored();
    stored.mutable_dataset()->set_sha256(assembler.sha256());
    stored.mutable_dataset()->set_size_bytes(assembler.size());
    stored.mutable_dataset()->set_name(assembler.name());
    stored.set_already_present(!added);
    if (added) {
      spdlog::log(options_.quiet ? spdlog::level::debug : spdlog::level::info,
                  "stored dataset {} ({} bytes) in {:.2f} s", assembler.name(), assembler.size(),
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count());
    }
  } catch (const ProtocolError& e) {
    answer.reply = ErrorReplyFor(work.request_id, e.code(), e.what());
  } catch (const std::exception& e) {
    answer.reply = ErrorReplyFor(work.request_id, proto::ERROR_CODE_INTERNAL, e.what());
  }
  answer.reply.set_request_id(work.request_id);
  work.upload = {};  // its spool file goes before the answer does
  deliver_(std::move(answer));
}

}  // namespace evoslam
