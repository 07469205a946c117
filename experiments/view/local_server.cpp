#include "experiments/view/local_server.hpp"

#include <httplib.h>
#include <pthread.h>
#include <signal.h>
#include <sys/socket.h>

#include <atomic>
#include <chrono>
#include <ctime>
#include <iostream>
#include <thread>

#include "experiments/run/provenance.hpp"
#include "sim/io/input_error.hpp"

namespace tcb {

std::filesystem::path viewer_directory(const std::filesystem::path& override_dir) {
  const std::filesystem::path dir = override_dir.empty() ? source_tree_dir() / "viewer" : override_dir;
  if (!std::filesystem::is_regular_file(dir / "index.html"))
    throw InputError(dir.string(), 0, "not a viewer directory (no index.html); --viewer DIR names another");
  if (!std::filesystem::is_regular_file(dir / "node_modules" / "three" / "build" / "three.module.js"))
    throw InputError(dir.string(), 0,
                     "three.js is not installed in node_modules (scripts/setup runs `npm ci` there)");
  return dir;
}

std::string content_type_for(const std::filesystem::path& file) {
  const std::string ext = file.extension().string();
  if (ext == ".html") return "text/html; charset=utf-8";
  if (ext == ".js" || ext == ".mjs") return "text/javascript; charset=utf-8";
  if (ext == ".json") return "application/json";
  if (ext == ".css") return "text/css; charset=utf-8";
  if (ext == ".csv") return "text/csv; charset=utf-8";
  if (ext == ".png") return "image/png";
  return "application/octet-stream";
}

int serve_locally(const std::filesystem::path& viewer_dir, int port, const std::string& what,
                  const std::function<void(httplib::Server&)>& add_routes, const ServerHooks& hooks) {
  if (port < 0 || port > 65535) throw InputError("--port", 0, "must be 0 .. 65535");
  httplib::Server server;
  // Only the page and its modules; never a listing, never outside the folder
  // (httplib's mount refuses paths with "..").
  if (!server.set_mount_point("/", viewer_dir.string()))
    throw InputError(viewer_dir.string(), 0, "cannot serve this directory");
  server.set_file_extension_and_mimetype_mapping("js", "text/javascript");
  server.set_file_extension_and_mimetype_mapping("mjs", "text/javascript");
  // Debian's httplib sets SO_REUSEPORT on its sockets: a second server
  // would then bind the same port and the kernel would split connections
  // between the two. SO_REUSEADDR only, so a taken port is an error.
  server.set_socket_options([](socket_t sock) {
    int yes = 1;
    setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof(yes));
  });
  add_routes(server);
  server.set_error_handler([](const httplib::Request& request, httplib::Response& response) {
    if (response.body.empty())
      response.set_content("tcbench: " + std::to_string(response.status) + " for " + request.method + " " +
                               request.path + "\n",
                           "text/plain");
  });

  const int bound = port == 0 ? server.bind_to_any_port("127.0.0.1") : (server.bind_to_port("127.0.0.1", port) ? port : -1);
  if (bound < 0)
    throw InputError("--port", 0,
                     "cannot listen on 127.0.0.1:" + std::to_string(port) + " (in use?); --port 0 picks a free one");

  // SIGINT/SIGTERM are blocked in this thread before the server starts its
  // workers (they inherit the mask), and one thread waits for them: no
  // handler, no global flag.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  sigset_t previous;
  pthread_sigmask(SIG_BLOCK, &signals, &previous);
  std::atomic<bool> done{false};
  std::atomic<bool> interrupted{false};
  std::thread waiter([&] {
    // httplib's stop() does nothing before listen_after_bind() has started
    // listening: a signal that came earlier stays pending until then.
    while (!done.load() && !server.is_running()) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    const timespec tick{0, 100'000'000};
    while (!done.load()) {
      const bool signalled = sigtimedwait(&signals, nullptr, &tick) > 0;
      if (signalled || (hooks.finished && hooks.finished())) {
        interrupted = true;
        if (hooks.on_stop) hooks.on_stop();
        server.stop();
        return;
      }
    }
  });

  if (hooks.on_listening) hooks.on_listening();
  std::cout << "tcbench " << what << ": http://127.0.0.1:" << bound << "/ (Ctrl-C stops)" << std::endl;
  const bool ok = server.listen_after_bind();
  done = true;
  waiter.join();
  pthread_sigmask(SIG_SETMASK, &previous, nullptr);
  if (!ok && !interrupted) throw std::runtime_error("the server stopped unexpectedly");
  std::cout << "tcbench " << what << ": stopped" << std::endl;
  return 0;
}

}  // namespace tcb
