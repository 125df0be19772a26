#include "cdp_client.hpp"

#include <unistd.h>

#include <chrono>
#include <condition_variable>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <websocketpp/client.hpp>
#include <websocketpp/config/asio_no_tls_client.hpp>

namespace viewer_test {

using Client = websocketpp::client<websocketpp::config::asio_client>;

std::string find_chromium() {
  if (const char* configured = std::getenv("UBERSIM_CHROMIUM")) return configured;
  for (const char* path : {"/usr/bin/chromium", "/usr/bin/chromium-browser"}) {
    if (::access(path, X_OK) == 0) return path;
  }
  return "";
}

// One WebSocket to the browser; replies are matched to requests by id.
class CdpConnection {
 public:
  explicit CdpConnection(const std::string& url) {
    client_.clear_access_channels(websocketpp::log::alevel::all);
    client_.clear_error_channels(websocketpp::log::elevel::all);
    client_.init_asio();
    client_.set_open_handler([this](const websocketpp::connection_hdl&) {
      std::lock_guard<std::mutex> lock(mutex_);
      open_ = true;
      changed_.notify_all();
    });
    client_.set_fail_handler([this](const websocketpp::connection_hdl&) {
      std::lock_guard<std::mutex> lock(mutex_);
      failed_ = true;
      changed_.notify_all();
    });
    client_.set_close_handler([this](const websocketpp::connection_hdl&) {
      std::lock_guard<std::mutex> lock(mutex_);
      failed_ = true;
      changed_.notify_all();
    });
    client_.set_message_handler([this](const websocketpp::connection_hdl&,
                                       const Client::message_ptr& message) {
      auto reply = nlohmann::json::parse(message->get_payload(), nullptr, false);
      // Events carry no id; replies to our requests carry the request's.
      if (reply.is_discarded() || !reply.contains("id") || !reply["id"].is_number_integer()) return;
      const int id = reply["id"].get<int>();  // before the move: json's operator= takes by value
      std::lock_guard<std::mutex> lock(mutex_);
      replies_[id] = std::move(reply);
      changed_.notify_all();
    });
    websocketpp::lib::error_code error;
    auto connection = client_.get_connection(url, error);
    if (error) throw std::runtime_error("DevTools URL " + url + ": " + error.message());
    handle_ = connection->get_handle();
    client_.connect(connection);
    thread_ = std::thread([this] { client_.run(); });
    std::unique_lock<std::mutex> lock(mutex_);
    if (!changed_.wait_for(lock, std::chrono::seconds(10), [this] { return open_ || failed_; }) ||
        failed_) {
      lock.unlock();
      stop();
      throw std::runtime_error("cannot connect to DevTools at " + url);
    }
  }
  ~CdpConnection() { stop(); }

  nlohmann::json call(const std::string& method, const nlohmann::json& params,
                      const std::string& session_id) {
    int id = 0;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      id = ++last_id_;
    }
    nlohmann::json request = {{"id", id}, {"method", method}, {"params", params}};
    if (!session_id.empty()) request["sessionId"] = session_id;
    websocketpp::lib::error_code error;
    client_.send(handle_, request.dump(), websocketpp::frame::opcode::text, error);
    if (error) throw std::runtime_error(method + ": send failed: " + error.message());
    std::unique_lock<std::mutex> lock(mutex_);
    if (!changed_.wait_for(lock, std::chrono::seconds(20),
                           [&] { return replies_.count(id) > 0 || failed_; }) ||
        replies_.count(id) == 0) {
      throw std::runtime_error(method + ": no reply from the browser");
    }
    nlohmann::json reply = std::move(replies_[id]);
    replies_.erase(id);
    if (reply.contains("error")) throw std::runtime_error(method + ": " + reply["error"].dump());
    return reply["result"];
  }

 private:
  void stop() {
    websocketpp::lib::error_code ignored;
    client_.close(handle_, websocketpp::close::status::going_away, "", ignored);
    client_.stop();
    if (thread_.joinable()) thread_.join();
  }

