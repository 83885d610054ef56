// `surfcert batch --mpi` (app/batch_mpi.hpp) under `mpirun -n 3` against the single-process
// batch on the same lines (the independent route: no MPI, no compute child, no scheduler):
// the same answers byte for byte apart from "time_ms" (ordered, unordered as a multiset, one
// rank), bad option combinations exit 2.
#include "surfcert/core/io/json.hpp"

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

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
  return std::string("ASAN_OPTIONS=detect_leaks=0 ") + SURFCERT_MPIEXEC +
         " --allow-run-as-root --oversubscribe -x ASAN_OPTIONS -n " + std::to_string(ranks) + " ";
}

std::string untimed(const std::string& out) {
  static const std::regex time_field(R"(,"time_ms":[0-9.]+)");
  return std::regex_replace(out, time_field, "");
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
  EXPECT_EQ(untimed(mpi.out), untimed(single_.out));
  // Every kind of line was there: certified, undecided (budget), input errors.
  EXPECT_NE(single_.out.find("\"reason\":\"budget\""), std::string::npos);
  EXPECT_NE(single_.out.find("\"branches\":"), std::string::npos);
  EXPECT_NE(single_.out.find("\"kind\":\"input\""), std::string::npos);
}

TEST_F(BatchMpi, UnorderedAndOneRankGiveTheSameAnswers) {
  const Outcome un = sh(mpirun(3) + SURFCERT_BINARY + " batch --mpi --unordered --threads 2", in_);
  EXPECT_EQ(un.code, single_.code) << un.err;
  EXPECT_EQ(sorted_lines(untimed(un.out)), sorted_lines(untimed(single_.out)));
  const Outcome one = sh(mpirun(1) + SURFCERT_BINARY + " batch --mpi", in_);
  EXPECT_EQ(one.code, single_.code) << one.err;
  EXPECT_EQ(untimed(one.out), untimed(single_.out));
}

TEST_F(BatchMpi, OptionsThatNeedMpiAreRefusedWithout) {
  const std::string bin = SURFCERT_BINARY;
  EXPECT_EQ(sh(bin + " batch --checkpoint " + tmp_path("ck"), in_).code, 2);
  EXPECT_EQ(sh(bin + " batch --retry-undecided 1000", in_).code, 2);
  EXPECT_EQ(sh(bin + " batch --mpi --retry-undecided 0", in_).code, 2);
}
