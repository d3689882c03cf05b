// The serial methods' calls in a child process (ChildRunner of study_internal.hpp): CORE::Expr
// ends its process on some inputs (std::exit(1) on a "possible zero divisor" in its BigFloat
// division, SIGFPE from GMP on a non-finite double), and a call that ends the child must not
// end the study. The child is a fork of the study taken on the main thread while no other
// thread runs, so it holds the methods already; a call sends the method's index and the input
// and receives the output. A call that ends the child is answered `ended` (with the exit status
// or the signal; its time is the time until the child ended), and the next call forks a new
// child.
#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstring>
#include <iostream>
#include <stdexcept>

#include <sys/wait.h>
#include <unistd.h>

#include "fd_io.hpp"
#include "study_internal.hpp"

namespace certcyl::cli::detail {
using namespace certcyl::study;

namespace {

// One call's request: the method's index, whether it is timed, the input's length; then the
// input's doubles.
struct Request {
  std::uint32_t method = 0;
  std::uint32_t timed = 0;
  std::uint32_t size = 0;
};

// One call's answer.
struct Reply {
  std::int32_t answer = 0;
  std::uint8_t intersecting = 0, error = 0, invalid = 0;
  double t_in = 0, ns = 0;
};

[[noreturn]] void serve(const std::vector<const Method*>& methods, int in, int out) {
  for (;;) {
    Request q;
    if (!read_all(in, &q, sizeof q)) _exit(0);  // the study closed the pipe: done
    std::vector<double> x(q.size);
    if (!read_all(in, x.data(), x.size() * sizeof(double)) || q.method >= methods.size()) _exit(2);
    const Method& m = *methods[q.method];
    MethodOutput o;
    double ns = 0;
    if (q.timed != 0) {
      std::tie(o, ns) = run_timed(m, x);
    } else {
      o = run_quiet(m, x);
    }
    Reply r;
    r.answer = static_cast<std::int32_t>(o.answer);
    r.intersecting = o.intersecting, r.error = o.error, r.invalid = o.invalid;
    r.t_in = o.t_in, r.ns = ns;
    if (!write_all(out, &r, sizeof r)) _exit(3);
  }
}

}  // namespace

ChildRunner::ChildRunner(std::vector<const Method*> methods) : methods_(std::move(methods)) {}

ChildRunner::~ChildRunner() { stop(); }

void ChildRunner::stop() {
  if (pid_ <= 0) return;
  ::close(to_child_), ::close(from_child_);  // the child reads end of file and exits
  int status = 0;
  while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
  }
  pid_ = -1;
}

bool ChildRunner::start() {
  int down[2], up[2];
  if (::pipe(down) != 0) return false;
  if (::pipe(up) != 0) {
    ::close(down[0]), ::close(down[1]);
    return false;
  }
  std::cout.flush(), std::cerr.flush();  // nothing buffered is written twice
  const pid_t pid = ::fork();
  if (pid < 0) {
    for (int fd : {down[0], down[1], up[0], up[1]}) ::close(fd);
    return false;
  }
  if (pid == 0) {
    ::close(down[1]), ::close(up[0]);
    serve(methods_, down[0], up[1]);
  }
  ::close(down[0]), ::close(up[1]);
  pid_ = pid, to_child_ = down[1], from_child_ = up[0];
  return true;
}

ChildCall ChildRunner::run(const Method& m, const std::vector<double>& x, bool timed) {
  const auto it = std::find(methods_.begin(), methods_.end(), &m);
  if (it == methods_.end()) throw std::logic_error("ChildRunner: " + m.name() + " is not one of its methods");
  const std::size_t method = static_cast<std::size_t>(it - methods_.begin());
  ChildCall call;
  if (pid_ <= 0 && !start()) {  // no child to be had (no process or pipe left): in this process
    call.isolated = false;
    if (timed) {
      std::tie(call.out, call.ns) = run_timed(m, x);
    } else {
      call.out = run_quiet(m, x);
    }
    return call;
  }
  const auto t0 = std::chrono::steady_clock::now();
  Request q;
  q.method = static_cast<std::uint32_t>(method), q.timed = timed ? 1 : 0, q.size = static_cast<std::uint32_t>(x.size());
  Reply r;
  if (write_all(to_child_, &q, sizeof q) && write_all(to_child_, x.data(), x.size() * sizeof(double)) && read_all(from_child_, &r, sizeof r)) {
    call.out.answer = static_cast<Answer>(r.answer);
    call.out.intersecting = r.intersecting != 0, call.out.error = r.error != 0, call.out.invalid = r.invalid != 0;
    call.out.t_in = r.t_in, call.ns = r.ns;
    return call;
  }
  // The child ended during the call: how, and a new child for the next call.
  ::close(to_child_), ::close(from_child_);
  int status = 0;
  while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
  }
  pid_ = -1;
  call.ended = true;
  call.out.error = true;
  call.ns = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count();
  if (WIFSIGNALED(status)) {
    const char* name = ::strsignal(WTERMSIG(status));
    call.reason = "signal " + std::to_string(WTERMSIG(status)) + " (" + (name != nullptr ? name : "unknown") + ")";
  } else if (WIFEXITED(status)) {
    call.reason = "exit status " + std::to_string(WEXITSTATUS(status));
  } else {
    call.reason = "ended";
  }
  return call;
}

}  // namespace certcyl::cli::detail
