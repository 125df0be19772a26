#include "ubersim/gc_link/ci_conversation.hpp"

namespace ubersim::gc_link {

std::string barrier_text(std::uint64_t n) {
  return "ubersim sync " + std::to_string(n);
}

CiConversation::CiConversation(CiInput tick, std::vector<Input> changes, std::uint64_t& barriers)
    : tick_(std::move(tick)), changes_(std::move(changes)), barriers_(barriers) {}

CiInput CiConversation::barrier_input(std::vector<Input> before) {
  CiInput input;
  for (Input& change : before) *input.add_api_inputs() = std::move(change);
  awaited_text_ = barrier_text(++barriers_);
  Change* barrier = input.add_api_inputs()->mutable_change();
  barrier->set_origin("ubersim");
  barrier->mutable_set_status_message_change()->set_status_message(awaited_text_);
  return input;
}

std::optional<CiInput> CiConversation::next_input() {
  if (waiting_ || step_ == Step::Done) return std::nullopt;
  waiting_ = true;
  switch (step_) {
    case Step::Tick:
      awaited_text_.clear();
      return tick_;
    case Step::Barrier1:
    case Step::Barrier2:
      return barrier_input({});
    case Step::Changes:
      return barrier_input(std::move(changes_));
    case Step::Done:
      break;
  }
  return std::nullopt;
}

void CiConversation::on_output(const CiOutput& output) {
  ++outputs_;
  if (output.has_referee_msg()) referee_ = output.referee_msg();
  if (!waiting_) return;
  if (!awaited_text_.empty() &&
      !(output.has_referee_msg() && output.referee_msg().status_message() == awaited_text_)) {
    return;  // an output of work queued before the barrier
  }
  waiting_ = false;
  advance();
}

void CiConversation::advance() {
  switch (step_) {
    case Step::Tick:
      step_ = Step::Barrier1;
      break;
    case Step::Barrier1:
      step_ = Step::Barrier2;
      break;
    case Step::Barrier2:
      step_ = changes_.empty() ? Step::Done : Step::Changes;
      break;
    case Step::Changes:
    case Step::Done:
      step_ = Step::Done;
      break;
  }
}

}  // namespace ubersim::gc_link
