#pragma once
// All-or-nothing output: files are written under temporary names beside their destination and renamed
// together at the end; anything not committed is removed, so no half-written file is ever left.
#include <filesystem>
#include <vector>

namespace petroscope {

class PendingOutputs {
public:
    PendingOutputs() = default;
    PendingOutputs(const PendingOutputs&) = delete;
    PendingOutputs& operator=(const PendingOutputs&) = delete;
    ~PendingOutputs();

    /// Checks that `destination` can be written (its folder exists and is writable, it is not a folder)
    /// by creating its temporary file now, and returns the temporary path to write to. Throws InputError.
    std::filesystem::path add(const std::filesystem::path& destination);
    /// Renames every temporary file onto its destination.
    void commit();

private:
    struct Entry {
        std::filesystem::path temporary, destination;
        int slot = -1;  // in the interrupt registry (install_interrupt_cleanup)
    };
    std::vector<Entry> entries_;
    bool committed_ = false;
};

/// Makes interruption leave nothing half-written: SIGINT and SIGTERM remove every pending temporary file
/// of every PendingOutputs, print "petroscope: interrupted (signal N); no output was written" and end the
/// program with status 128 + N. SIGXFSZ (a file size limit) is ignored, so that a write beyond the limit
/// fails with an error the writers report, like a full disk. Call once, early in main.
void install_interrupt_cleanup();

}  // namespace petroscope
