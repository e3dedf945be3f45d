// gjkdem view OUT: serves a run folder and the browser viewer's page on
// 127.0.0.1 (cpp-httplib). The page (web/) and its three.js come from the
// npm registry at build time; nothing is fetched at run time.
#include <httplib.h>

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <stdexcept>

#include "commands.hpp"
#include "gjkdem/io/view_format.hpp"

namespace gjkdem::app {

namespace fs = std::filesystem;

namespace {

bool page_complete(const fs::path& web) {
  return fs::is_regular_file(web / "index.html") && fs::is_regular_file(web / "node_modules/three/build/three.module.js");
}

/// The viewer's page: --web, $GJKDEM_WEB_DIR, the copy installed beside this
/// program (PREFIX/share/gjkdem/web), the one installed where it was
/// configured to go, the source tree's.
// True when `relative` names a path inside `root` reached without a symbolic
// link: a link in a run folder may lead anywhere (/etc/passwd, /).
bool reached_without_links(const fs::path& root, const std::string& relative) {
  fs::path at = root;
  for (const fs::path& part : fs::path(relative)) {
    if (part.empty() || part == "/" || part == ".") continue;
    if (part == "..") return false;
    at /= part;
    std::error_code ec;
    if (fs::is_symlink(fs::symlink_status(at, ec))) return false;
  }
  return true;
}

fs::path find_page(const std::string& given) {
  std::vector<fs::path> tried;
  if (!given.empty()) tried.push_back(given);
  if (const char* env = std::getenv("GJKDEM_WEB_DIR")) tried.push_back(env);
  if (given.empty()) {
    std::error_code ec;
    const fs::path self = fs::read_symlink("/proc/self/exe", ec);
    if (!ec) tried.push_back(self.parent_path().parent_path() / "share/gjkdem/web");
    tried.push_back(GJKDEM_WEB_INSTALLED_DIR), tried.push_back(GJKDEM_WEB_SOURCE_DIR);
  }
  for (const fs::path& p : tried)
    if (page_complete(p)) return p;
  std::string names;
  for (const fs::path& p : tried) names += "\n  " + p.string();
  throw std::runtime_error("the viewer's page is not built (index.html and node_modules/three) in any of:" + names +
                           "\nrun `npm ci` in the source tree's web/ folder (./build.sh does)");
}

}  // namespace

int view_run(const ViewOptions& opt) {
  const fs::path run = fs::absolute(opt.run);
  io::require_view_frames(run);
  const fs::path web = find_page(opt.web);

  httplib::Server server;
  // The page fetches many frames at once, and a browser holds its idle
  // keep-alive connections open, each taking a worker: with the default pool
  // (8) and keep-alive (5 s), fetches past the eighth waited seconds.
  server.new_task_queue = [] { return new httplib::ThreadPool(32); };
  server.set_keep_alive_timeout(1);
  // httplib's default sets SO_REUSEPORT, which lets a second server share a
  // busy port (requests then go to either run): a busy port must be refused.
  server.set_socket_options([](socket_t sock) {
    int yes = 1;
    setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  });
  const httplib::Headers no_cache = {{"Cache-Control", "no-store"}};
  // Only three.js's files are served from node_modules, never the rest of it.
  int port = 0;
  server.set_pre_routing_handler([&port, &run](const httplib::Request& req, httplib::Response& res) {
    // Only three.js of node_modules, under /vendor/ (any spelling of a path
    // through node_modules: /./node_modules, //node_modules, ...), and only
    // the run folder's own files: never through a symbolic link in it.
    if (req.path.find("node_modules") != std::string::npos ||
        (req.path.rfind("/run", 0) == 0 && !reached_without_links(run, req.path.substr(4)))) {  // "/runx" too
      res.status = 404;
      return httplib::Server::HandlerResponse::Handled;
    }
    // A page of another site that rebinds its name to 127.0.0.1 would send
    // its own Host: only this address serves the run.
    const std::string host = req.get_header_value("Host");
    const std::size_t colon = host.rfind(':');
    const std::string name = host.substr(0, colon);
    const std::string number = colon == std::string::npos ? std::string() : host.substr(colon + 1);
    if ((name != "127.0.0.1" && name != "localhost") || number != std::to_string(port)) {
      res.status = 403;
      return httplib::Server::HandlerResponse::Handled;
    }
    // Files on this machine gain nothing from compression, and cpp-httplib
    // compresses text with Brotli at its slowest setting when the browser
    // accepts it (1.9 s for three.js, where sending it takes 2 ms). The
    // request is httplib's own, not const: the handler only sees it as const
    // (cpp-httplib 0.11: the request is a local of the server's loop, and the
    // encoding is chosen after routing).
    const_cast<httplib::Request&>(req).headers.erase("Accept-Encoding");
    return httplib::Server::HandlerResponse::Unhandled;
  });
  server.set_file_extension_and_mimetype_mapping("bin", "application/octet-stream");
  server.set_file_extension_and_mimetype_mapping("csv", "text/csv");
  server.set_file_extension_and_mimetype_mapping("json", "application/json");
  // A run still going rewrites its index and logs: the browser must not cache them.
  if (!server.set_mount_point("/run", run.string(), no_cache) ||
      !server.set_mount_point("/vendor/three", (web / "node_modules/three/build").string()) ||
      !server.set_mount_point("/vendor/three-addons", (web / "node_modules/three/examples/jsm").string()) ||
      !server.set_mount_point("/", web.string(), no_cache))
    throw std::runtime_error("cannot serve " + run.string() + " or " + web.string());

  port = opt.port == 0 ? server.bind_to_any_port("127.0.0.1")
                       : (server.bind_to_port("127.0.0.1", opt.port) ? opt.port : -1);
  if (port < 0)
    throw std::runtime_error("cannot listen on 127.0.0.1:" + std::to_string(opt.port) +
                             " (in use?); choose another with --port, or --port 0 for any free one");
  std::cout << "gjkdem view: serving " << run.string() << " at http://127.0.0.1:" << port << "/ (Ctrl-C stops)"
            << std::endl;
  if (!server.listen_after_bind()) throw std::runtime_error("the server stopped on an error");
  return 0;
}

}  // namespace gjkdem::app
