// Start-up (issue 22): `petroscope` links none of the heavy libraries (OpenCV, Ceres, cpp-httplib,
// OpenImageIO) and hands the commands that need them to petroscope-full beside it, with the same command
// line, so that a user sees one program: same help, same messages, same exit codes. How long a start takes
// is measured in bench/bench_startup.cpp, not here.
#include "support/cli_fixture.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>

namespace petroscope {
namespace {

namespace fs = std::filesystem;

using testing::CommandResult;
using testing::quoted;

class CliStartup : public testing::CliFixture {};

/// The shared libraries the dynamic loader maps for `program` (glibc's loader lists them and exits when
/// LD_TRACE_LOADED_OBJECTS is set, running none of the program's code: what ldd does).
std::string loaded_libraries(const fs::path& program) {
    const std::string command = "LD_TRACE_LOADED_OBJECTS=1 " + quoted(program);
    std::string listing;
    if (std::FILE* pipe = ::popen(command.c_str(), "r")) {
        char buffer[512];
        while (std::fgets(buffer, sizeof buffer, pipe)) listing += buffer;
        ::pclose(pipe);
    }
    return listing;
}

TEST_F(CliStartup, PetroscopeLoadsNoHeavyLibrary) {
    const std::string petroscope = loaded_libraries(PETROSCOPE_BINARY);
    ASSERT_NE(petroscope.find("libc.so"), std::string::npos) << petroscope;
    for (const char* heavy : {"opencv", "ceres", "httplib", "OpenImageIO", "libav", "gstreamer", "ssl"}) {
        EXPECT_EQ(petroscope.find(heavy), std::string::npos) << heavy << " is loaded by petroscope:\n" << petroscope;
    }
    // The check can fail: petroscope-full does load them.
    const std::string full = loaded_libraries(fs::path(PETROSCOPE_BINARY).parent_path() / "petroscope-full");
    for (const char* heavy : {"opencv", "ceres", "httplib"}) EXPECT_NE(full.find(heavy), std::string::npos) << heavy << ":\n" << full;
}

TEST_F(CliStartup, HeavyCommandsAnswerThroughPetroscopeAsThemselves) {
    const CommandResult help = petroscope("fit conoscope --help");
    EXPECT_EQ(help.exit_code, 0) << help.err;
    EXPECT_NE(help.out.find("--photo"), std::string::npos) << help.out;
    const CommandResult listing = petroscope("--help");
    EXPECT_EQ(listing.exit_code, 0);
    for (const char* command : {"conoscope", "chart", "sweep", "fit", "serve"}) EXPECT_NE(listing.out.find(command), std::string::npos) << command;
    // Bad input to a handed-over command: petroscope-full's own message and exit code, no output written.
    expect_rejected("chart --max-retardation 1000", {"--output is required"});
    expect_rejected("sweep conoscope --vary azimuth-deg=0:30:10", {"--output is required"});
}

TEST_F(CliStartup, AMissingPetroscopeFullIsNamed) {
    const fs::path alone = scratch() / "alone" / "petroscope";
    fs::create_directories(alone.parent_path());
    fs::copy_file(PETROSCOPE_BINARY, alone);
    const std::string command = quoted(alone) + " fit conoscope --help > " + quoted(scratch() / "logs" / "o.txt") + " 2> " +
                                quoted(scratch() / "logs" / "e.txt");
    const int status = std::system(command.c_str());
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 2) << status;
    const std::string message = testing::read_text(scratch() / "logs" / "e.txt");
    EXPECT_NE(message.find("'fit' is run by " + (alone.parent_path() / "petroscope-full").string()), std::string::npos) << message;
    // The commands of its own still work.
    EXPECT_EQ(std::system((quoted(alone) + " minerals > /dev/null").c_str()), 0);
}

}  // namespace
}  // namespace petroscope
