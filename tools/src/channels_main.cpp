// ubersim_channels: the LCM channels ubersim uses, printed from the typed
// topics (common/include/ubersim/topics.hpp): with --markdown the table the
// README holds, otherwise one line per channel: name and message type.
#include <CLI/CLI.hpp>
#include <cstdio>

#include "ubersim/cli.hpp"
#include "ubersim/dds_bridge/bridged_topics.hpp"
#include "ubersim/process_main.hpp"
#include "ubersim/topics.hpp"

namespace {

// The DDS bridge carries whichever of its channels its routes name, either
// way, so it has no row entries of its own: one sentence under the table.
std::string dds_bridge_paragraph() {
  std::string names;
  ubersim::dds::for_each_bridged_topic([&](const auto& topic) {
    names += (names.empty() ? "`" : ", `") + std::string(topic.name) + "`";
  });
  return "\nThe DDS bridge (`ubersim_dds_bridge`, docs/dds_bridge.md) carries " + names +
         " between LCM and DDS, each the way its routes say.\n";
}

int parse_and_run(int argc, char** argv) {
  bool markdown = false;
  bool wiring = false;
  CLI::App app{"ubersim channels: every LCM channel, its message type, who publishes and reads it"};
  app.add_flag("--markdown", markdown, "print the README's channel table (Markdown)");
  app.add_flag("--wiring", wiring,
               "print one line per channel, direction and program (test_channel_wiring)");
  if (const auto stop = ubersim::parse_command_line(app, argc, argv)) return *stop;
  if (markdown) {
    std::fputs(ubersim::topic_table_markdown().c_str(), stdout);
    std::fputs(dds_bridge_paragraph().c_str(), stdout);
    return 0;
  }
  if (wiring) {
    std::fputs(ubersim::topic_table_wiring().c_str(), stdout);
    return 0;
  }
  for (const ubersim::TopicRow& row : ubersim::topic_table()) {
    std::printf("%-50s %s\n", row.channels.c_str(), row.type.c_str());
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return ubersim::run_main("ubersim_channels", [&] { return parse_and_run(argc, argv); });
}
