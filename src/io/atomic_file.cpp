#include "petroscope/io/atomic_file.hpp"

#include "petroscope/core/error.hpp"

#include <atomic>
#include <cerrno>
#include <cstring>
#include <csignal>
#include <fcntl.h>
#include <mutex>
#include <string>
#include <unistd.h>

namespace petroscope {
namespace {

// The temporary files a signal handler must remove, in storage it can read without allocating: a path per
// slot, published by its `used` flag. Paths longer than a slot are not registered (they are removed on
// every normal exit, but not on a signal).
constexpr int kSlots = 256;
constexpr std::size_t kPathBytes = 1024;
struct Slot {
    std::atomic<bool> used{false};
    char path[kPathBytes];
};
Slot slots[kSlots];
std::mutex registry_mutex;

int register_temporary(const std::filesystem::path& path) {
    const std::string text = path.string();
    if (text.size() + 1 > kPathBytes) return -1;
    const std::lock_guard<std::mutex> lock(registry_mutex);
    for (int k = 0; k < kSlots; ++k) {
        if (slots[k].used.load(std::memory_order_relaxed)) continue;
        std::memcpy(slots[k].path, text.c_str(), text.size() + 1);
        slots[k].used.store(true, std::memory_order_release);
        return k;
    }
    return -1;
}

void unregister_temporary(int slot) {
    if (slot >= 0) slots[slot].used.store(false, std::memory_order_release);
}

// Async-signal-safe: unlink, write and _exit only (POSIX.1-2017 §2.4.3).
extern "C" void remove_temporaries_and_exit(int signal_number) {
    for (Slot& slot : slots) {
        if (slot.used.load(std::memory_order_acquire)) ::unlink(slot.path);
    }
    char message[] = "\npetroscope: interrupted (signal   ); no output was written\n";
    char* digits = std::strchr(message, ')') - 2;
    digits[0] = static_cast<char>('0' + (signal_number / 10) % 10);
    digits[1] = static_cast<char>('0' + signal_number % 10);
    [[maybe_unused]] const ssize_t written = ::write(STDERR_FILENO, message, sizeof message - 1);
    ::_exit(128 + signal_number);
}

}  // namespace

void install_interrupt_cleanup() {
    struct sigaction action {};
    action.sa_handler = remove_temporaries_and_exit;
    sigemptyset(&action.sa_mask);
    ::sigaction(SIGINT, &action, nullptr);
    ::sigaction(SIGTERM, &action, nullptr);
    ::signal(SIGXFSZ, SIG_IGN);
}

PendingOutputs::~PendingOutputs() {
    for (const Entry& entry : entries_) {
        if (!committed_) {
            std::error_code ignored;
            std::filesystem::remove(entry.temporary, ignored);
        }
        unregister_temporary(entry.slot);
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
    entries_.push_back({temporary, destination, register_temporary(temporary)});
    return temporary;
}

void PendingOutputs::commit() {
    for (const Entry& entry : entries_) {
        std::error_code error;
        std::filesystem::rename(entry.temporary, entry.destination, error);
        if (error) throw InputError("cannot move the finished output onto " + entry.destination.string() + ": " + error.message());
        unregister_temporary(entry.slot);
    }
    committed_ = true;
}

}  // namespace petroscope
