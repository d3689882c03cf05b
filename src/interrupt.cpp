#include "interrupt.hpp"

#include <atomic>
#include <csignal>

#include <unistd.h>

namespace certcyl::cli {
namespace {

std::atomic<int> g_signal{0};
std::atomic<bool> g_reading{false};

extern "C" void on_signal(int sig) {
  if (g_reading.load()) _exit(128 + sig);  // nothing answered is pending: end now
  int expected = 0;
  g_signal.compare_exchange_strong(expected, sig);
}

}  // namespace

void install_interrupt_handlers() {
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = 0;
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

int interrupt_signal() { return g_signal.load(); }

InterruptibleRead::InterruptibleRead() {
  g_reading.store(true);
  // A signal that came while the flag was down is honoured now.
  if (const int sig = g_signal.load()) _exit(128 + sig);
}

InterruptibleRead::~InterruptibleRead() { g_reading.store(false); }

}  // namespace certcyl::cli
