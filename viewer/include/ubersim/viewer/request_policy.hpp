#pragma once
// What the viewer's server lets in, as plain functions of the request's text
// (no sockets): which file a path names, whether a WebSocket handshake may
// open a page, how deep a page's JSON may nest. WebServer applies them; the
// fuzz targets (fuzz/) drive them through the same websocketpp pipeline.
#include <cstddef>
#include <string>
#include <vector>

namespace ubersim::viewer {

// Pages (WebSocket connections) open at once; a handshake beyond it is refused
// with 503. Each costs at most a 64 KB inbound message and max_buffered_bytes
// outbound, so the limit bounds the memory pages can take.
inline constexpr std::size_t kDefaultMaxPages = 16;
// Largest text message a page may send (control requests are ~100 bytes).
inline constexpr std::size_t kMaxPageMessageBytes = std::size_t{64} * 1024;
// HTTP requests carry no body we use; websocketpp would buffer 32 MB by default.
inline constexpr std::size_t kMaxHttpBodyBytes = 4096;
// Control requests are flat JSON objects; deeper nesting is refused unparsed.
inline constexpr int kMaxJsonDepth = 4;

struct HandshakeDecision {
  bool accept = false;
  int status = 0;      // HTTP status when refused (403, 503)
  std::string reason;  // for the log
};

// Whether a WebSocket handshake may open a page. `origin` is the Origin header
// ("" when absent: not a browser, e.g. a script on this host), `host` the Host
// header. Browsers send Origin, so a page of another site is refused unless
// `allowed_origins` names its origin (or holds "*"). A same-origin request
// from a loopback-bound server must also name a loopback host, so a site that
// points its own DNS name at 127.0.0.1 (DNS rebinding) is refused too.
HandshakeDecision decide_handshake(const std::string& origin, const std::string& host,
                                   bool loopback_bound,
                                   const std::vector<std::string>& allowed_origins,
                                   std::size_t open_pages, std::size_t max_pages);

// True when `text` nests JSON arrays/objects no deeper than max_depth (strings
// and their escapes skipped); a cheap scan before any parse.
bool json_depth_within(const std::string& text, int max_depth);

// Content type for a served file name ("index.html" -> "text/html; charset=utf-8").
std::string content_type_for(const std::string& file_name);
// The file a request path names inside the web folder, or "" when it names none
// we serve ("/" -> "index.html"; no folders, no "..", query strings ignored).
std::string served_file_name(const std::string& request_path);

}  // namespace ubersim::viewer
