#include "ubersim/ssl_bridge/sync_answers.hpp"

namespace ubersim::ssl {

bool SyncAnswers::on_frame(double t_capture, Clock::time_point now) {
  if (!registered_) return false;
  if (owed_.size() >= kMaxOwed) {
    ++stats_.overflows;
    leave();
    return true;
  }
  owed_.push_back({t_capture, now});
  ++stats_.frames;
  return false;
}

SyncAnswers::Datagram SyncAnswers::on_datagram() {
  Datagram result;
  if (!registered_) {
    registered_ = true;
    result.kind = Kind::Registered;
    return result;
  }
  if (owed_.empty()) {
    ++stats_.extra;
    result.kind = Kind::Extra;
    return result;
  }
  result.kind = Kind::Answer;
  result.t_capture = owed_.front().t_capture;
  owed_.pop_front();
  ++stats_.answers;
  return result;
}

bool SyncAnswers::expire(Clock::time_point now) {
  if (!registered_ || owed_.empty()) return false;
  if (std::chrono::duration<double>(now - owed_.front().sent).count() <= timeout_) return false;
  ++stats_.timeouts;
  leave();
  return true;
}

void SyncAnswers::leave() {
  registered_ = false;
  owed_.clear();
}

}  // namespace ubersim::ssl
