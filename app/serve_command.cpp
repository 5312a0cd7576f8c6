// radiant serve MODEL.glb — serves the browser viewer (viewer/) and one model
// on a local HTTP server (cpp-httplib, Debian's libcpp-httplib-dev), and
// prints the address to open. It listens on 127.0.0.1 unless --bind says
// otherwise, answers GET and HEAD only, and serves the viewer's folder and
// the one model file, nothing else: a path leaving the folder ("..") is
// refused by the library, and the model is served as a single route.
#include <fmt/format.h>
#include <httplib.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <thread>

#include "commands.h"
#include "interrupt_handler.h"
#include "scene/load_scene.h"
#include "util/error.h"
#include "util/file_extension.h"
#include "util/input_file.h"
#include "util/interrupt.h"

namespace radiant {

namespace {

struct ServeCommandOptions {
  std::string modelPath;
  std::string bind = "127.0.0.1";
  int port = 8000;
  std::string viewerDir = RADIANT_VIEWER_DIR;
  bool quiet = false;
};

std::string readWholeFile(const std::string &path) {
  return readInputFile(path, InputLocation{path}, "file");
}

}  // namespace

CommandRunner addServeCommand(CLI::App &app) {
  auto o = std::make_shared<ServeCommandOptions>();
  app.add_option("model", o->modelPath, "A .glb or .gltf file from `radiant export`")->required();
  app.add_option("--port", o->port, "TCP port (0: any free one)")->default_val(8000)->check(CLI::Range(0, 65535));
  app.add_option("--bind", o->bind,
                 "Address to listen on: 127.0.0.1 (this machine only), or e.g. 0.0.0.0 for every network")
      ->default_val("127.0.0.1");
  app.add_option("--viewer", o->viewerDir, "The viewer's folder (default: the source tree's viewer/)");
  app.add_flag("-q,--quiet", o->quiet, "No request log on stderr");

  return [o]() {
    namespace fs = std::filesystem;
    const std::string extension = lowercaseExtension(o->modelPath);
    if (extension != ".glb" && extension != ".gltf")
      throw InputError(InputLocation{o->modelPath}, "expected a .glb or .gltf file (from `radiant export`)");
    std::error_code error;
    if (!fs::is_regular_file(o->modelPath, error)) throw InputError(InputLocation{o->modelPath}, "no such file");
    if (!fs::is_regular_file(fs::path(o->viewerDir) / "index.html", error))
      throw InputError(InputLocation{"--viewer"}, "'" + o->viewerDir + "' has no index.html");
    if (!fs::is_regular_file(fs::path(o->viewerDir) / "node_modules/three/build/three.module.js", error))
      throw InputError(InputLocation{"--viewer"}, "'" + o->viewerDir +
                                                      "' has no node_modules/three: run scripts/install-deps.sh "
                                                      "(it runs npm ci there)");
    // Read as the renderer reads a glTF, so that a broken or empty model is
    // refused here, naming the file, not in the browser without a word.
    if (loadScene(o->modelPath).faces.empty())
      throw InputError(InputLocation{o->modelPath}, "the model has no faces (no mesh primitives): nothing to show");
    const std::string modelRoute = "/model" + extension;
    const std::string modelBytes = readWholeFile(o->modelPath);

    httplib::Server server;
    // Under load (tests/serve_stress_test.py): cpp-httplib gives each
    // connection a worker from a pool (8 by default) for as long as the
    // client keeps sending, so 8 clients dribbling their headers a byte at a
    // time held every worker and the viewer got no answer at all. With
    // kWorkers, a client silent for kIdle is dropped, and an idle keep-alive
    // connection is closed after kIdle too; a browser opens 6 at most.
    constexpr size_t kWorkers = 64;
    constexpr time_t kIdle = 2;  // seconds
    server.new_task_queue = [] { return new httplib::ThreadPool(kWorkers); };
    server.set_read_timeout(kIdle, 0);
    server.set_keep_alive_timeout(kIdle);
    server.set_payload_max_length(1 << 16);  // GET and HEAD only: no request has a body to read
    // A browser sends about 20 headers; cpp-httplib 0.11 reads any number (each line at most 8 KiB).
    constexpr size_t kMaxHeaders = 128;
    server.set_pre_routing_handler([](const httplib::Request &request, httplib::Response &response) {
      if (request.headers.size() <= kMaxHeaders) return httplib::Server::HandlerResponse::Unhandled;
      response.status = 431;  // Request Header Fields Too Large
      return httplib::Server::HandlerResponse::Handled;
    });
    for (const auto &[ext, type] : {std::pair{"html", "text/html"},
                                    {"js", "text/javascript"},
                                    {"mjs", "text/javascript"},
                                    {"css", "text/css"},
                                    {"json", "application/json"},
                                    {"png", "image/png"},
                                    {"glb", "model/gltf-binary"},
                                    {"gltf", "model/gltf+json"}})
      server.set_file_extension_and_mimetype_mapping(ext, type);
    server.Get(modelRoute, [&](const httplib::Request &, httplib::Response &response) {
      response.set_content(modelBytes, extension == ".glb" ? "model/gltf-binary" : "model/gltf+json");
    });
    if (!server.set_mount_point("/", o->viewerDir))
      throw InputError(InputLocation{"--viewer"}, "cannot serve '" + o->viewerDir + "'");
    if (!o->quiet)
      server.set_logger([](const httplib::Request &request, const httplib::Response &response) {
        fmt::print(stderr, "radiant: {} {} {}\n", request.method, request.path, response.status);
      });
    const int port =
        o->port == 0 ? server.bind_to_any_port(o->bind) : (server.bind_to_port(o->bind, o->port) ? o->port : -1);
    if (port < 0)
      throw InputError(InputLocation{"--port"}, fmt::format("cannot listen on {}:{} (in use, or not an address "
                                                            "of this machine)",
                                                            o->bind, o->port));
    // Ctrl-C stops the server; the first line of standard output is the address (scripts read it).
    InterruptHandler interrupts;
    std::atomic<bool> listenerDone = false;
    std::thread listener([&] {
      server.listen_after_bind();
      listenerDone = true;
    });
    const std::string host = o->bind == "0.0.0.0" ? "127.0.0.1" : o->bind;
    fmt::print("http://{}:{}/index.html?model={}\n", host, port, modelRoute.substr(1));
    std::fflush(stdout);
    if (!o->quiet) fmt::print(stderr, "radiant: serving {} and {} (Ctrl-C stops)\n", o->viewerDir, o->modelPath);
    // Until Ctrl-C; stop() ends listen_after_bind only once it runs, so it is repeated until the thread is done.
    while (!interruptRequested()) std::this_thread::sleep_for(std::chrono::milliseconds(100));
    while (!listenerDone) {
      server.stop();
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    listener.join();
    return 0;
  };
}

}  // namespace radiant
