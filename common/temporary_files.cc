#include "common/temporary_files.h"

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <cstring>
#include <mutex>

namespace motif {
namespace {

// Far more than one process has in flight (a few per stage); a name without a slot is left to
// the next run's sweep, as after a kill -9.
constexpr int kTrackedSlots = 512;
std::atomic<char*> tracked[kTrackedSlots];
std::once_flag termination_handler_once;

void OnTermination(int signal_number) {
  for (std::atomic<char*>& slot : tracked) {
    const char* path = slot.load(std::memory_order_acquire);
    if (path != nullptr) unlink(path);
  }
  // The signal is blocked while this runs: the default action ends the process on return.
  struct sigaction default_action {};
  default_action.sa_handler = SIG_DFL;
  sigemptyset(&default_action.sa_mask);
  sigaction(signal_number, &default_action, nullptr);
  raise(signal_number);
}

void Install() {
  struct sigaction action {};
  action.sa_handler = OnTermination;
  sigemptyset(&action.sa_mask);
  for (int signal_number : {SIGTERM, SIGINT, SIGHUP}) sigaction(signal_number, &action, nullptr);
}

}  // namespace

void TrackTemporaryFile(const std::string& path) {
  char* copy = strdup(path.c_str());
  if (copy == nullptr) return;
  for (std::atomic<char*>& slot : tracked) {
    char* empty = nullptr;
    if (slot.compare_exchange_strong(empty, copy, std::memory_order_acq_rel)) return;
  }
  std::free(copy);
}

void UntrackTemporaryFile(const std::string& path) {
  for (std::atomic<char*>& slot : tracked) {
    char* held = slot.load(std::memory_order_acquire);
    if (held == nullptr || path != held) continue;
    if (slot.compare_exchange_strong(held, nullptr, std::memory_order_acq_rel)) std::free(held);
    return;
  }
}

void RemoveTemporaryFilesOnTermination() { std::call_once(termination_handler_once, Install); }

}  // namespace motif
