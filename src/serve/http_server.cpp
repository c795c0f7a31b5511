#include "petroscope/serve/http_server.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/core/heap.hpp"
#include "petroscope/core/text.hpp"

#include <httplib.h>
#include <nlohmann/json.hpp>
#include <pthread.h>

#include <algorithm>
#include <csignal>
#include <memory>
#include <cstdio>
#include <thread>

namespace petroscope::serve {
namespace {

constexpr std::size_t kStreamedBodyBytes = 1 << 20;

bool loopback(const std::string& host) { return host == "127.0.0.1" || host == "localhost" || host == "::1"; }

/// While bound to loopback, a page from elsewhere that resolves its own name to 127.0.0.1 must not
/// reach the server: the Host header must name this machine.
bool allowed_host(const httplib::Request& request, const ServeSettings& settings, int port) {
    if (!loopback(settings.host)) return true;
    const std::string host = request.get_header_value("Host");
    const std::string suffix = ":" + std::to_string(port);
    return host == "127.0.0.1" + suffix || host == "localhost" + suffix || host == "[::1]" + suffix;
}

void answer(const ServeSettings& settings, int port, const httplib::Request& request, httplib::Response& response,
            const std::function<Reply()>& reply_of) {
    Reply reply;
    if (!allowed_host(request, settings, port)) {
        reply = {403, "application/json", R"({"error": "this server answers only requests addressed to this machine"})"};
    } else {
        try {
            reply = reply_of();
        } catch (const InputError& error) {  // a parameter given twice
            reply = {400, "application/json", nlohmann::json{{"error", error.what()}}.dump()};
        }
    }
    response.status = reply.status;
    response.set_header("Cache-Control", "no-store");
    response.set_header("X-Content-Type-Options", "nosniff");
    response.set_header("Content-Security-Policy", "default-src 'self'; img-src 'self' blob: data:");
    if (reply.body.size() < kStreamedBodyBytes) {
        response.set_content(reply.body, reply.content_type);
    } else {  // a view: sent from the reply itself, not from a copy
        const auto body = std::make_shared<const std::string>(std::move(reply.body));
        response.set_content_provider(body->size(), reply.content_type, [body](std::size_t offset, std::size_t length, httplib::DataSink& sink) {
            return sink.write(body->data() + offset, std::min(length, body->size() - offset));
        });
    }
    if (settings.verbose) std::fprintf(stderr, "%d %s\n", reply.status, quote_input(request.target, 200).c_str());
}

}  // namespace

void serve_until_interrupted(const LiveMicroscope& microscope, const ServeSettings& settings,
                             const std::function<void(const std::string& url)>& on_listening) {
    keep_large_blocks_in_heap();  // a view allocates tens of MB
    httplib::Server server;
    server.set_payload_max_length(settings.max_body_bytes);
    int port = settings.port;
    server.Get(".*", [&](const httplib::Request& request, httplib::Response& response) {
        answer(settings, port, request, response, [&] { return microscope.get(request.path, QueryParameters({request.params.begin(), request.params.end()})); });
    });
    server.Post("/api/section", [&](const httplib::Request& request, httplib::Response& response) {
        answer(settings, port, request, response, [&] {
            std::vector<UploadedFile> files;
            for (const auto& [field, file] : request.files) files.push_back({field, file.filename, file.content});
            return microscope.post_section(files);
        });
    });
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
