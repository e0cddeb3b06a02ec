#include "app/mpi/interrupt_signals.h"

#include <time.h>

#include <array>
#include <chrono>
#include <csignal>
#include <cstdint>

namespace penumbra::mpi {

namespace {

constexpr int64_t kTickNanoseconds = 50'000'000;
constexpr int64_t kStopGapNanoseconds = 1'000'000'000;   // above a loaded machine's wake-up delays
constexpr unsigned kTicksKept = 64, kTicksChecked = 40;  // the last two seconds of ticks

std::atomic<int> gSignal{0};
std::atomic<int64_t> gSignalAt{0};
std::array<std::atomic<int64_t>, kTicksKept> gTicks;
std::atomic<unsigned> gTickCount{0};

int64_t monotonicNanoseconds() {
  timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);  // async-signal-safe
  return int64_t(t.tv_sec) * 1'000'000'000 + t.tv_nsec;
}

// Whether the process was stopped within the last two seconds: a gap between the ticker's readings, or
// since the last one (when the handler runs before the resumed ticker).
bool stoppedRecently(int64_t now) {
  const unsigned n = gTickCount.load(std::memory_order_acquire);
  int64_t later = now;
  for (unsigned i = 1; i <= kTicksChecked && i <= n; ++i) {
    const int64_t tick = gTicks[(n - i) % kTicksKept].load(std::memory_order_relaxed);
    if (later - tick > kStopGapNanoseconds) return true;
    later = tick;
  }
  return false;
}

void record(int sig, int64_t now) {
  int none = 0;
  if (gSignal.compare_exchange_strong(none, sig)) gSignalAt = now;
}

extern "C" void onInterrupt(int sig) {
  record(sig, monotonicNanoseconds());
}

extern "C" void onContinue(int sig) {
  const int64_t now = monotonicNanoseconds();
  if (!stoppedRecently(now)) record(sig, now);
}

void install(int sig, void (*handler)(int)) {
  struct sigaction action {};
  action.sa_handler = handler;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  sigaction(sig, &action, nullptr);
}

}  // namespace

InterruptSignals::InterruptSignals() {
  gSignal = 0;
  const int64_t now = monotonicNanoseconds();
  for (auto& tick : gTicks) tick.store(now, std::memory_order_relaxed);
  gTickCount.store(kTicksKept, std::memory_order_release);
  ticker_ = std::thread([this] {
    while (!stopTicker_.load(std::memory_order_relaxed)) {
      std::this_thread::sleep_for(std::chrono::nanoseconds(kTickNanoseconds));
      const unsigned n = gTickCount.load(std::memory_order_relaxed);
      gTicks[n % kTicksKept].store(monotonicNanoseconds(), std::memory_order_relaxed);
      gTickCount.store(n + 1, std::memory_order_release);
    }
  });
  install(SIGINT, onInterrupt);
  install(SIGTERM, onInterrupt);  // what mpirun sends every rank when it ends the job
  install(SIGUSR1, onInterrupt);  // forwarded by mpirun to every rank without ending the job
  install(SIGCONT, onContinue);
}

InterruptSignals::~InterruptSignals() {
  for (int sig : {SIGINT, SIGTERM, SIGUSR1, SIGCONT}) std::signal(sig, SIG_DFL);
  stopTicker_ = true;
  ticker_.join();
}

bool InterruptSignals::interrupted() const {
  return gSignal.load() != 0;
}

int InterruptSignals::signal() const {
  return gSignal.load();
}

double InterruptSignals::secondsSinceInterrupt() const {
  return double(monotonicNanoseconds() - gSignalAt.load()) * 1e-9;
}

}  // namespace penumbra::mpi
