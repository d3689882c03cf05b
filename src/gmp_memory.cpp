#include "gmp_memory.hpp"

#include <gmp.h>

#include <atomic>
#include <climits>
#include <cstdlib>
#include <cstring>

#include <malloc.h>
#include <sys/mman.h>
#include <unistd.h>

namespace certcyl::cli {
namespace {

// The calling thread's bytes and its scope. Trivial, so the thread_local needs no guard and
// is never destroyed (GMP may free blocks while a thread or the process ends).
struct ThreadMemory {
  long long held = 0;  // bytes this thread's GMP calls allocated minus those they freed
  long long base = 0;  // held when the scope began
  long long peak = 0;  // the most of held - base in the scope
  long long limit = 0;  // 0: none
  bool in_scope = false;
  GmpMemoryEvent event = GmpMemoryEvent::none;
};
thread_local ThreadMemory t_memory;

std::atomic<bool> g_installed{false};
std::atomic<void*> g_reserve{nullptr};
// Set by install_gmp_memory() before the command starts its threads.
const char* g_command = "certcyl";
const char* g_consequence = "";
void* system_allocate(std::size_t size) { return std::malloc(size); }
void* system_reallocate(void* p, std::size_t size) { return std::realloc(p, size); }
GmpSystemAllocator g_system{system_allocate, system_reallocate};

void account(long long delta) {
  ThreadMemory& m = t_memory;
  m.held += delta;
  if (!m.in_scope) return;
  if (const long long above = m.held - m.base; above > m.peak) {
    m.peak = above;
    if (m.limit > 0 && above > m.limit && m.event == GmpMemoryEvent::none) m.event = GmpMemoryEvent::over_limit;
  }
}

long long usable(void* p) { return static_cast<long long>(malloc_usable_size(p)); }

void arm_reserve() {
  if (g_reserve.load(std::memory_order_relaxed)) return;
  void* r = mmap(nullptr, kGmpReserveBytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (r == MAP_FAILED) return;
  void* expected = nullptr;
  if (!g_reserve.compare_exchange_strong(expected, r)) munmap(r, kGmpReserveBytes);
}

// Appends text to buf (of capacity cap, used `used`) without allocating.
void append(char* buf, std::size_t cap, std::size_t& used, const char* text) {
  for (; *text && used < cap; ++text) buf[used++] = *text;
}

[[noreturn]] void out_of_memory(std::size_t size, bool released) {
  char digits[24];
  int n = 0;
  do {
    digits[n++] = static_cast<char>('0' + size % 10);
    size /= 10;
  } while (size > 0);
  char number[24];
  for (int i = 0; i < n; ++i) number[i] = digits[n - 1 - i];
  number[n] = '\0';
  char message[1024];
  std::size_t used = 0;
  append(message, sizeof message - 1, used, g_command);
  append(message, sizeof message - 1, used, ": out of memory: GMP could not allocate ");
  append(message, sizeof message - 1, used, number);
  append(message, sizeof message - 1, used, released ? " bytes, even after releasing its reserve; " : " bytes, and had no reserve left to release; ");
  append(message, sizeof message - 1, used, g_consequence);
  message[used++] = '\n';
  for (std::size_t done = 0; done < used;) {
    const ssize_t w = write(2, message + done, used - done);
    if (w <= 0) break;
    done += static_cast<std::size_t>(w);
  }
  _exit(kGmpOutOfMemoryStatus);
}

// After a failed allocation: release the reserve, mark the scope, retry once; the end when the
// retry fails too.
template <class Retry>
void* after_failure(std::size_t size, Retry retry) {
  void* reserve = g_reserve.exchange(nullptr);
  if (reserve) munmap(reserve, kGmpReserveBytes);
  if (t_memory.in_scope) t_memory.event = GmpMemoryEvent::allocation_failed;
  if (void* p = retry()) return p;
  out_of_memory(size, reserve != nullptr);
}

void* gmp_allocate(std::size_t size) {
  size = size == 0 ? 1 : size;
  void* p = g_system.allocate(size);
  if (!p) p = after_failure(size, [size] { return g_system.allocate(size); });
  account(usable(p));
  return p;
}

void* gmp_reallocate(void* old, std::size_t, std::size_t size) {
  size = size == 0 ? 1 : size;  // (realloc to 0 bytes would free the block)
  const long long before = usable(old);
  void* p = g_system.reallocate(old, size);
  if (!p) p = after_failure(size, [old, size] { return g_system.reallocate(old, size); });
  account(usable(p) - before);
  return p;
}

void gmp_free(void* p, std::size_t) {
  account(-usable(p));
  std::free(p);
}

}  // namespace

void install_gmp_memory(const char* command, const char* consequence, GmpSystemAllocator system) {
  g_command = command;
  g_consequence = consequence;
  g_system.allocate = system.allocate ? system.allocate : system_allocate;
  g_system.reallocate = system.reallocate ? system.reallocate : system_reallocate;
  if (!g_installed.exchange(true)) {
    arm_reserve();
    mp_set_memory_functions(gmp_allocate, gmp_reallocate, gmp_free);
  }
}

bool gmp_memory_installed() { return g_installed.load(); }

GmpMemoryScope::GmpMemoryScope(std::size_t limit) : limit_(limit) {
  if (g_installed.load(std::memory_order_relaxed)) arm_reserve();
  ThreadMemory& m = t_memory;
  m.in_scope = true;
  m.base = m.held;
  m.peak = 0;
  m.limit = limit > static_cast<std::size_t>(LLONG_MAX) ? LLONG_MAX : static_cast<long long>(limit);
  m.event = GmpMemoryEvent::none;
}

GmpMemoryScope::~GmpMemoryScope() {
  t_memory.in_scope = false;
  t_memory.event = GmpMemoryEvent::none;
}

GmpMemoryEvent GmpMemoryScope::event() const { return t_memory.event; }

std::size_t GmpMemoryScope::peak() const { return static_cast<std::size_t>(t_memory.peak); }

bool gmp_memory_stop(void*) { return t_memory.in_scope && t_memory.event != GmpMemoryEvent::none; }

bool gmp_reserve_armed() { return g_reserve.load() != nullptr; }

}  // namespace certcyl::cli
