#include "petroscope/serve/http_server.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/core/text.hpp"

#include <httplib.h>
#include <nlohmann/json.hpp>
#include <pthread.h>

#include <csignal>
#include <cstdio>
#include <thread>

namespace petroscope::serve {
namespace {

bool loopback(const std::string& host) { return host == "127.0.0.1" || host == "localhost" || host == "::1"; }

/// While bound to loopback, a page from elsewhere that resolves its own name to 127.0.0.1 must not
/// reach the server: the Host header must name this machine.
bool allowed_host(const httplib::Request& request, const ServeSettings& settings, int port) {
    if (!loopback(settings.host)) return true;
    const std::string host = request.get_header_value("Host");
    const std::string suffix = ":" + std::to_string(port);
    return host == "127.0.0.1" + suffix || host == "localhost" + suffix || host == "[::1]" + suffix;
}

void answer(const LiveMicroscope& microscope, const ServeSettings& settings, int port, const httplib::Request& request,
            httplib::Response& response) {
    Reply reply;
    if (!allowed_host(request, settings, port)) {
        reply = {403, "application/json", R"({"error": "this server answers only requests addressed to this machine"})"};
    } else {
        try {
            reply = microscope.get(request.path, QueryParameters({request.params.begin(), request.params.end()}));
        } catch (const InputError& error) {  // a parameter given twice
            reply = {400, "application/json", nlohmann::json{{"error", error.what()}}.dump()};
        }
    }
    response.status = reply.status;
    response.set_header("Cache-Control", "no-store");
    response.set_header("X-Content-Type-Options", "nosniff");
    response.set_header("Content-Security-Policy", "default-src 'self'; img-src 'self' blob: data:");
    response.set_content(reply.body, reply.content_type.c_str());
    if (settings.verbose) std::fprintf(stderr, "%d %s\n", reply.status, quote_input(request.target, 200).c_str());
}

}  // namespace

void serve_until_interrupted(const LiveMicroscope& microscope, const ServeSettings& settings,
                             const std::function<void(const std::string& url)>& on_listening) {
    httplib::Server server;
    server.set_payload_max_length(settings.max_body_bytes);
    int port = settings.port;
    server.Get(".*", [&](const httplib::Request& request, httplib::Response& response) { answer(microscope, settings, port, request, response); });
    port = settings.port == 0 ? server.bind_to_any_port(settings.host) : (server.bind_to_port(settings.host, settings.port) ? settings.port : -1);
    if (port < 0) {
        throw InputError("cannot listen on " + quote_input(settings.host) + " port " + std::to_string(settings.port) +
                         " (in use, or not an address of this machine)");
    }
    // Ctrl-C and SIGTERM reach one thread that stops the server: blocked here before the server's threads
    // (and the renders' OpenMP threads) start, so that they inherit the mask.
    sigset_t stop_signals, previous;
    sigemptyset(&stop_signals);
    for (const int signal_number : {SIGINT, SIGTERM, SIGUSR1}) sigaddset(&stop_signals, signal_number);
    pthread_sigmask(SIG_BLOCK, &stop_signals, &previous);
    std::thread watcher([&] {
        int received = 0;
        sigwait(&stop_signals, &received);
        server.stop();
    });
    const std::string shown_host = settings.host.find(':') != std::string::npos ? "[" + settings.host + "]" : settings.host;
    on_listening("http://" + shown_host + ":" + std::to_string(port) + "/");
    server.listen_after_bind();
    pthread_kill(watcher.native_handle(), SIGUSR1);  // wakes the watcher if the server stopped by itself
    watcher.join();
    pthread_sigmask(SIG_SETMASK, &previous, nullptr);
}

}  // namespace petroscope::serve
