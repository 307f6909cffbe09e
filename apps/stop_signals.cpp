#include "apps/stop_signals.h"

#include <csignal>
#include <stdexcept>

namespace prism {
namespace {

// A signal handler may only touch lock-free atomics and volatile sig_atomic_t (C++20 [support.signal]).
std::atomic<std::atomic<bool>*> g_stop{nullptr};
volatile std::sig_atomic_t g_received = 0;
struct sigaction g_previous_int, g_previous_term;

extern "C" void on_stop_signal(int signal) {
  g_received = signal;
  if (std::atomic<bool>* stop = g_stop.load()) stop->store(true);
}

void install(int signal, struct sigaction& previous) {
  struct sigaction action = {};
  action.sa_handler = on_stop_signal;
  sigemptyset(&action.sa_mask);
  // SA_RESETHAND: the handler runs once; a second signal takes the default action and ends prism.
  action.sa_flags = SA_RESETHAND | SA_RESTART;
  if (sigaction(signal, &action, &previous) != 0) throw std::runtime_error("cannot install a signal handler");
}

}  // namespace

StopSignals::StopSignals(std::atomic<bool>& stop) {
  static_assert(std::atomic<std::atomic<bool>*>::is_always_lock_free && std::atomic<bool>::is_always_lock_free);
  g_received = 0;
  g_stop.store(&stop);
  install(SIGINT, g_previous_int);
  install(SIGTERM, g_previous_term);
}

StopSignals::~StopSignals() {
  sigaction(SIGINT, &g_previous_int, nullptr);
  sigaction(SIGTERM, &g_previous_term, nullptr);
  g_stop.store(nullptr);
}

int StopSignals::received() { return g_received; }

const char* StopSignals::name(int signal) {
  return signal == SIGINT ? "SIGINT" : signal == SIGTERM ? "SIGTERM" : "a signal";
}

}  // namespace prism
