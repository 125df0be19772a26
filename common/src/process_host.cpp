#include "ubersim/process_host.hpp"

#include <algorithm>

#include "ubersim/common_options.hpp"

namespace ubersim {

ProcessHost::ProcessHost(const std::string& lcm_url, ChannelNames channels, std::string name)
    : bus_(lcm_url), channels_(std::move(channels)), name_(std::move(name)) {}

ProcessHost::ProcessHost(const CommonOptions& common, std::string name)
    : ProcessHost(with_receive_buffer(common.lcm_url), common.channels(), std::move(name)) {}

void ProcessHost::Timer::run(Clock::time_point now) {
  tick_(now);
  if (rate_ == Rate::FixedRate) {
    due_ += period_;
    if (due_ < now) due_ = now + period_;  // fell behind: skip, do not catch up
  } else {
    due_ = now + period_;
  }
}

ProcessHost::Timer& ProcessHost::every(Clock::duration period, Tick tick, Timer::Rate rate) {
  timers_.push_back(
      std::unique_ptr<Timer>(new Timer(period, rate, std::move(tick), now() + period)));
  return *timers_.back();
}

void ProcessHost::after_wake(Tick hook) {
  hooks_.push_back(std::move(hook));
}

void ProcessHost::at_stop(std::function<void()> hook) {
  stop_hooks_.push_back(std::move(hook));
}

void ProcessHost::ask_for_truth(TruthDemandAnnouncer::Source demand) {
  if (!truth_demand_) {
    truth_demand_ = std::make_unique<TruthDemandAnnouncer>(bus_, channels_, name_);
    hooks_.push_back([this](Clock::time_point now) { truth_demand_->tick(now); });
  }
  truth_demand_->ask(std::move(demand));
}

void ProcessHost::ask_for_truth(const truth_demand_t& fixed) {
  ask_for_truth([fixed] { return fixed; });
}

void ProcessHost::send_truth_demand(Clock::time_point now) {
  if (truth_demand_) truth_demand_->send_now(now);
}

void ProcessHost::renew_truth_demand(Clock::time_point now) {
  if (truth_demand_) truth_demand_->tick(now);
}

void ProcessHost::stop(int status) {
  if (!stop_status_) stop_status_ = status;
}

void ProcessHost::run_hooks(Clock::time_point now) {
  for (const Tick& hook : hooks_) hook(now);
}

void ProcessHost::run_due_timers(Clock::time_point now) {
  // By index: a timer's tick may add another timer.
  for (std::size_t i = 0; i < timers_.size(); ++i) {
    if (now >= timers_[i]->due()) timers_[i]->run(now);
  }
}

ProcessHost::Clock::time_point ProcessHost::next_timer(Clock::time_point otherwise) const {
  Clock::time_point next = otherwise;
  for (const auto& timer : timers_) next = std::min(next, timer->due());
  return next;
}

bool ProcessHost::carry_out(const Turn& turn) {
  switch (turn.kind) {
    case Turn::Kind::Again:
      return true;
    case Turn::Kind::Finish:
      return false;
    case Turn::Kind::Poll:
      bus_.handle_pending();
      return true;
    case Turn::Kind::PollThenWait:
      // What already waits may be what the policy waits for: no sleep then.
      if (bus_.handle_pending() > 0) return true;
      [[fallthrough]];
    case Turn::Kind::Wait:
      bus_.wait_until_and_handle(next_timer(turn.until), &shutdown_);
      return true;
  }
  return true;
}

int ProcessHost::run(Pacing& pacing) {
  bool hooks_due = true;  // before the first wait, then after every wakeup
  while (!stopping()) {
    const Clock::time_point now = this->now();
    if (hooks_due) run_hooks(now);
    run_due_timers(now);
    if (stopping()) break;
    const Turn turn = pacing.turn(now);
    if (stopping() || !carry_out(turn)) break;
    hooks_due = turn.kind != Turn::Kind::Again;
  }
  for (const auto& hook : stop_hooks_) hook();
  return stop_status_.value_or(0);
}

int ProcessHost::run(Clock::duration max_wait) {
  WaitForMessages pacing(max_wait);
  return run(pacing);
}

}  // namespace ubersim
