// The study's serial methods run in a child process (src/study_child.cpp): a method that ends
// its process (as CORE::Expr does with exit(1) on a "possible zero divisor", or by a signal) on
// one input costs that input's answer, which becomes process_ended (an error), and nothing else:
// the other inputs are answered, by a new child, and the study's process goes on. The methods
// here are the test's own, ending their process on chosen inputs; their other answers are fixed.
#define BOOST_TEST_MODULE study_isolation
#include <boost/test/unit_test.hpp>

#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "study_internal.hpp"

using namespace certcyl;
using namespace certcyl::study;
using namespace certcyl::cli;
using namespace certcyl::cli::detail;

namespace {

// Ends its process with exit status 1 when x[0] is `exit_at`, by SIGFPE when it is `signal_at`;
// otherwise answers overlapping with t_in = x[0] (so each answer shows which input it belongs to).
Method ending_method(const std::string& name, double exit_at, double signal_at, Query q = Query::line_cylinder) {
  Method m;
  m.base = name;
  m.nt = "test";
  m.query = q;
  m.serial = true;
  m.run = [exit_at, signal_at](const std::vector<double>& x) {
    if (x.at(0) == exit_at) std::exit(1);
    if (x.at(0) == signal_at) {
      std::signal(SIGFPE, SIG_DFL);  // as in the command: the test framework's handler is not the study's
      std::raise(SIGFPE);
    }
    return three_valued(Answer::overlapping, x.at(0));
  };
  return m;
}

struct IgnorePipe {
  IgnorePipe() { std::signal(SIGPIPE, SIG_IGN); }  // as certcyl_main.cpp does
};

}  // namespace

BOOST_AUTO_TEST_CASE(a_call_that_ends_the_child_is_answered_and_the_next_runs_in_a_new_child) {
  IgnorePipe ignore;
  const Method a = ending_method("a", 13, 14), b = ending_method("b", -1, -1);
  ChildRunner child({&a, &b});
  const pid_t self = ::getpid();
  for (double v : {1.0, 2.0}) {
    const ChildCall c = child.run(a, {v}, /*timed=*/true);
    BOOST_TEST(!c.ended);
    BOOST_TEST(c.isolated);
    BOOST_TEST(to_string(c.out.answer) == "overlapping");
    BOOST_TEST(c.out.t_in == v);
    BOOST_TEST(c.ns > 0);
  }
  const ChildCall exited = child.run(a, {13.0}, true);
  BOOST_TEST(exited.ended);
  BOOST_TEST(exited.out.error);
  BOOST_TEST(exited.reason == "exit status 1");
  BOOST_TEST(answer_code(exited.out) == 'e');
  const ChildCall next = child.run(b, {13.0}, false);  // the other method, in a new child
  BOOST_TEST(!next.ended);
  BOOST_TEST(next.out.t_in == 13.0);
  const ChildCall signalled = child.run(a, {14.0}, false);
  BOOST_TEST(signalled.ended);
  BOOST_TEST(signalled.reason.rfind("signal " + std::to_string(SIGFPE) + " (", 0) == 0, signalled.reason);
  const ChildCall after = child.run(a, {3.0}, false);
  BOOST_TEST(!after.ended);
  BOOST_TEST(after.out.t_in == 3.0);
  BOOST_TEST(::getpid() == self);  // this process is still the one running
  const Method other = ending_method("other", -1, -1);
  BOOST_CHECK_THROW(child.run(other, {1.0}, false), std::logic_error);  // not one of its methods
}

// The instances stage: a serial method that ends its process on two inputs of a tiny study's
// plan answers process_ended (outcome error) on exactly those two rows; every other row of that
// method and of a second serial method is answered, in the study's row order.
BOOST_AUTO_TEST_CASE(the_instances_stage_answers_process_ended_only_where_the_method_ended) {
  IgnorePipe ignore;
  StudyOptions o;
  o.size = "tiny";
  o.progress = false;
  o.plots = false;
  o.threads = 2;
  configure_study(o, {});
  std::vector<Planned> plan = plan_instances(o);
  std::vector<double> firsts;  // the first coordinate of each line-cylinder instance
  for (const Planned& p : plan)
    if (p.inst.query == Query::line_cylinder) firsts.push_back(p.inst.x.at(0));
  BOOST_TEST_REQUIRE(firsts.size() > 10);
  std::map<double, int> count;
  for (double v : firsts) ++count[v];
  // Two inputs whose first coordinate no other instance shares.
  std::vector<double> unique;
  for (double v : firsts)
    if (count[v] == 1) unique.push_back(v);
  BOOST_TEST_REQUIRE(unique.size() >= 2);
  const double exit_at = unique[unique.size() / 3], signal_at = unique[2 * unique.size() / 3];
  Registry registry{ending_method("ends", exit_at, signal_at), ending_method("steady", -1, -1)};
  const std::vector<std::vector<Row>> rows = run_instances(o, registry, plan);
  BOOST_TEST_REQUIRE(rows.size() == plan.size());
  long ended = 0, answered = 0, steady = 0;
  for (std::size_t i = 0; i < plan.size(); ++i) {
    if (plan[i].inst.query != Query::line_cylinder) {
      BOOST_TEST(rows[i].empty());
      continue;
    }
    BOOST_TEST_REQUIRE(rows[i].size() == 2u);  // both methods (stride 1), in registry order
    const Row& r = rows[i][0];
    BOOST_TEST(r.method == "ends/test");
    BOOST_TEST(rows[i][1].method == "steady/test");
    BOOST_TEST(rows[i][1].answer == "overlapping");
    ++steady;
    const double v = plan[i].inst.x.at(0);
    if (v == exit_at || v == signal_at) {
      ++ended;
      BOOST_TEST(r.answer == "process_ended");
      BOOST_TEST(r.outcome == "error");
    } else {
      ++answered;
      BOOST_TEST(r.answer == "overlapping");
    }
  }
  BOOST_TEST(ended == 2);
  BOOST_TEST(answered + ended == static_cast<long>(firsts.size()));
  BOOST_TEST(steady == static_cast<long>(firsts.size()));
}
