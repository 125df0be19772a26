#pragma once
// How far physics may run ahead of the vision emulator as fast as possible
// (--speed 0 outside sync mode; docs/vision.md, "As fast as possible"). The
// vision emulator acknowledges its progress with the t_state of its
// SIM_VISION_SCHEDULE; physics never starts a step more than kVisionLead of
// sim time after the last state acknowledged, so what waits in the vision's
// socket stays far below its receive buffer and no state (no frame) is lost.
#include <chrono>

namespace ubersim {

// s of sim time: about 24 states of 240 Hz, 0.1 MB of 2 x 11 ground truth,
// at 100 x real time 1 ms of wall time for the vision to catch up.
inline constexpr double kVisionLead = 0.1;
// s of sim time: the vision acknowledges a state at least this long after the
// last one it acknowledged (it says more with its frames), so a lead of
// kVisionLead always has an acknowledgement on its way.
inline constexpr double kVisionAckInterval = kVisionLead / 4;
// Wall time without a schedule after which physics stops waiting for a vision
// emulator (gone, or stopped), as it forgets a silent truth consumer.
inline constexpr std::chrono::seconds kVisionSilence{3};

}  // namespace ubersim
