#include "common/mapping_guard.h"

#include <signal.h>
#include <sys/mman.h>
#include <unistd.h>

#include <atomic>
#include <mutex>

namespace motif {
namespace {

// Enough for every file one process maps at once (an archive, a trellis, a search cache per
// open reader); a range without a slot is only unguarded, not wrong.
constexpr int kSlots = 1024;

struct Slot {
  std::atomic<bool> taken{false};
  std::atomic<uintptr_t> begin{0};
  std::atomic<uintptr_t> end{0};  // 0: no range (being set up or torn down)
  std::atomic<bool> cut{false};
};

Slot slots[kSlots];
struct sigaction previous_action;
uintptr_t page_bytes = 4096;
std::once_flag install_once;

// A SIGBUS that is not ours: the earlier handler takes it, or, if there was none, the default
// action is restored and the signal raised again, so that it kills the process as before.
void PassOn(int signal_number, siginfo_t* info, void* context) {
  if ((previous_action.sa_flags & SA_SIGINFO) && previous_action.sa_sigaction != nullptr) {
    previous_action.sa_sigaction(signal_number, info, context);
    return;
  }
  if (previous_action.sa_handler != SIG_DFL && previous_action.sa_handler != SIG_IGN) {
    previous_action.sa_handler(signal_number);
    return;
  }
  struct sigaction default_action {};
  default_action.sa_handler = SIG_DFL;
  sigemptyset(&default_action.sa_mask);
  sigaction(SIGBUS, &default_action, nullptr);
  raise(SIGBUS);  // blocked while this runs: delivered on return
}

// Async-signal-safe: atomics and mmap only.
void OnSigbus(int signal_number, siginfo_t* info, void* context) {
  if (info != nullptr && info->si_code == BUS_ADRERR) {
    const uintptr_t address = reinterpret_cast<uintptr_t>(info->si_addr);
    for (Slot& slot : slots) {
      if (address < slot.begin.load(std::memory_order_acquire) ||
          address >= slot.end.load(std::memory_order_acquire)) {
        continue;
      }
      void* page = reinterpret_cast<void*>(address & ~(page_bytes - 1));
      void* zeros = mmap(page, page_bytes, PROT_READ, MAP_PRIVATE | MAP_ANONYMOUS | MAP_FIXED,
                         -1, 0);
      if (zeros == MAP_FAILED) break;
      slot.cut.store(true, std::memory_order_release);
      return;
    }
  }
  PassOn(signal_number, info, context);
}

void InstallHandler() {
  page_bytes = static_cast<uintptr_t>(sysconf(_SC_PAGESIZE));
  struct sigaction action {};
  action.sa_sigaction = OnSigbus;
  action.sa_flags = SA_SIGINFO;
  sigemptyset(&action.sa_mask);
  sigaction(SIGBUS, &action, &previous_action);
}

}  // namespace

MappingGuard::MappingGuard(const void* begin, uint64_t bytes) {
  if (begin == nullptr || bytes == 0) return;
  std::call_once(install_once, InstallHandler);
  for (int i = 0; i < kSlots; ++i) {
    bool free = false;
    if (!slots[i].taken.compare_exchange_strong(free, true)) continue;
    const uintptr_t start = reinterpret_cast<uintptr_t>(begin);
    slots[i].cut.store(false);
    slots[i].begin.store(start, std::memory_order_release);
    slots[i].end.store(start + bytes, std::memory_order_release);
    slot_ = i;
    return;
  }
}

MappingGuard::~MappingGuard() {
  if (slot_ < 0) return;
  slots[slot_].end.store(0, std::memory_order_release);
  slots[slot_].begin.store(0, std::memory_order_release);
  slots[slot_].taken.store(false, std::memory_order_release);
}

bool MappingGuard::cut() const {
  return slot_ >= 0 && slots[slot_].cut.load(std::memory_order_acquire);
}

}  // namespace motif
