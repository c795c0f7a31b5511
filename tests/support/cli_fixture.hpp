#pragma once
// Running the petroscope command-line tool as a user would, from a scratch folder per test.
#include "support/test_files.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace petroscope::testing {

inline std::string quoted(const std::filesystem::path& path) { return "'" + path.string() + "'"; }

struct CommandResult {
    int exit_code = -1;
    std::string out, err;
};

/// A scratch folder per test under PETROSCOPE_TEST_OUTPUT_DIR: out/ receives the images, logs/ the captured
/// standard output and error (kept apart so that out/ lists only what petroscope wrote). Removed at the end.
class CliFixture : public ::testing::Test {
protected:
    void SetUp() override {
        static std::atomic<int> counter{0};
        scratch_ = std::filesystem::path(PETROSCOPE_TEST_OUTPUT_DIR) /
                   ("cli-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) + "-" +
                    ::testing::UnitTest::GetInstance()->current_test_info()->name());
        std::filesystem::remove_all(scratch_);
        std::filesystem::create_directories(out());
        std::filesystem::create_directories(scratch_ / "logs");
    }
    void TearDown() override {
        std::error_code ignored;
        std::filesystem::remove_all(scratch_, ignored);
    }

    std::filesystem::path out() const { return scratch_ / "out"; }
    const std::filesystem::path& scratch() const { return scratch_; }

    /// Runs `petroscope ARGUMENTS` with the environment overrides removed (so the shipped data is used).
    CommandResult petroscope(const std::string& arguments) {
        const std::filesystem::path out_log = scratch_ / "logs" / "stdout.txt";
        const std::filesystem::path err_log = scratch_ / "logs" / "stderr.txt";
        const std::string command = "env -u PETROSCOPE_MINERALS -u PETROSCOPE_DATA_DIR " + quoted(PETROSCOPE_BINARY) +
                                    " " + arguments + " > " + quoted(out_log) + " 2> " + quoted(err_log) + " < /dev/null";
        const int status = std::system(command.c_str());
        CommandResult run;
        run.exit_code = (status != -1 && WIFEXITED(status)) ? WEXITSTATUS(status) : -1;
        run.out = read_text(out_log);
        run.err = read_text(err_log);
        return run;
    }

    /// A command that must fail on bad input: exit code 2, every `expected` text in the message, and out/
    /// exactly as before (no image, no sidecar, no ".NAME.tmp-*" file).
    void expect_rejected(const std::string& arguments, const std::vector<std::string>& expected) {
        SCOPED_TRACE("petroscope " + arguments);
        const std::set<std::string> before = listing(out());
        const CommandResult run = petroscope(arguments);
        EXPECT_EQ(run.exit_code, 2) << run.err;
        for (const std::string& text : expected) {
            EXPECT_NE(run.err.find(text), std::string::npos) << "'" << text << "' not in stderr: " << run.err;
        }
        EXPECT_EQ(listing(out()), before);
    }

private:
    std::filesystem::path scratch_;
};

}  // namespace petroscope::testing
