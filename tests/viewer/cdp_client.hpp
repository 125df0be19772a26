#pragma once
// Just enough of the Chrome DevTools Protocol to drive a headless Chromium
// from a test: start it, open a page, evaluate JavaScript, send mouse events,
// take a screenshot. Commands are synchronous; events are ignored.
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "child_process.hpp"

namespace viewer_test {

// Debian's chromium, or $UBERSIM_CHROMIUM; "" when there is none.
std::string find_chromium();

class CdpConnection;

class HeadlessChromium {
 public:
  // Starts the browser with its own profile folder under `work_dir`; throws
  // std::runtime_error when it does not offer its DevTools endpoint in time.
  HeadlessChromium(const std::string& chromium, const std::string& work_dir);
  ~HeadlessChromium();
  HeadlessChromium(const HeadlessChromium&) = delete;
  HeadlessChromium& operator=(const HeadlessChromium&) = delete;

  // Opens `url` in a new tab; later calls act on that tab.
  void open(const std::string& url);
  // Evaluates an expression in the page; returns its value (JSON-serialisable values only).
  nlohmann::json evaluate(const std::string& expression);
  // Mouse events in viewport CSS pixels: "mousePressed", "mouseMoved", "mouseReleased".
  void mouse(const std::string& type, double x, double y);
  void click(double x, double y);
  // A PNG of the tab.
  std::string screenshot_png();
  std::string log() const { return process_->log(); }

 private:
  nlohmann::json call(const std::string& method, const nlohmann::json& params, bool in_page = true);

  std::unique_ptr<ubersim::test::ChildProcess> process_;
  std::unique_ptr<CdpConnection> connection_;
  std::string session_id_;
};

std::string base64_decode(const std::string& text);

}  // namespace viewer_test
