#pragma once
// The TCP side of the CI port: connect (retrying while the GC starts), send a
// CiInput, read CiOutputs. Every wait has a limit, so a GC that died or hangs
// is a clear error, never a stall.
#include <ssl_gc_ci.pb.h>

#include <chrono>
#include <stdexcept>
#include <string>

#include "ubersim/gc_link/ci_conversation.hpp"
#include "ubersim/gc_link/ci_framing.hpp"

namespace ubersim::gc_link {

class CiError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class CiClient {
 public:
  // "HOST:PORT" (an IPv4 address or localhost); retries until `timeout`.
  CiClient(const std::string& address, std::chrono::milliseconds timeout);
  ~CiClient();
  CiClient(const CiClient&) = delete;
  CiClient& operator=(const CiClient&) = delete;

  void send(const CiInput& input);
  // The next CiOutput; throws CiError after `timeout` without one, or when the
  // GC closed the connection or sent bytes that are not a CiOutput.
  CiOutput receive(std::chrono::milliseconds timeout);
  // Holds the conversation to its end.
  void run(CiConversation& conversation, std::chrono::milliseconds timeout);

 private:
  int fd_ = -1;
  FrameReader reader_;
};

}  // namespace ubersim::gc_link
