// A libFuzzer target for one parser; FUZZ_TARGET_NAME (set by CMake) names it (fuzz_inputs.hpp).
#include "fuzz_inputs.hpp"

#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    petroscope::fuzz::run_target(FUZZ_TARGET_NAME, std::string_view(reinterpret_cast<const char*>(data), size));
    return 0;
}
