#pragma once
// The CPU time physics spends stepping in real time (its log's "stepping
// took", which ubersim_truth_bench compares against stepping alone). Read per
// run of steps, not per step: in real time physics runs the steps up to the
// next wanted state at once, and the thread's CPU clock is a system call (no
// vDSO for it), two per step were about 480 a second of sim time.
namespace ubersim::physics {

class SteppingClock {
 public:
  // Before a step: opens a run unless one is open.
  void step_begins();
  // When anything but stepping comes next (publishing, waiting): closes the run.
  void run_ends();
  double seconds() const { return seconds_; }

 private:
  double run_start_ = 0;
  bool in_run_ = false;
  double seconds_ = 0;
};

}  // namespace ubersim::physics
