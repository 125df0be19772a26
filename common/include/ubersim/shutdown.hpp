#pragma once
// Clean shutdown on SIGINT/SIGTERM. One ShutdownSignal per process: while it
// lives, the signals set a flag and make fd() readable, so a loop blocked in
// poll() on its LCM socket wakes at once instead of at its next timeout.
namespace ubersim {

class ShutdownSignal {
 public:
  ShutdownSignal();   // installs the handlers; throws if one already exists
  ~ShutdownSignal();  // restores the previous handlers
  ShutdownSignal(const ShutdownSignal&) = delete;
  ShutdownSignal& operator=(const ShutdownSignal&) = delete;

  bool requested() const;
  int fd() const;  // readable once a signal arrived
  int signal_number() const;
  void request();  // as if a signal had arrived (for tests and fatal errors)
};

}  // namespace ubersim
