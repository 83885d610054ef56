// `surfcert batch --mpi` (app/batch_mpi.hpp) under `mpirun -n 3` against the single-process
// batch on the same lines (the independent route: no MPI, no compute child, no scheduler):
// the same answers byte for byte apart from "time_ms" (ordered, unordered as a multiset, one
// rank; a budget-stopped answer by id, status and reason: see comparable()), bad option
// combinations exit 2; resume after SIGKILL of rank 0 from the checkpoint; a killed compute
// child (lines retried; a line lost twice is an internal error line); a killed worker rank
// under `mpirun --enable-recovery` (its lines retried by the other worker, or by rank 0 once no
// worker is left); --retry-undecided. The `surfcert` these tests run does not load libmpi:
// its batch --mpi execs the surfcert-mpi next to it (app/CMakeLists.txt), so every test here
// goes through that exec; without surfcert-mpi, --mpi exits 2 naming the missing file.
#include "surfcert/core/io/json.hpp"

#include <gtest/gtest.h>

#include <dirent.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <map>
#include <thread>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

using surfcert::core::io::Json;

namespace {

struct Outcome {
  int code;
  std::string out, err;
};

std::string tmp_path(const std::string& name) {
  return (::testing::TempDir().empty() ? std::string("/tmp/") : ::testing::TempDir()) +
         "surfcert_mpi_" + std::to_string(getpid()) + "_" + name;
}

std::string slurp(const std::string& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

// Runs a shell command with stdin from in_path.
Outcome sh(const std::string& cmd, const std::string& in_path) {
  const std::string out = tmp_path("stdout"), err = tmp_path("stderr");
  const int st = std::system((cmd + " <" + in_path + " >" + out + " 2>" + err).c_str());
  Outcome r{WIFEXITED(st) ? WEXITSTATUS(st) : -1, slurp(out), slurp(err)};
  std::remove(out.c_str());
  std::remove(err.c_str());
  return r;
}

// mpirun as the tests run it: root allowed (CI containers), more ranks than cores, and the
// leak checker off in the ranks (Open MPI's own allocations outlive MPI_Finalize).
std::string mpirun(int ranks) {
  return std::string("env ASAN_OPTIONS=detect_leaks=0 ") + SURFCERT_MPIEXEC +
         " --allow-run-as-root --oversubscribe -x ASAN_OPTIONS -n " + std::to_string(ranks) + " ";
}

std::string untimed(const std::string& out) {
  static const std::regex time_field(R"(,"time_ms":[0-9.]+)");
  return std::regex_replace(out, time_field, "");
}

// What two runs of the same lines must agree on: every answer without its "time_ms", except
// that an answer stopped by its budget is compared by id, status and reason only (which route
// the budget stopped, and what it had established by then, depends on the wall clock: two
// runs of the single-process batch differ there too).
std::string comparable(const std::string& out) {
  std::istringstream in(untimed(out));
  std::string l, r;
  while (std::getline(in, l)) {
    if (l.find("\"reason\":\"budget\"") != std::string::npos) {
      const Json a = surfcert::core::io::parse_json(l, "answer");
      const Json* reason = a.find("reason");
      if (a.find("status")->text() == "undecided" && reason && reason->text() == "budget") {
        Json b = Json::object();
        b.set("id", *a.find("id"));
        b.set("status", *a.find("status"));
        b.set("reason", *reason);
        l = surfcert::core::io::dump(b);
      }
    }
    r += l + "\n";
  }
  return r;
}

std::vector<std::string> sorted_lines(const std::string& text) {
  std::vector<std::string> v;
  std::istringstream in(text);
  std::string l;
  while (std::getline(in, l))
    v.push_back(l);
  std::sort(v.begin(), v.end());
  return v;
}

// Two tori 1e-20 apart: the distance's branch and bound runs for minutes, so a budget of
// budget_ms always ends it undecided (reason "budget").
std::string budget_line(const std::string& id, int budget_ms) {
  return R"({"id":")" + id +
         R"(","op":"distance","a":{"type":"torus","center":[0,0,0],"axis":[0,0,1],)"
         R"("major_radius":3,"minor_radius":1},"b":{"type":"torus","center":)"
         R"(["799999999999999999999/100000000000000000000",0,0],"axis":[0,0,1],"major_radius":3,)"
         R"("minor_radius":1},"budget_ms":)" +
         std::to_string(budget_ms) + "}";
}

// classify (generated, labelled), distance (generated), intersect, error and budget-limited
// lines, interleaved.
std::string mixed_input() {
  const std::string gen = tmp_path("gen");
  const std::string bin = SURFCERT_BINARY;
  const std::string cmd = "(" + bin +
                          " generate --case all --count 1 --seed 3 --encoding double; " + bin +
                          " generate --case distance --count 1 --seed 5) > " + gen;
  EXPECT_EQ(std::system(cmd.c_str()), 0);
  std::vector<std::string> lines;
  std::istringstream g(slurp(gen));
  std::remove(gen.c_str());
  std::string l;
  while (std::getline(g, l))
    lines.push_back(l);
  const std::vector<std::string> extra = {
      R"({"id":"i1","op":"intersect","a":"x^2+y^2+z^2=1","b":"x^2+y^2/4=0.5"})",
      R"({"id":"i2","op":"intersect","a":"x^2+y^2-1=0","b":"x^2+z^2-1=0","box":[-2,-2,-2,2,2,2]})",
      R"({"id":"e1","op":"classify","a":"x^2+","b":"y=0"})",
      "not json at all",
      R"({"id":"e2","op":"frobnicate","a":"x=0","b":"y=0"})",
      budget_line("slow1", 30),
      R"({"id":"d1","op":"distance","a":"x^2+y^2+z^2=1","b":"(x-3)^2+y^2+z^2=1","detail":"value"})",
      "",
      budget_line("slow2", 50),
      R"({"id":"c1","op":"classify","a":"x^2+y^2+z^2=1","b":"x^2+y^2=0.25","detail":"topology"})",
  };
  std::string in;
  for (size_t i = 0; i < std::max(lines.size(), extra.size()); ++i) {
    if (i < lines.size()) in += lines[i] + "\n";
    if (i < extra.size()) in += extra[i] + "\n";
  }
  return in;
}

// The records of a checkpoint file per line number (batch_checkpoint.hpp: "<line_no> ...").
std::map<long, int> checkpoint_counts(const std::string& path) {
  std::map<long, int> n;
  std::istringstream in(slurp(path));
  std::string l;
  while (std::getline(in, l))
    ++n[std::stol(l)];
  return n;
}

long count_records(const std::map<long, int>& m) {
  long n = 0;
  for (const auto& [no, k] : m)
    n += k;
  return n;
}

// Starts a shell command in the background (its stdin, stdout, stderr redirected); its pid.
pid_t start(const std::string& cmd) {
  const pid_t pid = fork();
  if (pid == 0) {
    execl("/bin/sh", "sh", "-c", ("exec " + cmd).c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  return pid;
}

// The processes whose parent is ppid and whose command line contains what.
std::vector<pid_t> children_of(pid_t ppid, const std::string& what) {
  std::vector<pid_t> out;
  DIR* d = opendir("/proc");
  if (!d) return out;
  while (dirent* e = readdir(d)) {
    const pid_t pid = static_cast<pid_t>(std::atol(e->d_name));
    if (pid <= 0) continue;
    std::istringstream st(slurp("/proc/" + std::to_string(pid) + "/stat"));
    std::string tok;
    pid_t parent = 0;
    // pid (comm) state ppid: comm has no spaces here (surfcert, mpirun, sh).
    st >> tok >> tok >> tok >> parent;
    if (parent != ppid) continue;
    std::string cmdline = slurp("/proc/" + std::to_string(pid) + "/cmdline");
    std::replace(cmdline.begin(), cmdline.end(), '\0', ' ');
    if (cmdline.find(what) != std::string::npos) out.push_back(pid);
  }
  closedir(d);
  return out;
}

// The rank of an MPI process, from the environment Open MPI gives it (-1: not one).
int rank_of(pid_t pid) {
  const std::string env = slurp("/proc/" + std::to_string(pid) + "/environ");
  const std::string key = std::string("OMPI_COMM_WORLD_RANK=");
  const size_t at = env.find(key);
  return at == std::string::npos ? -1 : std::atoi(env.c_str() + at + key.size());
}

// The CPU time (user + system, clock ticks) of a process so far.
long cpu_ticks(pid_t pid) {
  std::istringstream st(slurp("/proc/" + std::to_string(pid) + "/stat"));
  std::string tok;
  long utime = 0, stime = 0;
  for (int field = 1; field <= 13; ++field)
    st >> tok; // pid (comm) state ppid ... cmajflt: comm has no spaces here
  st >> utime >> stime;
  return utime + stime;
}

int wait_exit(pid_t pid) {
  int st = 0;
  waitpid(pid, &st, 0);
  return WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
}

// wait_exit, but a run still going after `seconds` (it hangs: the failure this guards against)
// is ended (SIGTERM: mpirun takes its ranks with it) and reported as -1.
int wait_exit_within(pid_t pid, int seconds) {
  int st = 0;
  for (int i = 0; i < seconds * 20; ++i) {
    if (waitpid(pid, &st, WNOHANG) == pid)
      return WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  kill(pid, SIGTERM);
  std::this_thread::sleep_for(std::chrono::seconds(5));
  kill(pid, SIGKILL);
  waitpid(pid, &st, 0);
  return -1;
}

// Lines that take a while: budget-limited tori (budget_ms each, always undecided) between
// fast classify lines.
std::string slow_input(int slow, int budget_ms) {
  std::string in;
  for (int i = 0; i < slow; ++i) {
    in += budget_line("slow" + std::to_string(i), budget_ms) + "\n";
    for (int k = 0; k < 3; ++k)
      in += R"({"id":")" + std::to_string(i) + "-" + std::to_string(k) +
            R"(","op":"classify","a":"x^2+y^2+z^2=1","b":"x^2+y^2=0.)" + std::to_string(k + 1) +
            "\"}\n";
  }
  return in;
}

class BatchMpi : public ::testing::Test {
protected:
  void SetUp() override {
    in_ = tmp_path("in");
    std::ofstream(in_) << mixed_input();
    single_ = sh(std::string(SURFCERT_BINARY) + " batch --threads 2", in_);
    ASSERT_EQ(single_.code, 2) << single_.err; // the input has bad lines
  }
  void TearDown() override { std::remove(in_.c_str()); }
  std::string in_;
  Outcome single_;
};

} // namespace

TEST_F(BatchMpi, ThreeRanksAnswerLikeTheSingleProcessBatch) {
  const Outcome mpi = sh(mpirun(3) + SURFCERT_BINARY + " batch --mpi", in_);
  EXPECT_EQ(mpi.code, single_.code) << mpi.err;
  EXPECT_EQ(comparable(mpi.out), comparable(single_.out));
  // Every kind of line was there: certified, undecided (budget), input errors.
  EXPECT_NE(single_.out.find("\"reason\":\"budget\""), std::string::npos);
  EXPECT_NE(single_.out.find("\"branches\":"), std::string::npos);
  EXPECT_NE(single_.out.find("\"kind\":\"input\""), std::string::npos);
}

TEST_F(BatchMpi, UnorderedAndOneRankGiveTheSameAnswers) {
  const Outcome un = sh(mpirun(3) + SURFCERT_BINARY + " batch --mpi --unordered --threads 2", in_);
  EXPECT_EQ(un.code, single_.code) << un.err;
  EXPECT_EQ(sorted_lines(comparable(un.out)), sorted_lines(comparable(single_.out)));
  const Outcome one = sh(mpirun(1) + SURFCERT_BINARY + " batch --mpi", in_);
  EXPECT_EQ(one.code, single_.code) << one.err;
  EXPECT_EQ(comparable(one.out), comparable(single_.out));
}

TEST_F(BatchMpi, OptionsThatNeedMpiAreRefusedWithout) {
  const std::string bin = SURFCERT_BINARY;
  EXPECT_EQ(sh(bin + " batch --checkpoint " + tmp_path("ck"), in_).code, 2);
  EXPECT_EQ(sh(bin + " batch --retry-undecided 1000", in_).code, 2);
  EXPECT_EQ(sh(bin + " batch --mpi --retry-undecided 0", in_).code, 2);
}

// SIGKILL to rank 0 midway (after some answers are in the checkpoint), then the same command
// again: the same final output as the single-process batch, and every line recorded exactly
// once (the restarted run computed only the lines the first one had not answered).
TEST(BatchMpiResume, KilledRootResumesFromTheCheckpoint) {
  const std::string in = tmp_path("slow_in"), out = tmp_path("slow_out"), ck = tmp_path("ck");
  std::remove(ck.c_str());
  const int kSlow = 12;
  std::ofstream(in) << slow_input(kSlow, 400);
  const long total = 4 * kSlow;
  const Outcome single = sh(std::string(SURFCERT_BINARY) + " batch --threads 2", in);
  ASSERT_EQ(single.code, 3) << single.err; // the budget-limited lines
  const std::string cmd =
      mpirun(3) + SURFCERT_BINARY + " batch --mpi --checkpoint " + ck + " <" + in + " >" + out;
  const pid_t run = start(cmd + " 2>/dev/null");
  long before = 0;
  pid_t root = -1;
  for (int i = 0; i < 6000 && before < 6; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    before = count_records(checkpoint_counts(ck));
  }
  for (pid_t p : children_of(run, "surfcert"))
    if (rank_of(p) == 0) root = p;
  ASSERT_GT(root, 0) << "rank 0 not found";
  ASSERT_EQ(kill(root, SIGKILL), 0);
  EXPECT_NE(wait_exit(run), 0);
  const auto first = checkpoint_counts(ck);
  const long answered = count_records(first);
  ASSERT_GE(answered, 6);
  ASSERT_LT(answered, total) << "the run ended before it was killed";
  for (const auto& [no, k] : first)
    EXPECT_EQ(k, 1) << "line " << no;

  const Outcome again = sh(mpirun(3) + SURFCERT_BINARY + " batch --mpi --checkpoint " + ck, in);
  EXPECT_EQ(again.code, single.code) << again.err;
  EXPECT_EQ(comparable(again.out), comparable(single.out));
  const auto both = checkpoint_counts(ck);
  EXPECT_EQ(static_cast<long>(both.size()), total);
  for (const auto& [no, k] : both)
    EXPECT_EQ(k, 1) << "line " << no << " computed twice";

  // A third run computes nothing and writes the same; a torn last record is cut off.
  std::ofstream(ck, std::ios::app) << "7 0123";
  const Outcome third = sh(mpirun(1) + SURFCERT_BINARY + " batch --mpi --checkpoint " + ck, in);
  EXPECT_EQ(third.code, single.code) << third.err;
  EXPECT_EQ(third.out, again.out); // the recorded answers, time_ms included
  EXPECT_EQ(count_records(checkpoint_counts(ck)), total);

  // Another input with this checkpoint: refused (exit 2), nothing answered from it.
  const std::string other = tmp_path("other_in");
  std::ofstream(other) << slow_input(kSlow, 400).substr(1);
  EXPECT_EQ(sh(mpirun(1) + SURFCERT_BINARY + " batch --mpi --checkpoint " + ck, other).code, 2);
  for (const std::string& p : {in, out, ck, other})
    std::remove(p.c_str());
}

// SIGKILL to a worker's compute child while it holds a slow line: the run completes, the
// lines it held are retried elsewhere, and the output is the single-process batch's.
TEST(BatchMpiFaults, KilledComputeChildLosesOnlyItsLines) {
  const std::string in = tmp_path("fault_in"), out = tmp_path("fault_out"),
                    err = tmp_path("fault_err");
  // 1.5 s budgets (wall): the budget is kept, so a line's CPU is what the load leaves of it.
  std::ofstream(in) << slow_input(8, 1500);
  const Outcome single = sh(std::string(SURFCERT_BINARY) + " batch --threads 2", in);
  const pid_t run =
      start(mpirun(3) + SURFCERT_BINARY + " batch --mpi <" + in + " >" + out + " 2>" + err);
  // A worker (rank 1 or 2) and its compute child, once it has been computing for a while.
  pid_t victim = -1;
  for (int i = 0; i < 3000 && victim < 0; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    for (pid_t p : children_of(run, "surfcert"))
      if (rank_of(p) > 0)
        for (pid_t c : children_of(p, "--mpi-child"))
          victim = c;
  }
  ASSERT_GT(victim, 0) << "no compute child found";
  // Killed once it has computed for 0.2 s of CPU: inside its lines (most of its time goes to
  // the 1.5 s ones), long before the run's 12 s of work end.
  for (int i = 0; i < 3000 && cpu_ticks(victim) < 20; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  ASSERT_EQ(kill(victim, SIGKILL), 0);
  EXPECT_EQ(wait_exit(run), single.code) << slurp(err);
  EXPECT_EQ(comparable(slurp(out)), comparable(single.out));
  std::smatch m;
  const std::string e = slurp(err);
  ASSERT_TRUE(std::regex_search(e, m, std::regex(R"(retried=([0-9]+) lost_twice=([0-9]+))"))) << e;
  EXPECT_GE(std::stol(m[1]), 1); // the killed child held at least its slow line
  EXPECT_EQ(std::stol(m[2]), 0);
  for (const std::string& p : {in, out, err})
    std::remove(p.c_str());
}

// --retry-undecided: distance lines with a budget far too small (undecided, reason "budget")
// are run again with a large one; their answers are then the unbudgeted single-process
// batch's, and the checkpoint holds both passes.
TEST(BatchMpiRetry, BudgetUndecidedLinesGetTheSecondPass) {
  const std::string gen = tmp_path("retry_gen"), in = tmp_path("retry_in"),
                    ck = tmp_path("retry_ck");
  std::remove(ck.c_str());
  ASSERT_EQ(std::system((std::string(SURFCERT_BINARY) +
                         " generate --case distance --count 1 --seed 5 > " + gen)
                            .c_str()),
            0);
  std::string budgeted;
  std::istringstream lines(slurp(gen));
  std::string l;
  int n = 0;
  while (std::getline(lines, l)) {
    budgeted += "{\"budget_ms\":0.001," + l.substr(1) + "\n";
    ++n;
  }
  std::ofstream(in) << budgeted;
  const Outcome first = sh(std::string(SURFCERT_BINARY) + " batch", in);
  EXPECT_EQ(first.code, 3); // undecided: the budget
  const Outcome unbudgeted = sh(std::string(SURFCERT_BINARY) + " batch", gen);
  EXPECT_EQ(unbudgeted.code, 0) << unbudgeted.err;
  const Outcome retried = sh(
      mpirun(3) + SURFCERT_BINARY + " batch --mpi --retry-undecided 600000 --checkpoint " + ck, in);
  EXPECT_EQ(retried.code, 0) << retried.err;
  EXPECT_EQ(untimed(retried.out), untimed(unbudgeted.out));
  int second = 0;
  std::istringstream recs(slurp(ck));
  while (std::getline(recs, l)) {
    std::istringstream f(l);
    long no;
    std::string hash;
    int pass = 0;
    f >> no >> hash >> pass;
    second += pass == 2;
  }
  EXPECT_GE(second, 1);
  EXPECT_LE(second, n);
  for (const std::string& p : {gen, in, ck})
    std::remove(p.c_str());
}

// The compute child holding a line is killed, and again on the retry: the line is answered
// with an "internal" error line (its id kept), the run completes with exit code 1.
TEST(BatchMpiFaults, LineLostTwiceIsAnInternalError) {
  const std::string in = tmp_path("lost_in"), out = tmp_path("lost_out"),
                    err = tmp_path("lost_err");
  std::ofstream(in) << budget_line("slow", 20000) << "\n";
  const pid_t run =
      start(mpirun(2) + SURFCERT_BINARY + " batch --mpi <" + in + " >" + out + " 2>" + err);
  // Each compute child of the worker (rank 1), once it has computed 0.3 s of CPU: then it is
  // inside the one line (starting takes a few ms).
  std::set<pid_t> killed;
  for (int i = 0; i < 12000 && killed.size() < 2; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    for (pid_t p : children_of(run, "surfcert"))
      if (rank_of(p) == 1)
        for (pid_t c : children_of(p, "--mpi-child"))
          if (!killed.count(c) && cpu_ticks(c) >= 30 && kill(c, SIGKILL) == 0) killed.insert(c);
  }
  ASSERT_EQ(killed.size(), 2u);
  EXPECT_EQ(wait_exit(run), 1) << slurp(err);
  const std::string answer = slurp(out);
  ASSERT_EQ(std::count(answer.begin(), answer.end(), '\n'), 1) << answer;
  const Json a = surfcert::core::io::parse_json(answer.substr(0, answer.size() - 1), "answer");
  EXPECT_EQ(a.find("id")->text(), "slow");
  EXPECT_EQ(a.find("status")->text(), "error");
  EXPECT_EQ(a.find("error")->find("kind")->text(), "internal");
  std::smatch m;
  const std::string e = slurp(err);
  ASSERT_TRUE(std::regex_search(e, m, std::regex(R"(retried=([0-9]+) lost_twice=([0-9]+))"))) << e;
  EXPECT_EQ(std::stol(m[1]), 1);
  EXPECT_EQ(std::stol(m[2]), 1);
  for (const std::string& p : {in, out, err})
    std::remove(p.c_str());
}

// SIGKILL to a worker rank itself (the relay between rank 0 and its compute child), while its
// child computes a slow line, in a job run with Open MPI's recovery: rank 0 finds it silent past
// --rank-timeout, its lines go to the other worker (ranks = 3) or, once no worker is left, to
// rank 0's own compute child (ranks = 2); the run completes with the single-process batch's
// answers, mpirun exits 0 (Open MPI 4.1 under --enable-recovery) and rank 0's summary carries
// the batch's exit code. Without the fault handling the run hangs (the guard ends it).
void kill_worker_rank(int ranks) {
  const std::string tag = "rank" + std::to_string(ranks);
  const std::string in = tmp_path(tag + "_in"), out = tmp_path(tag + "_out"),
                    err = tmp_path(tag + "_err");
  // Budget lines of 2 s (wall): the budget is kept to within a few tens of ms, so a line's CPU
  // is what the machine's load leaves of 2 s; at load 10 on 2 cores that is still > 0.2 s.
  // The single-process answers are computed once for both tests.
  std::ofstream(in) << slow_input(4, 2000);
  static const Outcome single = sh(std::string(SURFCERT_BINARY) + " batch --threads 2", in);
  ASSERT_EQ(single.code, 3) << single.err; // the budget-limited lines
  const pid_t run = start(mpirun(ranks) + "--enable-recovery " + SURFCERT_BINARY +
                          " batch --mpi --rank-timeout 5 <" + in + " >" + out + " 2>" + err);
  // The first worker rank whose compute child has computed 0.2 s of CPU: then it holds a slow
  // line (which worker gets the slow lines is up to the scheduler: on 16 lines one worker may
  // get them all).
  pid_t victim = -1;
  for (int i = 0; i < 6000 && victim < 0; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    for (pid_t p : children_of(run, "surfcert"))
      if (rank_of(p) > 0)
        for (pid_t c : children_of(p, "--mpi-child"))
          if (cpu_ticks(c) >= 20) victim = p;
  }
  ASSERT_GT(victim, 0) << "no worker's compute child computed 0.2 s";
  ASSERT_EQ(kill(victim, SIGKILL), 0);
  EXPECT_EQ(wait_exit_within(run, 300), 0) << slurp(err);
  EXPECT_EQ(comparable(slurp(out)), comparable(single.out));
  const std::string e = slurp(err);
  std::smatch m;
  ASSERT_TRUE(
      std::regex_search(e, m,
                        std::regex(R"(retried=([0-9]+) lost_twice=([0-9]+) .*dead_ranks=)"
                                   R"(([0-9]+) recovery=1 exit=([0-9]+) local_fallback=([01]))")))
      << e;
  EXPECT_GE(std::stol(m[1]), 1); // the killed rank held at least its child's slow line
  EXPECT_EQ(std::stol(m[2]), 0);
  EXPECT_EQ(std::stol(m[3]), 1);
  EXPECT_EQ(std::stoi(m[4]), single.code);
  // Rank 0 computed lines itself exactly when the killed rank was the only worker.
  EXPECT_EQ(std::stoi(m[5]), ranks == 2 ? 1 : 0) << e;
  for (const std::string& p : {in, out, err})
    std::remove(p.c_str());
}

TEST(BatchMpiFaults, KilledWorkerRankUnderRecoveryLosesOnlyItsLines) {
  kill_worker_rank(3);
}

TEST(BatchMpiFaults, LastWorkerRankKilledUnderRecoveryRankZeroFinishes) {
  kill_worker_rank(2);
}

// `surfcert` does not load Open MPI (libmpi, libopen-rte, libopen-pal: ~85 page faults at every
// start); surfcert-mpi does (the check sees them where they are).
TEST(BatchMpiExec, SurfcertDoesNotLoadLibmpi) {
  const Outcome plain = sh(std::string("ldd ") + SURFCERT_BINARY, "/dev/null");
  ASSERT_EQ(plain.code, 0) << plain.err;
  ASSERT_NE(plain.out.find("libflint"), std::string::npos) << plain.out; // ldd listed them
  EXPECT_EQ(plain.out.find("libmpi"), std::string::npos) << plain.out;
  EXPECT_EQ(plain.out.find("libopen-"), std::string::npos) << plain.out;
  const Outcome mpi = sh(std::string("ldd ") + SURFCERT_MPI_BINARY, "/dev/null");
  ASSERT_EQ(mpi.code, 0) << mpi.err;
  EXPECT_NE(mpi.out.find("libmpi"), std::string::npos) << mpi.out;
  EXPECT_NE(mpi.out.find("libopen-pal"), std::string::npos) << mpi.out;
}

// A `surfcert` without surfcert-mpi next to it: batch --mpi exits 2 naming the missing file,
// with no answer written; the single-process batch still runs.
TEST(BatchMpiExec, WithoutSurfcertMpiBatchMpiNamesTheMissingFile) {
  const std::string dir = tmp_path("alone");
  ASSERT_EQ(mkdir(dir.c_str(), 0700), 0);
  const std::string bin = dir + "/surfcert";
  ASSERT_EQ(std::system(("cp " + std::string(SURFCERT_BINARY) + " " + bin).c_str()), 0);
  const std::string in = tmp_path("alone_in");
  std::ofstream(in) << R"({"id":"d","op":"distance","a":"x^2+y^2+z^2=1","b":"(x-3)^2+y^2+z^2=1"})"
                    << "\n";
  const Outcome r = sh(mpirun(1) + bin + " batch --mpi", in);
  EXPECT_NE(r.code, 0) << r.err;
  EXPECT_EQ(r.out, "");
  EXPECT_NE(r.err.find(dir + "/surfcert-mpi"), std::string::npos) << r.err;
  const Outcome direct = sh(bin + " batch --mpi", in);
  EXPECT_EQ(direct.code, 2) << direct.err;
  EXPECT_NE(direct.err.find(dir + "/surfcert-mpi"), std::string::npos) << direct.err;
  EXPECT_EQ(direct.out, "");
  const Outcome single = sh(bin + " batch", in);
  EXPECT_EQ(single.code, 0) << single.err;
  EXPECT_NE(single.out.find("\"status\":\"certified\""), std::string::npos) << single.out;
  std::remove(bin.c_str());
  std::remove(in.c_str());
  rmdir(dir.c_str());
}
