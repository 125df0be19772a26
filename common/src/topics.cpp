#include "ubersim/topics.hpp"

#include <sstream>

namespace ubersim {
namespace {

template <class Msg>
std::string quoted(const Topic<Msg>& topic) {
  return "`" + std::string(topic.name) + "`";
}

template <class Msg>
TopicRow row(const Topic<Msg>& topic, std::vector<Role> publishers, std::vector<Role> readers,
             std::string rate) {
  return {std::string(topic.name), quoted(topic),      Msg::getTypeName(),
          std::move(publishers),   std::move(readers), std::move(rate)};
}

template <class Msg>
TopicRow team_row(const TeamTopic<Msg>& topic, std::vector<Role> publishers,
                  std::vector<Role> readers, std::string rate) {
  TopicRow result = row(topic.yellow, std::move(publishers), std::move(readers), std::move(rate));
  result.channels += ", " + quoted(topic.blue);
  return result;
}

std::string_view program_name(Program program) {
  switch (program) {
    case Program::Physics:
      return "physics";
    case Program::VisionEmulator:
      return "vision emulator";
    case Program::RadioEmulator:
      return "radio emulator";
    case Program::Referee:
      return "referee";
    case Program::GcLink:
      return "GC link";
    case Program::SslBridge:
      return "SSL bridge";
    case Program::Viewer:
      return "viewer";
    case Program::DemoTeam:
      return "team software (the demo team)";
    case Program::ReportRig:
      return "report rig";
  }
  return "?";
}

std::string roles_text(const std::vector<Role>& roles) {
  std::string text;
  for (const Role& role : roles) {
    if (!text.empty()) text += ", ";
    text += program_name(role.program);
    if (!role.note.empty()) text += " (" + std::string(role.note) + ")";
  }
  return text;
}

}  // namespace

std::string_view program_id(Program program) {
  switch (program) {
    case Program::Physics:
      return "physics";
    case Program::VisionEmulator:
      return "vision_emulator";
    case Program::RadioEmulator:
      return "radio_emulator";
    case Program::Referee:
      return "referee";
    case Program::GcLink:
      return "gc_link";
    case Program::SslBridge:
      return "ssl_bridge";
    case Program::Viewer:
      return "viewer";
    case Program::DemoTeam:
      return "demo_team";
    case Program::ReportRig:
      return "report";
  }
  return "?";
}

// Who publishes and reads each channel, and how often: the README's table.
// test_channel_wiring checks the programs named here against their code.
std::vector<TopicRow> topic_table() {
  using P = Program;
  return {
      row(topics::kVision,
          {{P::VisionEmulator, "or the real vision server"},
           {P::SslBridge, "onto an LCM team's private bus, on sim time"}},
          {{P::DemoTeam}, {P::SslBridge}, {P::Viewer}, {P::ReportRig}},
          "per camera, 30 Hz (paper profile)"),
      row(topics::kVisionGeometry,
          {{P::VisionEmulator, "or the real vision server"},
           {P::SslBridge, "onto an LCM team's private bus, on sim time"}},
          {{P::DemoTeam}, {P::SslBridge}, {P::Viewer}}, "on start, then low rate"),
      team_row(topics::kRadio,
               {{P::DemoTeam}, {P::SslBridge, "for SSL and grSim teams"}, {P::ReportRig}},
               {{P::RadioEmulator, "or the real radio server"},
                {P::Referee, "counts the teams' commands"},
                {P::SslBridge, "from an LCM team's private bus"},
                {P::Viewer}},
               "the team's control rate"),
      team_row(topics::kRadioFeedback,
               {{P::RadioEmulator}, {P::SslBridge, "onto an LCM team's private bus, on sim time"}},
               {{P::SslBridge}}, "feedback rate of the radio profile"),
      row(topics::kSimCommands, {{P::RadioEmulator}}, {{P::Physics}, {P::ReportRig}},
          "what gets through the radio"),
      row(topics::kSimState, {{P::Physics}},
          {{P::VisionEmulator},
           {P::RadioEmulator},
           {P::Referee},
           {P::GcLink},
           {P::SslBridge},
           {P::Viewer},
           {P::ReportRig}},
          "at the instants its readers ask for on `SIM_TRUTH_DEMAND` (about 45 Hz with the "
          "emulators; every step, 240 Hz, while nobody asks or with `--truth-every-step`)"),
      row(topics::kSimControl,
          {{P::Referee},
           {P::GcLink},
           {P::SslBridge, "a client's simulator control"},
           {P::Viewer},
           {P::VisionEmulator, "geometry requests"},
           {P::ReportRig}},
          {{P::Physics}, {P::VisionEmulator, "the robot types a `DEFINE_ROBOT_TYPE` defines"}},
          "on demand"),
      row(topics::kSimControlAck, {{P::Physics}},
          {{P::Referee}, {P::GcLink}, {P::SslBridge}, {P::Viewer}, {P::ReportRig}},
          "one per `SIM_CONTROL`"),
      row(topics::kSimGeometry, {{P::Physics}},
          {{P::VisionEmulator}, {P::Referee}, {P::GcLink}, {P::Viewer}},
          "on start, ~1 Hz, on request, after a SET_FIELD"),
      row(topics::kVisionSchedule, {{P::VisionEmulator}},
          {{P::Physics, "in sync mode"},
           {P::RadioEmulator, "in sync mode"},
           {P::SslBridge, "with team programs under the time shim"}},
          "per frame published in sync mode; 10 Hz in real time and when idle"),
      row(topics::kSyncClient,
          {{P::DemoTeam, "`--sync`"},
           {P::SslBridge,
            "`--sync`, for SSL teams; timed for the programs it runs under the time shim"}},
          {{P::RadioEmulator, "`--sync`"}}, "1 Hz"),
      row(topics::kSyncHorizon, {{P::RadioEmulator, "`--sync`"}}, {{P::Physics, "`--sync`"}},
          "per answer, 10 Hz when idle"),
      row(topics::kSyncStatus, {{P::RadioEmulator, "`--sync`"}}, {{P::Referee}},
          "at each dropped or rejoined client, 1 Hz"),
      row(topics::kReferee,
          {{P::Referee, "`ubersim_referee auto`"},
           {P::GcLink, "the official game controller in CI mode, docs/official_gc.md"},
           {P::SslBridge, "`--official-referee`: the official game controller in real time"}},
          {{P::DemoTeam}, {P::SslBridge}, {P::Physics, "`--sync-referee`"}, {P::Viewer}},
          "on each command or event, 10 Hz of sim time (after every state with `--sync`); the "
          "official game controller's rate when forwarded"),
      row(topics::kEmulatorRealism, {{P::SslBridge, "a client's realism config"}},
          {{P::VisionEmulator}, {P::RadioEmulator}}, "per change"),
      row(topics::kVisionCameras,
          {{P::SslBridge, "the camera calibrations of a client's geometry"}},
          {{P::VisionEmulator, "replaces its cameras, docs/vision.md"}}, "per change"),
      row(topics::kTruthDemand,
          {{P::VisionEmulator},
           {P::RadioEmulator},
           {P::Referee},
           {P::SslBridge},
           {P::Viewer},
           {P::ReportRig}},
          {{P::Physics}},
          "when it changes (vision: every 6 frames, its next 8 frames' release times), 1 Hz"),
  };
}

std::string topic_table_wiring() {
  std::ostringstream out;
  for (const TopicRow& r : topic_table()) {
    for (const Role& role : r.publishers) {
      out << r.base_name << " publishes " << program_id(role.program) << "\n";
    }
    for (const Role& role : r.readers) {
      out << r.base_name << " reads " << program_id(role.program) << "\n";
    }
  }
  return out.str();
}

std::string topic_table_markdown() {
  std::ostringstream out;
  out << "| channel | type | publisher | subscribers | rate |\n|---|---|---|---|---|\n";
  for (const TopicRow& r : topic_table()) {
    out << "| " << r.channels << " | `" << r.type << "` | " << roles_text(r.publishers) << " | "
        << roles_text(r.readers) << " | " << r.rate << " |\n";
  }
  return out.str();
}

}  // namespace ubersim
