// GMP's memory functions of the streaming commands (src/gmp_memory.hpp), installed in this
// process over a system allocator that fails on request: a scope's count of the bytes GMP holds
// and its limit, per thread; a failed allocation retried after the reserve is released, and the
// reserve mapped again by the next scope; `certcyl query`'s lines over --memory-limit or after a
// failed allocation answered with an error line, the next line as usual; and, when the retry
// fails too, the end of the process with status 3, its message, and only complete lines written.
#define BOOST_TEST_MODULE gmp_memory
#include <boost/test/unit_test.hpp>

#include <gmp.h>

#include <climits>
#include <cstdint>
#include <cstdlib>
#include <ext/stdio_filebuf.h>
#include <sstream>
#include <string>
#include <thread>

#include <sys/wait.h>
#include <unistd.h>

#include "gmp_memory.hpp"
#include "query.hpp"

using namespace certcyl::cli;

namespace {

// The system allocator under test: requests of at least g_fail_size bytes fail, g_failures
// times (then succeed again).
std::size_t g_fail_size = SIZE_MAX;
long g_failures = 0;
bool fails(std::size_t size) { return size >= g_fail_size && g_failures > 0 && g_failures-- > 0; }
void* test_allocate(std::size_t size) { return fails(size) ? nullptr : std::malloc(size); }
void* test_reallocate(void* p, std::size_t size) { return fails(size) ? nullptr : std::realloc(p, size); }

struct Installed {
  Installed() {
    install_gmp_memory("certcyl test", "the test's consequence", {test_allocate, test_reallocate});
  }
};
BOOST_TEST_GLOBAL_FIXTURE(Installed);

// Makes x hold about `bytes` bytes of limbs.
void grow(mpz_t x, std::size_t bytes) { mpz_setbit(x, 8 * bytes); }

std::string cylinder(const std::string& x, const std::string& top) {
  return R"({"p0":[)" + x + R"(,0,0],"p1":[)" + x + ",0," + top + R"(],"radius":1})";
}
std::string pair_line(int id, const std::string& a, const std::string& b) {
  return R"({"id":)" + std::to_string(id) + R"(,"query":"cylinder_cylinder","a":)" + a + R"(,"b":)" + b + "}";
}
// Two unit cylinders 3 apart, as doubles, and with a top of 15,000 digits (about 50,000 bits).
const std::string small_pair = pair_line(1, cylinder("0", "2"), cylinder("3", "2"));
const std::string big_pair = pair_line(2, cylinder("0", '"' + std::string(14999, '7') + "1\""), cylinder("3", '"' + std::string(14999, '3') + "9\""));

}  // namespace

BOOST_AUTO_TEST_CASE(a_scope_counts_the_bytes_gmp_holds_above_its_start_and_its_limit) {
  BOOST_TEST_REQUIRE(gmp_memory_installed());
  mpz_t before, x;
  mpz_init(before);
  grow(before, 1 << 20);  // held before the scope: not the scope's
  {
    const GmpMemoryScope scope(1 << 20);
    mpz_init(x);
    grow(x, 100000);
    BOOST_TEST(scope.peak() >= 100000u);
    BOOST_TEST(scope.peak() < 200000u);
    BOOST_TEST((scope.event() == GmpMemoryEvent::none));
    BOOST_TEST(!gmp_memory_stop());
    grow(x, 2 << 20);  // a realloc past the limit
    BOOST_TEST((scope.event() == GmpMemoryEvent::over_limit));
    BOOST_TEST(gmp_memory_stop());
    BOOST_TEST(scope.peak() >= (2u << 20));
    mpz_clear(x);
    BOOST_TEST((scope.event() == GmpMemoryEvent::over_limit));  // it stays
    BOOST_TEST(scope.peak() >= (2u << 20));
  }
  mpz_clear(before);
  BOOST_TEST(!gmp_memory_stop());  // no scope
  {
    const GmpMemoryScope unlimited;
    mpz_init(x);
    grow(x, 4 << 20);
    BOOST_TEST((unlimited.event() == GmpMemoryEvent::none));
    BOOST_TEST(unlimited.peak() >= (4u << 20));
    mpz_clear(x);
  }
  // Another thread's scope counts its own thread's blocks only.
  const GmpMemoryScope scope(1 << 20);
  GmpMemoryEvent other = GmpMemoryEvent::none;
  std::thread([&other] {
    const GmpMemoryScope its(1 << 20);
    mpz_t y;
    mpz_init(y);
    grow(y, 2 << 20);
    mpz_clear(y);
    other = its.event();
  }).join();
  BOOST_TEST((other == GmpMemoryEvent::over_limit));
  BOOST_TEST((scope.event() == GmpMemoryEvent::none));
  BOOST_TEST(scope.peak() == 0u);
}

