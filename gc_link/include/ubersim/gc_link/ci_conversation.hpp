#pragma once
// One exchange with the game controller in CI mode, for one simulation state,
// such that the GC's answer depends only on what was sent, not on how its
// goroutines were scheduled. Pure: CiInputs out, CiOutputs in, no socket.
//
// Why it takes more than one message (ssl-game-controller at 78a9b3b,
// internal/app/ci and internal/app/engine): a CiInput's changes go into the
// engine's change queue and its timestamp into a tick channel; the engine's
// loop takes whichever is ready (Go's select picks at random when both are),
// and a tick can queue more work (accepting proposals, the auto-continue
// action on a third queue) that runs after the tick's own answer is out. Every
// processed change and every tick sends one CiOutput. So:
//
//   1. the tick alone (timestamp, tracker frame, geometry), sent while the GC
//      is idle: the first output to come is its answer;
//   2. a barrier: a SetStatusMessage change with a text of ours, sent after
//      that answer, so it queues behind whatever the tick queued; its output
//      (the Referee carries the text) comes after theirs;
//   3. a second barrier, for the auto-continue action, which the engine may
//      take after the first barrier and which queues its command only then;
//   4. only if there are any, our changes (game events, the operator's
//      commands) followed by a third barrier: the GC is idle again, so they
//      are processed in our order, and their consequences run inside them.
//
// After the last barrier's output the GC is idle and its Referee is settled.
#include <ssl_gc_ci.pb.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace ubersim::gc_link {

// The text of barrier number n in the Referee's status_message.
std::string barrier_text(std::uint64_t n);

class CiConversation {
 public:
  // tick: the CiInput with the timestamp (no api_inputs); changes: applied
  // after the tick has settled. barriers: the running count of barriers of
  // this link (each conversation takes the next numbers).
  CiConversation(CiInput tick, std::vector<Input> changes, std::uint64_t& barriers);

  // What to send now: the next CiInput, or nothing while an answer is awaited
  // (or when done).
  std::optional<CiInput> next_input();
  // A CiOutput arrived (any; those the conversation does not wait for are
  // counted and their Referee kept as the latest).
  void on_output(const CiOutput& output);

  bool done() const { return step_ == Step::Done; }
  bool awaiting() const { return waiting_; }
  // The GC's last Referee; once done(), its settled state for this tick.
  const Referee& referee() const { return referee_; }
  int outputs() const { return outputs_; }

 private:
  enum class Step { Tick, Barrier1, Barrier2, Changes, Done };
  CiInput barrier_input(std::vector<Input> before);
  void advance();

  CiInput tick_;
  std::vector<Input> changes_;
  std::uint64_t& barriers_;
  Step step_ = Step::Tick;
  bool waiting_ = false;
  std::string awaited_text_;  // empty: any output answers
  Referee referee_;
  int outputs_ = 0;
};

}  // namespace ubersim::gc_link
