#include "petroscope/io/atomic_file.hpp"

#include "petroscope/core/error.hpp"

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <string>
#include <unistd.h>

namespace petroscope {

PendingOutputs::~PendingOutputs() {
    if (committed_) return;
    for (const Entry& entry : entries_) {
        std::error_code ignored;
        std::filesystem::remove(entry.temporary, ignored);
    }
}

std::filesystem::path PendingOutputs::add(const std::filesystem::path& destination) {
    static std::atomic<unsigned> counter{0};
    const std::string shown = destination.string();
    std::error_code error;
    if (std::filesystem::is_directory(destination, error)) {
        throw InputError("cannot write output " + shown + ": it is a folder");
    }
    std::filesystem::path folder = destination.parent_path();
    if (folder.empty()) folder = ".";
    if (!std::filesystem::is_directory(folder, error)) {
        throw InputError("cannot write output " + shown + ": folder " + folder.string() + " does not exist");
    }
    const std::filesystem::path temporary =
        folder / ("." + destination.filename().string() + ".tmp-" + std::to_string(::getpid()) + "-" +
                  std::to_string(counter++));
    const int descriptor = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0644);
    if (descriptor < 0) {
        throw InputError("cannot write output " + shown + ": " + std::strerror(errno));
    }
    ::close(descriptor);
    entries_.push_back({temporary, destination});
    return temporary;
}

void PendingOutputs::commit() {
    for (const Entry& entry : entries_) {
        std::error_code error;
        std::filesystem::rename(entry.temporary, entry.destination, error);
        if (error) throw InputError("cannot move the finished output onto " + entry.destination.string() + ": " + error.message());
    }
    committed_ = true;
}

}  // namespace petroscope
