// ubersim_viewer: the live field viewer. Subscribes to ground truth, vision,
// field geometry, both teams' radio commands and the referee, and serves a web page that
// draws them, pushing it one snapshot per display frame over a WebSocket. The
// page's controls (pause, speed, reset, drag to place) go out on SIM_CONTROL.
// See docs/viewer.md; its shell (ViewerShell) is viewer_shell.cpp.
#include <CLI/CLI.hpp>

#include "ubersim/cli.hpp"
#include "ubersim/logging.hpp"
#include "ubersim/process_main.hpp"
#include "viewer_shell.hpp"

namespace {

int parse_and_run(int argc, char** argv) {
  ubersim::viewer::ViewerOptions options;
  CLI::App app{"ubersim viewer: the field, ground truth, vision and commands in a web browser"};
  ubersim::add_common_options(app, options.common);
  app.add_option("--port", options.port, "HTTP/WebSocket port (0 = any free port)")
      ->check(ubersim::in_range(0, 65535))
      ->capture_default_str();
  app.add_option("--bind", options.bind,
                 "address to listen on (0.0.0.0 lets other machines in: there is no password)")
      ->capture_default_str();
  app.add_option("--display-rate", options.display_rate,
                 "snapshots per second sent to each page (messages are coalesced to this)")
      ->check(ubersim::in_range(1.0, 240.0))
      ->capture_default_str();
  app.add_option("--web-dir", options.web_dir, "folder of the page's files")->capture_default_str();
  app.add_option(
      "--allow-origin", options.allowed_origins,
      "let pages of this other origin (e.g. http://example.org:8000, or * for any) open "
      "the WebSocket and send control requests; by default only the viewer's own page may");
  app.add_option("--max-pages", options.max_pages, "pages (WebSocket connections) open at once")
      ->check(ubersim::in_range(1, 1024))
      ->capture_default_str();
  if (const auto stop = ubersim::parse_command_line(app, argc, argv)) return *stop;

  ubersim::setup_logging("viewer", options.common.verbosity());
  return ubersim::viewer::run_viewer(options);
}

}  // namespace

int main(int argc, char** argv) {
  return ubersim::run_main("ubersim_viewer", [&] { return parse_and_run(argc, argv); });
}
