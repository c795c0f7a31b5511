// Every input kept in fuzz/regressions/TARGET/ (found by fuzz/run.sh, or written by hand for the edges:
// NaN, overflow, absurd sizes, deep nesting, degenerate shapes) goes through its parser again: accepted,
// or rejected with InputError, never another exception or a crash (the sanitizer build turns memory
// errors into failures too).
#include "fuzz_inputs.hpp"

#include "support/test_files.hpp"

#include <gtest/gtest.h>

#include <filesystem>

namespace petroscope {
namespace {

TEST(FuzzRegressions, EveryKeptInputIsAcceptedOrRejectedCleanly) {
    const std::filesystem::path root = std::filesystem::path(PETROSCOPE_SOURCE_DIR) / "fuzz" / "regressions";
    int replayed = 0;
    for (const std::string& target : fuzz::target_names()) {
        const std::filesystem::path folder = root / target;
        if (!std::filesystem::is_directory(folder)) continue;
        for (const auto& entry : std::filesystem::directory_iterator(folder)) {
            SCOPED_TRACE(entry.path().string());
            const std::string input = testing::read_text(entry.path());
            EXPECT_NO_THROW(fuzz::run_target(target, input));
            ++replayed;
        }
    }
    EXPECT_GE(replayed, 14);  // the hand-written edges at least
}

}  // namespace
}  // namespace petroscope