  Client client_;
  websocketpp::connection_hdl handle_;
  std::thread thread_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::map<int, nlohmann::json> replies_;
  int last_id_ = 0;
  bool open_ = false;
  bool failed_ = false;
};

namespace {

// Chromium writes its DevTools port and browser path into this file once it listens.
std::string wait_for_devtools_url(const std::filesystem::path& profile,
                                  ubersim::test::ChildProcess& process) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (std::chrono::steady_clock::now() < deadline) {
    std::ifstream file(profile / "DevToolsActivePort");
    std::string port, path;
    if (std::getline(file, port) && std::getline(file, path) && !port.empty() && !path.empty()) {
      return std::string("ws://127.0.0.1:").append(port).append(path);
    }
    if (!process.running()) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  throw std::runtime_error("chromium offered no DevTools endpoint: " + process.log());
}

}  // namespace

HeadlessChromium::HeadlessChromium(const std::string& chromium, const std::string& work_dir) {
  const std::filesystem::path profile = std::filesystem::path(work_dir) / "chromium-profile";
  std::filesystem::create_directories(profile);
  process_ = std::make_unique<ubersim::test::ChildProcess>(
      // Under timeout(1): should this test crash, its browser still ends soon after.
      std::vector<std::string>{"/usr/bin/timeout", "--kill-after=5", "170", chromium, "--headless",
                               "--no-sandbox", "--disable-gpu", "--disable-background-networking",
                               "--disable-component-update", "--disable-sync", "--no-first-run",
                               "--disable-extensions", "--mute-audio", "--disable-crash-reporter",
                               "--window-size=1280,800", "--remote-debugging-port=0",
                               "--remote-debugging-address=127.0.0.1",
                               "--user-data-dir=" + profile.string(), "about:blank"},
      (std::filesystem::path(work_dir) / "chromium.log").string());
  connection_ = std::make_unique<CdpConnection>(wait_for_devtools_url(profile, *process_));
}

HeadlessChromium::~HeadlessChromium() {
  connection_.reset();
  process_->stop(5);
}

nlohmann::json HeadlessChromium::call(const std::string& method, const nlohmann::json& params,
                                      bool in_page) {
  return connection_->call(method, params, in_page ? session_id_ : "");
}

void HeadlessChromium::open(const std::string& url) {
  const auto target = call("Target.createTarget", {{"url", url}}, false);
  const auto attached =
      call("Target.attachToTarget", {{"targetId", target["targetId"]}, {"flatten", true}}, false);
  session_id_ = attached["sessionId"].get<std::string>();
}

nlohmann::json HeadlessChromium::evaluate(const std::string& expression) {
  const auto result =
      call("Runtime.evaluate", {{"expression", expression}, {"returnByValue", true}});
  if (result.contains("exceptionDetails")) {
    throw std::runtime_error("page threw on `" + expression +
                             "`: " + result["exceptionDetails"].dump());
  }
  const auto& value = result["result"];
  return value.contains("value") ? value["value"] : nlohmann::json();
}

void HeadlessChromium::mouse(const std::string& type, double x, double y) {
  nlohmann::json params = {{"type", type}, {"x", x}, {"y", y}, {"button", "left"}};
  if (type != "mouseMoved") params["clickCount"] = 1;
  params["buttons"] = type == "mouseReleased" ? 0 : 1;
  call("Input.dispatchMouseEvent", params);
}

void HeadlessChromium::click(double x, double y) {
  mouse("mousePressed", x, y);
  mouse("mouseReleased", x, y);
}

std::string HeadlessChromium::screenshot_png() {
  return base64_decode(call("Page.captureScreenshot", {{"format", "png"}})["data"]);
}

std::string base64_decode(const std::string& text) {
  static const std::string alphabet =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  unsigned bits = 0;
  int count = 0;
  for (char c : text) {
    const auto index = alphabet.find(c);
    if (index == std::string::npos) continue;  // padding, line breaks
    bits = (bits << 6) | static_cast<unsigned>(index);
    count += 6;
    if (count >= 8) {
      count -= 8;
      out.push_back(static_cast<char>((bits >> count) & 0xFF));
    }
  }
  return out;
}

}  // namespace viewer_test
