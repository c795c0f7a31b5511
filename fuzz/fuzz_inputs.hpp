#pragma once
// One input for each of petroscope's parsers, shared by the libFuzzer targets (fuzz/fuzz_*.cpp) and the
// regression test that replays the inputs kept in fuzz/regressions/ (tests/io/test_fuzz_regressions.cpp).
// Each function parses the bytes and returns normally when they are accepted or rejected with InputError;
// anything else (another exception, a crash, a sanitizer report, a hang) is a bug.
#include <string>
#include <string_view>
#include <vector>

namespace petroscope::fuzz {

/// The targets by name: "mineral", "thin_section", "interface_case", "scene", "values", "jpeg_header", "serve_query", "image_file".
const std::vector<std::string>& target_names();
/// Runs target `name` on `input`.
void run_target(const std::string& name, std::string_view input);

}  // namespace petroscope::fuzz