BOOST_AUTO_TEST_CASE(a_failed_allocation_is_retried_after_the_reserve_is_released) {
  BOOST_TEST_REQUIRE(gmp_reserve_armed());
  for (const bool realloc_path : {false, true}) {
    {
      const GmpMemoryScope scope;
      mpz_t x;
      mpz_init(x);
      if (realloc_path) grow(x, 10);
      g_fail_size = 1 << 20, g_failures = 1;
      grow(x, 2 << 20);  // fails once, then succeeds from the retry
      BOOST_TEST(g_failures == 0);
      BOOST_TEST(mpz_sizeinbase(x, 2) == 8u * (2u << 20) + 1);
      BOOST_TEST((scope.event() == GmpMemoryEvent::allocation_failed));
      BOOST_TEST(gmp_memory_stop());
      BOOST_TEST(!gmp_reserve_armed());
      mpz_clear(x);
    }
    g_fail_size = SIZE_MAX;
    const GmpMemoryScope next;  // maps the reserve again
    BOOST_TEST(gmp_reserve_armed());
    BOOST_TEST((next.event() == GmpMemoryEvent::none));
  }
}

BOOST_AUTO_TEST_CASE(query_lines_out_of_gmp_memory_are_error_lines_and_the_next_lines_are_answered) {
  QueryOptions plain;
  const std::string small_answer = answer_line(small_pair, plain, 1).dump();
  BOOST_TEST(small_answer.find(R"("answer":"separated")") != std::string::npos);
  const std::string big_answer = answer_line(big_pair, plain, 2).dump();
  BOOST_TEST(big_answer.find(R"("answer":"separated")") != std::string::npos);

  QueryOptions limited;
  limited.memory_limit_bytes = 64 << 10;
  BOOST_TEST(answer_line(small_pair, limited, 1).dump() == small_answer);
  BOOST_TEST(answer_line(big_pair, limited, 2).dump() ==
             R"j({"id":2,"line":2,"error":"out of memory answering this line: its GMP memory went over the limit of 65536 bytes (--memory-limit)"})j");
  BOOST_TEST(answer_line(small_pair, limited, 3).dump() == small_answer);

  // A failed allocation: the line is an error, the reserve is back for the next line.
  g_fail_size = 4096, g_failures = 1;
  BOOST_TEST(answer_line(big_pair, plain, 2).dump() ==
             R"({"id":2,"line":2,"error":"out of memory answering this line: an allocation of GMP failed"})");
  g_fail_size = SIZE_MAX;
  BOOST_TEST(answer_line(big_pair, plain, 2).dump() == big_answer);
  BOOST_TEST(gmp_reserve_armed());
}

// In a child process: every GMP request of 4096 bytes or more fails, also after the reserve is
// released. The big line's numbers need such blocks, the small line's do not.
BOOST_AUTO_TEST_CASE(when_the_retry_fails_too_the_process_ends_with_status_3_after_complete_lines_only) {
  for (const bool line_buffered : {true, false}) {
    QueryOptions options;
    options.line_buffered = line_buffered;
    const std::string first = answer_line(small_pair, options, 1).dump();
    int out_pipe[2], err_pipe[2];
    BOOST_TEST_REQUIRE(pipe(out_pipe) == 0);
    BOOST_TEST_REQUIRE(pipe(err_pipe) == 0);
    const pid_t pid = fork();
    BOOST_TEST_REQUIRE(pid >= 0);
    if (pid == 0) {
      close(out_pipe[0]), close(err_pipe[0]);
      dup2(err_pipe[1], 2);
      install_gmp_memory("certcyl query", "the consequence", {test_allocate, test_reallocate});
      g_fail_size = 4096, g_failures = LONG_MAX;
      __gnu_cxx::stdio_filebuf<char> buf(out_pipe[1], std::ios::out);
      std::ostream out(&buf);
      std::istringstream in(small_pair + "\n" + big_pair + "\n" + small_pair + "\n");
      run_query(in, out, options, 2);
      _exit(99);  // not reached
    }
    close(out_pipe[1]), close(err_pipe[1]);
    const auto read_all = [](int fd) {
      std::string s;
      char b[4096];
      for (ssize_t n; (n = read(fd, b, sizeof b)) > 0;) s.append(b, static_cast<std::size_t>(n));
      close(fd);
      return s;
    };
    const std::string out = read_all(out_pipe[0]);
    const std::string err = read_all(err_pipe[0]);
    int status = 0;
    waitpid(pid, &status, 0);
    BOOST_TEST(WIFEXITED(status));
    BOOST_TEST(WEXITSTATUS(status) == kGmpOutOfMemoryStatus);
    // --line-buffered: the first line was answered and written before the second began;
    // in one batch, nothing was written: never a cut line.
    BOOST_TEST(out == (line_buffered ? first + "\n" : std::string()));
    BOOST_TEST(err.rfind("certcyl query: out of memory: GMP could not allocate ", 0) == 0);
    BOOST_TEST(err.find(" bytes, even after releasing its reserve; the consequence\n") != std::string::npos);
    BOOST_TEST(err.find('\n') == err.size() - 1);
  }
}
