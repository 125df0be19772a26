#include "ubersim/topics.hpp"

#include <sstream>

namespace ubersim {
namespace {

template <class Msg>
std::string quoted(const Topic<Msg>& topic) {
  return "`" + std::string(topic.name) + "`";
}

template <class Msg>
TopicRow row(const Topic<Msg>& topic, std::string publishers, std::string subscribers,
             std::string rate) {
  return {quoted(topic), Msg::getTypeName(), std::move(publishers), std::move(subscribers),
          std::move(rate)};
}

template <class Msg>
TopicRow team_row(const TeamTopic<Msg>& topic, std::string publishers, std::string subscribers,
                  std::string rate) {
  TopicRow result =
      row(topic.yellow, std::move(publishers), std::move(subscribers), std::move(rate));
  result.channels += ", " + quoted(topic.blue);
  return result;
}

}  // namespace

// Who publishes and reads each channel, and how often: the README's table.
std::vector<TopicRow> topic_table() {
  return {
      row(topics::kVision, "vision emulator (or the real vision server)", "control software",
          "per camera, 30 Hz (paper profile)"),
      row(topics::kVisionGeometry, "vision emulator (or the real vision server)",
          "control software", "on start, then low rate"),
      team_row(topics::kRadio, "control software", "radio emulator (or the real radio server)",
               "the team's control rate"),
      team_row(topics::kRadioFeedback, "radio emulator", "control software",
               "feedback rate of the radio profile"),
      row(topics::kSimCommands, "radio emulator", "physics", "what gets through the radio"),
      row(topics::kSimState, "physics",
          "emulators, referee, GC link, viewer, SSL and DDS bridges, tools",
          "at the instants its readers ask for on `SIM_TRUTH_DEMAND` (about 45 Hz with the "
          "emulators; every step, 240 Hz, while nobody asks or with `--truth-every-step`)"),
      row(topics::kSimControl,
          "referee, GC link, SSL bridge (a client's simulator control), viewer, vision emulator "
          "and DDS bridge (geometry requests), tools",
          "physics; vision emulator (the robot types a `DEFINE_ROBOT_TYPE` defines)", "on demand"),
      row(topics::kSimControlAck, "physics", "referee, GC link, SSL bridge, viewer, tools",
          "one per `SIM_CONTROL`"),
      row(topics::kSimGeometry, "physics", "vision emulator, referee, GC link, viewer, tools",
          "on start, ~1 Hz, on request, after a SET_FIELD"),
      row(topics::kVisionSchedule, "vision emulator", "radio emulator and physics in sync mode",
          "per frame published in sync mode; 10 Hz in real time and when idle"),
      row(topics::kSyncClient,
          "sync clients (team programs, `--sync`; the SSL bridge `--sync` for SSL teams)",
          "radio emulator `--sync`", "1 Hz"),
      row(topics::kSyncHorizon, "radio emulator `--sync`", "physics `--sync`",
          "per answer, 10 Hz when idle"),
      row(topics::kSyncStatus, "radio emulator `--sync`", "automatic referee, tools",
          "at each dropped or rejoined client, 1 Hz"),
      row(topics::kReferee,
          "automatic referee (`ubersim_referee auto`), the official game controller through "
          "`ubersim_gc_link` (CI mode, docs/official_gc.md), or the SSL bridge "
          "`--official-referee` forwarding the official game controller in real time",
          "control software, SSL bridge, physics `--sync-referee`",
          "on each command or event, 10 Hz of sim time (after every state with `--sync`); the "
          "official game controller's rate when forwarded"),
      row(topics::kEmulatorRealism, "SSL bridge (a client's realism config), tools",
          "vision and radio emulators", "per change"),
      row(topics::kVisionCameras,
          "SSL bridge (the camera calibrations of a client's geometry), tools",
          "vision emulator (replaces its cameras, docs/vision.md)", "per change"),
      row(topics::kTruthDemand, "every reader of `SIM_STATE` (emulators, viewer, bridges, report)",
          "physics",
          "when it changes (vision: every 6 frames, its next 8 frames' release times), 1 Hz"),
  };
}

std::string topic_table_markdown() {
  std::ostringstream out;
  out << "| channel | type | publisher | subscribers | rate |\n|---|---|---|---|---|\n";
  for (const TopicRow& r : topic_table()) {
    out << "| " << r.channels << " | `" << r.type << "` | " << r.publishers << " | "
        << r.subscribers << " | " << r.rate << " |\n";
  }
  return out.str();
}

}  // namespace ubersim
