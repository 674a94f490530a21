#include "coordinator/zap_handler.h"

#include <spdlog/spdlog.h>
#include <zmq.h>

#include <array>
#include <utility>
#include <vector>

#include "common/protocol/zmq_io.h"

namespace evoslam {
namespace {

std::string Z85(const zmq::message_t& key) {
  if (key.size() != 32) return {};
  std::array<char, 41> text{};
  if (zmq_z85_encode(text.data(), static_cast<const std::uint8_t*>(key.data()), 32) == nullptr)
    return {};
  return std::string(text.data(), 40);
}

}  // namespace

ZapHandler::ZapHandler(zmq::context_t& context,
                       std::map<std::string, std::set<std::string>> accepted)
    : socket_(context, zmq::socket_type::rep), accepted_(std::move(accepted)) {
  socket_.bind("inproc://zeromq.zap.01");
}

void ZapHandler::HandleOne() {
  const auto frames = ReceiveFrames(socket_);
  if (!frames) return;
  // version, request id, domain, address, identity, mechanism, credentials...
  // The User-Id of an accepted peer is its public key: the coordinator reads it off each message
  // (zmq_msg_gets) to know whose request it is.
  const auto reply = [&](const std::string& request_id, const char* code, const char* text,
                         const std::string& user_id = {}) {
    const std::vector<std::string> parts = {"1.0", request_id, code, text, user_id, ""};
    for (std::size_t i = 0; i < parts.size(); ++i) {
      socket_.send(zmq::buffer(parts[i]),
                   i + 1 < parts.size() ? zmq::send_flags::sndmore : zmq::send_flags::none);
    }
  };
  if (frames->size() < 6) {
    reply(frames->size() > 1 ? Text((*frames)[1]) : "", "400", "malformed ZAP request");
    return;
  }
  const std::string request_id = Text((*frames)[1]);
  const std::string domain = Text((*frames)[2]);
  const std::string address = Text((*frames)[3]);
  const std::string mechanism = Text((*frames)[5]);
  const auto keys = accepted_.find(domain);
  if (mechanism != "CURVE" || frames->size() < 7 || keys == accepted_.end()) {
    spdlog::warn("refused a {} connection from {} on '{}'", mechanism, address, domain);
    reply(request_id, "400", "not accepted");
    return;
  }
  const std::string key = Z85((*frames)[6]);
  if (!keys->second.contains(key)) {
    spdlog::warn("refused {} ({}): public key {} is not accepted", address, domain,
                 key.empty() ? "?" : key);
    reply(request_id, "400", "key not accepted");
    return;
  }
  spdlog::debug("accepted {} ({}) with key {}", address, domain, key);
  reply(request_id, "200", "OK", key);
}

}  // namespace evoslam
