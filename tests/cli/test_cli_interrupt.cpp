// Nothing half-written: an interrupted render (SIGINT, SIGTERM) and a write that fails for want of space
// (a file size limit stands in for a full disk) leave no output file, only a clear message.
#include "support/cli_fixture.hpp"

#include <gtest/gtest.h>

namespace petroscope {
namespace {

class Interrupt : public testing::CliFixture {
protected:
    /// Runs a shell command line (the binary is $P) with its output captured.
    testing::CommandResult shell(const std::string& script) {
        const std::filesystem::path err_log = scratch() / "logs" / "stderr.txt";
        const std::string command = "P=" + testing::quoted(PETROSCOPE_BINARY) + "; cd " + testing::quoted(out()) + " && " + script + " 2> " +
                                    testing::quoted(err_log) + " < /dev/null";
        const int status = std::system(("sh -c " + testing::quoted(command)).c_str());
        testing::CommandResult run;
        run.exit_code = (status != -1 && WIFEXITED(status)) ? WEXITSTATUS(status) : -1;
        run.err = testing::read_text(err_log);
        return run;
    }
};

TEST_F(Interrupt, SigintAndSigtermLeaveNoOutputFile) {
    const std::string scene = testing::quoted(std::filesystem::path(PETROSCOPE_SOURCE_DIR) / "scenes" / "calcite-box.json");
    for (const std::string signal : {"INT", "TERM"}) {
        // A render of hours, stopped after 2 s, while the temporary image and sidecar exist.
        const testing::CommandResult run = shell("timeout --preserve-status -s " + signal + " 2 \"$P\" render --scene " + scene + " --spp 50000 -o box.png");
        EXPECT_EQ(run.exit_code, signal == "INT" ? 130 : 143) << run.err;
        EXPECT_NE(run.err.find("interrupted"), std::string::npos) << run.err;
        EXPECT_NE(run.err.find("no output was written"), std::string::npos) << run.err;
        EXPECT_TRUE(testing::listing(out()).empty()) << "left behind: " << *testing::listing(out()).begin();
    }
}

TEST_F(Interrupt, AWriteThatRunsOutOfSpaceIsAnErrorAndLeavesNothing) {
    // 4 KiB of file size allowed: the 256² PNG needs more.
    const testing::CommandResult run = shell("ulimit -f 4; \"$P\" conoscope --size 256 -o figure.png");
    EXPECT_EQ(run.exit_code, 2) << run.err;
    // The PNG writer checks every write and sees the failure itself (EFBIG).
    EXPECT_NE(run.err.find("cannot write"), std::string::npos) << run.err;
    EXPECT_NE(run.err.find("File too large"), std::string::npos) << run.err;
    EXPECT_NE(run.err.find("figure.png"), std::string::npos) << run.err;
    EXPECT_TRUE(testing::listing(out()).empty());
}

}  // namespace
}  // namespace petroscope
