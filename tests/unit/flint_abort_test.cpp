// A FLINT/Arb abort (flint_abort) inside one batch line: the handler installed by
// install_flint_abort_handler throws FlintAbort through FLINT's C frames, the per-line guard of
// process_batch answers that line with an "internal" error line, the batch counts it (the CLI
// then exits 1) and goes on answering the following lines, in order.
#include "surfcert/app/scene.hpp"

#include <flint/fmpz.h>
#include <gtest/gtest.h>

#include <sstream>
#include <string>

using surfcert::app::FlintAbort;
using surfcert::core::io::Json;

namespace {

// fmpz_divexact(q, 6, 0): FLINT 2.9 prints "Exception (fmpz_divexact). Division by zero." and
// calls flint_abort().
void divexact_by_zero() {
  struct Fmpz {
    fmpz_t v;
    Fmpz() { fmpz_init(v); }
    ~Fmpz() { fmpz_clear(v); }
  } a, b, q;
  fmpz_set_ui(a.v, 6);
  fmpz_divexact(q.v, a.v, b.v);
}

const char* kLine =
    R"({"id": ID, "op": "classify", "a": "x^2+y^2+z^2=1", "b": "(x-1)^2+y^2+z^2=1"})";

std::string line(int id) {
  std::string l = kLine;
  return l.replace(l.find("ID"), 2, std::to_string(id));
}

} // namespace

TEST(FlintAbort, HandlerThrowsThroughFlint) {
  surfcert::app::install_flint_abort_handler();
  EXPECT_THROW(divexact_by_zero(), FlintAbort);
  EXPECT_THROW(divexact_by_zero(), FlintAbort); // and again: the handler stays installed
}

TEST(FlintAbort, BatchAnswersInternalErrorAndGoesOn) {
  for (int threads : {1, 3}) {
    std::string in = line(1) + "\nboom\n" + line(3) + "\nboom\n" + line(5) + "\n";
    auto answer = [](const std::string& l, long no, surfcert::certify::Mode m, bool* fb) {
      if (l == "boom") divexact_by_zero();
      return surfcert::app::process_batch_line(l, no, m, fb);
    };
    std::istringstream is(in);
    std::ostringstream os;
    auto st =
        surfcert::app::process_batch(is, os, surfcert::certify::Mode::Filtered, threads, answer);
    EXPECT_EQ(st.lines, 5);
    EXPECT_EQ(st.errors, 2);
    EXPECT_EQ(st.internal, 2);
    std::istringstream out(os.str());
    std::string l;
    int n = 0;
    while (std::getline(out, l)) {
      ++n;
      Json o = surfcert::core::io::parse_json(l, "out");
      if (n % 2 == 0) {
        EXPECT_EQ(o.find("status")->text(), "error") << l;
        EXPECT_TRUE(o.find("id")->is_null());
        EXPECT_EQ(o.find("error")->find("kind")->text(), "internal") << l;
        EXPECT_NE(o.find("error")->find("message")->text().find("FLINT"), std::string::npos);
      } else {
        EXPECT_EQ(o.find("status")->text(), "certified") << l;
        EXPECT_EQ(o.find("id")->text(), std::to_string(n));
        EXPECT_EQ(o.find("result")->find("tu_case")->text(), "17");
      }
    }
    EXPECT_EQ(n, 5);
  }
}

TEST(FlintAbort, InternalErrorLineHasTheErrorShape) {
  Json o = surfcert::app::internal_error_line(Json::string("q7"), "boom");
  EXPECT_EQ(surfcert::core::io::dump(o),
            R"({"id":"q7","status":"error","error":{"kind":"internal","message":"boom"}})");
}
