#pragma once
// `petroscope serve` on a socket: the live microscope's answers over HTTP (cpp-httplib), until Ctrl-C.
#include "petroscope/serve/live_microscope.hpp"

#include <cstddef>
#include <functional>
#include <string>

namespace petroscope::serve {

struct ServeSettings {
    std::string host = "127.0.0.1";  // loopback unless told otherwise
    int port = 8765;                 // 0: any free port
    std::size_t max_body_bytes = 16 << 20;  // a section sent from the page: its description and grain map
    bool verbose = false;            // one line per request on standard error
};

/// Binds, calls `on_listening` with the page's URL, and answers until SIGINT or SIGTERM, then returns.
/// Requests whose Host header names another machine are refused (403) while bound to loopback, against
/// DNS rebinding. Throws InputError when the address cannot be bound.
void serve_until_interrupted(const LiveMicroscope& microscope, const ServeSettings& settings,
                             const std::function<void(const std::string& url)>& on_listening);

}  // namespace petroscope::serve
