#pragma once
// ubersim_viewer's shell (docs/design.md, "One shape for every program"): the
// ViewerModel and the WebServer on the process host. The command line
// (main.cpp) fills the options.
#include <string>
#include <vector>

#include "ubersim/common_options.hpp"
#include "ubersim/viewer/web_server.hpp"

#ifndef UBERSIM_VIEWER_WEB_DIR
#error "UBERSIM_VIEWER_WEB_DIR must name the page's folder"
#endif

namespace ubersim::viewer {

struct ViewerOptions {
  CommonOptions common;
  std::string bind = "127.0.0.1";
  int port = 8080;
  double display_rate = 60;
  std::string web_dir = UBERSIM_VIEWER_WEB_DIR;
  std::vector<std::string> allowed_origins;
  int max_pages = static_cast<int>(kDefaultMaxPages);
};

// Serves the page until SIGINT/SIGTERM (0). Throws std::runtime_error when
// the port cannot be opened or LCM fails.
int run_viewer(const ViewerOptions& options);

}  // namespace ubersim::viewer
