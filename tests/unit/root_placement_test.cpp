// Certified answers must not depend on WHERE a valid isolating interval sits. refine_root's
// testing hook (algebra::set_root_placement) hands the routes other valid intervals: Newton's
// bracket, a grid-snapped centre, the root near either end, far narrower than asked.
// - every placement returns a valid isolating interval (exact signs at its ends, width, inside
//   the input, the root inside: checked against an independent isolation);
// - the exact offset-system route answers the cone two-minima family (ellipsoid centred at
//   (2, 0, 4), semi-axes 1/2, b, 1/2, against x^2 + y^2 = z^2; b = b* +- 3e-7, 3e-21: see
//   cone_distance_test.cpp) the same for every placement: certified, the mpmath distance
//   inside, the same minimizer count. Newton's and the centred placement once made it give
//   up: mirror-symmetric roots (x + z = 6 at the minimizer) got mirror-symmetric intervals, the
//   box centre projected EXACTLY onto the minimizer, where the normal line is parallel to a
//   generator of the cone (the leading coefficient of the line-cone quadratic is exactly 0,
//   which no ball can prove), so no upper bound was certified in any round.
#include "surfcert/algebra/real_roots.hpp"
#include "surfcert/certify/distance/distance.hpp"

#include "support/distance_checks.hpp"

#include <gtest/gtest.h>

#include <mpfr.h>

using namespace surfcert;
using surfcert::testing::q;

namespace {

const algebra::RootPlacement kAll[] = {
    algebra::RootPlacement::Bisect,     algebra::RootPlacement::Newton,
    algebra::RootPlacement::Centred,    algebra::RootPlacement::RootNearLo,
    algebra::RootPlacement::RootNearHi, algebra::RootPlacement::Tiny};

const char* name(algebra::RootPlacement p) {
  switch (p) {
  case algebra::RootPlacement::Bisect:
    return "bisect";
  case algebra::RootPlacement::Newton:
    return "newton";
  case algebra::RootPlacement::Centred:
    return "centred";
  case algebra::RootPlacement::RootNearLo:
    return "near-lo";
  case algebra::RootPlacement::RootNearHi:
    return "near-hi";
  case algebra::RootPlacement::Tiny:
    return "tiny";
  }
  return "?";
}

// Sets a placement for a scope (restores Bisect even when an assertion returns early).
struct Placed {
  explicit Placed(algebra::RootPlacement p) { algebra::set_root_placement(p); }
  ~Placed() { algebra::set_root_placement(algebra::RootPlacement::Bisect); }
  Placed(const Placed&) = delete;
  Placed& operator=(const Placed&) = delete;
};

} // namespace

TEST(RootPlacement, EveryPlacementIsAValidIsolatingInterval) {
  // (x^2 - 2)(x - 1/3)(x + 7)(3x^2 - 6x + 2): irrational, rational and close roots.
  algebra::UPolyZ p = algebra::UPolyZ::from_coeffs({core::Integer(1)});
  for (const std::vector<long>& f :
       std::vector<std::vector<long>>{{-2, 0, 1}, {-1, 3}, {7, 1}, {2, -6, 3}}) {
    std::vector<core::Integer> c;
    for (long v : f)
      c.emplace_back(v);
    fmpz_poly_mul(p.raw_mut(), p.raw(), algebra::UPolyZ::from_coeffs(c).raw());
  }
  const auto sep = algebra::isolate_real_roots(p);
  ASSERT_EQ(sep.num_roots(), 6u);
  for (algebra::RootPlacement pl : kAll)
    for (long bits : {4L, 20L, 70L, 200L}) {
      core::Rational w(1);
      fmpq_div_2exp(w.raw_mut(), w.raw(), static_cast<ulong>(bits));
      for (size_t i = 0; i + 1 < sep.separators.size(); ++i) {
        // the root to 2^-(bits + 40) by plain bisection: the reference
        core::Rational rlo = sep.separators[i], rhi = sep.separators[i + 1];
        core::Rational fine = w;
        fmpq_div_2exp(fine.raw_mut(), fine.raw(), 40);
        algebra::refine_root(p, rlo, rhi, fine);
        core::Rational lo = sep.separators[i], hi = sep.separators[i + 1];
        {
          Placed placed(pl);
          algebra::refine_root(p, lo, hi, w);
        }
        SCOPED_TRACE(std::string(name(pl)) + " bits " + std::to_string(bits));
        EXPECT_LE(hi - lo, w);
        EXPECT_TRUE(sep.separators[i] <= lo && hi <= sep.separators[i + 1]);
        if (lo == hi) {
          EXPECT_EQ(p.sign_at(lo), 0);
          continue;
        }
        EXPECT_LT(p.sign_at(lo) * p.sign_at(hi), 0);
        EXPECT_TRUE(lo <= rlo && rhi <= hi) << "the root is outside";
      }
    }
}

TEST(RootPlacement, ConeTwoMinimaOffsetRouteDoesNotDependOnIntervals) {
  const auto round = q("x^2 + y^2 - z^2 = 0");
  struct Case {
    const char* b; // b* +- delta (cone_distance_test.cpp)
    const char* d; // the distance (mpmath, 50 digits)
    int count;     // minimizers
  };
  const char* tail = "2616104368355";
  const Case cases[] = {
      {"1.29004431567275798467585054385318245260684251930365172072037218251070532960245362656403",
       "0.91421356237303972066520418109359638371169817543307", 2},
      {"1.29004371567275798467585054385318245260684251930365172072037218251070532960245362656403",
       "0.91421356237309504880168872420969807856967187537695", 1},
      {"1.29004401567275798467885054385318245260684251930365172072037218251070532960245362656403",
       "0.91421356237309504880168872420969807856966634256156", 2},
      {"1.29004401567275798467285054385318245260684251930365172072037218251070532960245362656403",
       "0.91421356237309504880168872420969807856967187537695", 1},
  };
  for (const Case& c : cases) {
    const std::string b = std::string(c.b) + tail;
    const auto e = q("4*(x-2)^2 + y^2/(" + b + ")^2 + 4*(z-4)^2 = 1");
    for (algebra::RootPlacement pl : kAll) {
      certify::DistanceResult r;
      {
        Placed placed(pl);
        r = certify::surface_distance(e, round, 15, false, certify::Mode::Exact);
      }
      SCOPED_TRACE(b + " placement " + name(pl));
      EXPECT_EQ(r.method, certify::Method::OffsetSystem);
      if (r.status != certify::Status::Certified) {
        ADD_FAILURE() << "not certified: " << r.note;
        continue;
      }
      mpfr_t d;
      mpfr_init2(d, 200);
      mpfr_set_str(d, c.d, 10, MPFR_RNDN);
      EXPECT_TRUE(surfcert::testing::contains(r, d)) << r.lower() << " " << r.upper();
      mpfr_clear(d);
      // the count, or undecided; never the other count
      if (r.minimizers.is_count())
        EXPECT_EQ(r.minimizers.value(), c.count) << r.note;
      else
        EXPECT_TRUE(r.minimizers.is_undecided()) << r.minimizers;
    }
  }
}
