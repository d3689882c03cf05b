// GMP's memory in the streaming commands (query, scene): accounted per unit of work, never the
// end of the process while memory can still be found, and a clean end when it cannot.
//
// GMP (and MPFR, which allocates through GMP's functions) must not get back a failed
// allocation, and nothing may be thrown or longjmp'd through it; by default it prints a message
// and aborts. install_gmp_memory() replaces its memory functions with ones that:
//   - count, per thread, the bytes GMP holds (malloc_usable_size of each block), so that a
//     GmpMemoryScope knows the most its unit of work held above what the thread held when the
//     scope began, and raises GmpMemoryEvent::over_limit when that exceeds the scope's limit (a
//     soft limit: the allocation still succeeds);
//   - on a failed allocation, release an emergency reserve (kGmpReserveBytes of address space,
//     mapped at installation when it can be and never touched, so it holds no resident memory;
//     under an address-space limit near the process's own size it may not be) and retry,
//     raising GmpMemoryEvent::allocation_failed in the thread's scope: the evaluation in progress
//     finishes, and the command ends the unit of work as out of memory. The next scope maps the
//     reserve again (when it can);
//   - when the retry fails too, write one line to standard error with write(2) (the command's
//     name, the size, whether a reserve was released, and `consequence`) and end the process
//     with _exit(kGmpOutOfMemoryStatus).
// Nothing is flushed at that end: the command must keep its output so that, whenever GMP may
// allocate, every byte it gave its output stream has reached the operating system and forms
// complete lines (query and scene flush after each batch or chunk of lines and compute nothing
// while writing), so that the end never leaves a cut line.
//
// The stop predicate gmp_memory_stop() tells the certified cylinder-pair query
// (CylinderCylinderOptions::stop) to stop at its next check once the thread's scope has an event.
#pragma once

#include <cstddef>

namespace certcyl::cli {

// The exit status of a process that GMP's allocation failed even after the reserve.
inline constexpr int kGmpOutOfMemoryStatus = 3;
// The emergency reserve.
inline constexpr std::size_t kGmpReserveBytes = std::size_t{16} << 20;

// The system allocator behind GMP's functions (std::malloc and std::realloc); replaceable to
// test the failure paths.
struct GmpSystemAllocator {
  void* (*allocate)(std::size_t) = nullptr;
  void* (*reallocate)(void*, std::size_t) = nullptr;
};

// Installs the functions (before any other use of GMP, so that every block GMP frees is one the
// functions could count; later installations only change `command`, `consequence` and the
// system allocator). command: "certcyl query"; consequence: what the fatal message says of the
// output. Both must outlive the process (string literals).
void install_gmp_memory(const char* command, const char* consequence, GmpSystemAllocator system = {});

// Whether install_gmp_memory() was called.
bool gmp_memory_installed();

// over_limit: the work held more than its scope's limit. allocation_failed: an allocation failed
// and was retried after the reserve was released (whether it was still mapped or not).
enum class GmpMemoryEvent { none, over_limit, allocation_failed };

// The GMP memory of one unit of work (a query line, a scene pair) on the calling thread, from
// construction to destruction; scopes do not nest. Maps the reserve again when it was released.
// Without install_gmp_memory() it sees nothing (event() stays none, peak() 0).
class GmpMemoryScope {
 public:
  // limit: the most bytes the work may hold above the thread's bytes at construction; 0 is none.
  explicit GmpMemoryScope(std::size_t limit = 0);
  ~GmpMemoryScope();
  GmpMemoryScope(const GmpMemoryScope&) = delete;
  GmpMemoryScope& operator=(const GmpMemoryScope&) = delete;

  // The scope's event (allocation_failed replaces over_limit).
  GmpMemoryEvent event() const;
  // The most bytes the work held so far above the thread's bytes at construction.
  std::size_t peak() const;
  std::size_t limit() const { return limit_; }

 private:
  std::size_t limit_;
};

// True when the calling thread's scope has an event (for CylinderCylinderOptions::stop; the
// context is not used).
bool gmp_memory_stop(void* context = nullptr);

// Whether the emergency reserve is mapped now.
bool gmp_reserve_armed();

}  // namespace certcyl::cli
