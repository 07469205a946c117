#pragma once
/// The HTTP server behind `tcbench view` and `tcbench live`: cpp-httplib
/// (Debian's libcpp-httplib-dev), listening on 127.0.0.1 only, serving the
/// browser page from the viewer directory (viewer/ in the source tree, with
/// three.js installed into viewer/node_modules by scripts/setup) and whatever
/// routes the command adds. Nothing is fetched from anywhere else.
///
/// Why cpp-httplib: one header and a small library in Debian, plain request
/// handlers, and chunked responses for server-sent events, which is all the
/// live mode needs (frames go one way; the mouse comes back as small POSTs).
/// Boost.Beast would need an async WebSocket stack for the same job.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>

namespace httplib {
class Server;
}

namespace tcb {

/// The viewer page's directory: `override_dir` when given, else viewer/ in
/// the source tree. InputError (exit 2) when it has no index.html or three.js
/// is not installed in it (naming scripts/setup).
std::filesystem::path viewer_directory(const std::filesystem::path& override_dir = {});

/// Serves `viewer_dir` at / on 127.0.0.1:`port` (0: a free port), with the
/// routes `add_routes` registers, until SIGINT or SIGTERM arrives or
/// `finished` (polled ten times a second) says so. Prints the address to
/// stdout once listening (tests read it). `on_listening` runs once the port
/// is bound (a live simulation starts there), `on_stop` when stopping, before
/// the server closes. InputError when the port is outside 0..65535 or cannot
/// be bound (nothing has started then). Returns 0 after a clean stop.
struct ServerHooks {
  std::function<void()> on_listening;
  std::function<void()> on_stop;
  std::function<bool()> finished;
};
int serve_locally(const std::filesystem::path& viewer_dir, int port, const std::string& what,
                  const std::function<void(httplib::Server&)>& add_routes, const ServerHooks& hooks = {});

/// The content type the page's files need (module scripts must be served as
/// JavaScript, or the browser refuses them).
std::string content_type_for(const std::filesystem::path& file);

}  // namespace tcb
