// Certified answers of the exact offset route (quadric_pair.cpp, offset_minimum.cpp) at inputs
// built to hit its sign and tie decisions exactly, each against a closed form or mpmath:
// - a bounded quartic whose zero set is two blobs (x^4 + y^4 + z^4 - 8 x^2 + 15 = 0: x in
//   +-[sqrt 3, sqrt 5]) against planes x = c between them, from both sides of the blob's tip
//   (|c| = sqrt 3 -+ 1e-10, 1e-20, 1e-30, 2^-100) and exactly on the symmetry plane (c = 0:
//   two minimizers): the quadric's equation takes both signs on the implicit surface, which
//   once was taken for a crossing (certified 0, while the distance is sqrt 3 - |c|). Closed
//   form: the distance is sqrt 3 - |c| (the blob's nearest point to x = c is its tip), or 0
//   when |c| > sqrt 3. The same blobs against the paraboloid x = y^2 + z^2 - 1 through the
//   offset system itself (mpmath, 250 digits: 0.51655606676886980078...).
// - an ellipsoid of revolution about the x axis against the cylinder x^2 + y^2 = 1 (exact
//   offset route): at the ellipsoid's top and bottom, exact rational solutions of the offset
//   system, the normal line runs along the cylinder's axis (the target's coefficients of mu
//   are exactly 0 there), which once made the lower bound an Arb indeterminate (NaN) that
//   kept both phantom boxes, so the single minimizer was reported as 3 undecided candidates.
//   Closed form: the distance is x0 - 2 (the ellipsoid's leftmost point (x0 - 1, 0, 0) to the
//   cylinder), gaps 1, 1e-10, 1e-20, 1e-30, 2^-100; x0 < 2: they cross.
// - the teardrop x^2 + y^2 = z^3 (1 - z) (a cusp at the origin, a singular point: grad f = 0,
//   no normal line) against an ellipsoid whose top is `gap` below the cusp: the cusp, an exact
//   rational solution of the offset system, is the closest point, and it once got no upper
//   bound (the source point was projected along its normal line), so the answer stayed
//   undecided with [gap, 2.5]. Closed form: the distance is gap (the teardrop rises as
//   z >= 0 and the ellipsoid falls away below its top); the ellipsoid raised by gap: they cross.
// The cylinder and cusp cases also run under every isolating-interval placement refine_root can
// hand the routes (algebra::set_root_placement): degenerate or not, the exact boxes must not
// change the answer.
#include "surfcert/algebra/real_roots.hpp"
#include "surfcert/certify/distance/distance.hpp"
#include "surfcert/certify/distance/quadric_pair.hpp"
#include "surfcert/core/io/json.hpp"
#include "surfcert/core/io/surface_reader.hpp"

#include "support/distance_checks.hpp"

#include <gtest/gtest.h>

#include <gmp.h>
#include <mpfr.h>

#include <string>
#include <vector>

using namespace surfcert;

namespace {

core::Surface surf(const std::string& eq) {
  return core::io::read_surface(core::io::Json::string(eq), "t", "$");
}

const char* const kBlobs = "x^4 + y^4 + z^4 - 8 x^2 + 15";

// The shifts probed on both sides (decimal strings; "2^-100" exactly).
const char* const kEps[] = {"1e-10", "1e-20", "1e-30", "2^-100"};

void set_eps(mpfr_t e, const std::string& s) {
  if (s == "2^-100")
    mpfr_set_ui_2exp(e, 1, -100, MPFR_RNDN);
  else
    mpfr_set_str(e, s.c_str(), 10, MPFR_RNDN);
}

// floor((sqrt 3 + sign eps) 10^60) / 10^60 as "N/10^60", and sqrt 3 - that value in `gap`
// (exact to 4000 bits: the reference distance when positive).
std::string tip_plane_offset(const std::string& eps, int sign, mpfr_t gap) {
  mpfr_t s, e, t;
  mpfr_inits2(4000, s, e, t, static_cast<mpfr_ptr>(nullptr));
  mpfr_sqrt_ui(s, 3, MPFR_RNDN);
  set_eps(e, eps);
  if (sign < 0) mpfr_neg(e, e, MPFR_RNDN);
  mpfr_add(t, s, e, MPFR_RNDN);
  mpz_t n, p;
  mpz_inits(n, p, nullptr);
  mpz_ui_pow_ui(p, 10, 60);
  mpfr_mul_z(t, t, p, MPFR_RNDN);
  mpfr_get_z(n, t, MPFR_RNDD);
  mpfr_set_z(t, n, MPFR_RNDN);
  mpfr_div_z(t, t, p, MPFR_RNDN);
  mpfr_set_prec(gap, 4000);
  mpfr_sub(gap, s, t, MPFR_RNDN);
  std::vector<char> buf(mpz_sizeinbase(n, 10) + 2);
  mpz_get_str(buf.data(), 10, n);
  const std::string out = std::string(buf.data()) + "/10^60";
  mpz_clears(n, p, nullptr);
  mpfr_clears(s, e, t, static_cast<mpfr_ptr>(nullptr));
  return out;
}

// Every valid isolating-interval placement refine_root can hand the routes (testing hook).
const algebra::RootPlacement kPlacements[] = {
    algebra::RootPlacement::Bisect,     algebra::RootPlacement::Newton,
    algebra::RootPlacement::Centred,    algebra::RootPlacement::RootNearLo,
    algebra::RootPlacement::RootNearHi, algebra::RootPlacement::Tiny};

// Sets a placement for a scope (restores Bisect even when an assertion returns early).
struct Placed {
  explicit Placed(algebra::RootPlacement p) { algebra::set_root_placement(p); }
  ~Placed() { algebra::set_root_placement(algebra::RootPlacement::Bisect); }
  Placed(const Placed&) = delete;
  Placed& operator=(const Placed&) = delete;
};

bool certified_zero(const certify::DistanceResult& r) {
  return r.status == certify::Status::Certified && r.upper() == "0";
}

} // namespace

TEST(OffsetAudit, PlaneBetweenTwoBlobsIsApart) {
  const core::Surface blobs = surf(kBlobs);
  ASSERT_TRUE(std::holds_alternative<core::ImplicitSurface>(blobs));
  mpfr_t ref;
  mpfr_init2(ref, 4000);
  // Exactly on the symmetry plane: sqrt 3 to both blobs, two minimizers (point reflection).
  {
    const auto r = certify::surface_distance(blobs, surf("x"), 15, false);
    ASSERT_EQ(r.status, certify::Status::Certified) << r.note;
    mpfr_sqrt_ui(ref, 3, MPFR_RNDN);
    EXPECT_TRUE(surfcert::testing::contains(r, ref)) << r.lower() << " " << r.upper();
    EXPECT_TRUE(r.minimizers == "2" || r.minimizers.is_undecided()) << r.minimizers.str();
  }
  for (const char* eps : kEps)
    for (int side : {-1, 1})       // below the tip (apart) / above it (crossing)
      for (int mirror : {1, -1}) { // the plane x = c near the right blob, or x = -c
        const std::string c = tip_plane_offset(eps, side, ref);
        const std::string plane = mirror > 0 ? "x - " + c : "x + " + c;
        SCOPED_TRACE(std::string(eps) + (side < 0 ? " below" : " above") + " " + plane);
        const auto r = certify::surface_distance(blobs, surf(plane), 15, false);
        ASSERT_EQ(r.status, certify::Status::Certified) << r.note;
        if (side < 0) {
          EXPECT_FALSE(certified_zero(r)) << r.note;
          EXPECT_TRUE(surfcert::testing::contains(r, ref)) << r.lower() << " " << r.upper();
          EXPECT_EQ(r.minimizers, "1") << r.note;
        } else {
          EXPECT_TRUE(certified_zero(r)) << r.lower() << " " << r.upper();
        }
      }
  mpfr_clear(ref);
}

TEST(OffsetAudit, ParaboloidBetweenTwoBlobsOffsetRoute) {
  // The offset route itself (the registry answers this pair by branch and bound first).
  const core::Surface blobs = surf(kBlobs);
  const auto r =
      certify::implicit_quadric_distance(std::get<core::ImplicitSurface>(blobs).f,
                                         surfcert::testing::q("x - y^2 - z^2 + 1"), 15, true);
  ASSERT_NE(r.status, certify::Status::Error) << r.note;
  if (r.status != certify::Status::Certified) return; // undecided is allowed, never wrong
  EXPECT_FALSE(certified_zero(r)) << r.note;
  // mpmath (250 digits, findroot on the critical-pair system from the float minimizer):
  // 0.51655606676886980078105979437632020770...
  EXPECT_TRUE(surfcert::testing::overlap_bounds(r, "0.5165560667688698007810597943763",
                                                "0.5165560667688698007810597943764"))
      << r.lower() << " " << r.upper();
}

namespace {

// (the gap as the equation reads it, its exact decimal value)
const std::pair<const char*, const char*> kGaps[] = {
    {"1", "1"},
    {"1/10^10", "1e-10"},
    {"1/10^20", "1e-20"},
    {"1/10^30", "1e-30"},
    {"1/1267650600228229401496703205376",
     "7.8886090522101180541172856528278622967320643510902300477027893066406250e-31"}};

} // namespace

TEST(OffsetAudit, NormalLineAlongCylinderAxis) {
  for (const auto placement : kPlacements)
    for (const auto& [g, name] : kGaps)
      for (int side : {1, -1}) {
        const Placed placed(placement);
        SCOPED_TRACE(static_cast<int>(placement));
        // Centre x0 = 2 +- gap: the leftmost point (x0 - 1, 0, 0) is gap outside / inside the
        // cylinder; the top and bottom (x0, 0, +-1/2) are exact rational solutions.
        const std::string x0 = std::string("(2 ") + (side > 0 ? "+ " : "- ") + g + ")";
        const std::string ell = "(x - " + x0 + ")^2 + 4 y^2 + 4 z^2 - 1";
        SCOPED_TRACE(ell);
        const auto r = certify::surface_distance(surfcert::testing::q(ell),
                                                 surfcert::testing::q("x^2 + y^2 - 1"), 15, false,
                                                 certify::Mode::Exact);
        ASSERT_EQ(r.status, certify::Status::Certified) << r.note;
        if (side < 0) {
          EXPECT_TRUE(certified_zero(r)) << r.lower() << " " << r.upper();
          continue;
        }
        EXPECT_TRUE(surfcert::testing::overlap_bounds(r, name, name))
            << r.lower() << " " << r.upper();
        EXPECT_EQ(r.minimizers, "1") << r.note;
      }
}

TEST(OffsetAudit, CuspOfImplicitSourceIsTheClosestPoint) {
  const core::Surface drop = surf("x^2 + y^2 - z^3 + z^4");
  for (const auto& [g, name] : kGaps)
    for (int side : {1, -1}) { // the ellipsoid's top (0, 0, -+gap): below the cusp / around it
      if (side < 0 && std::string(g) == "1") continue; // its bottom would touch the cusp
      const std::string ell =
          std::string("x^2 + 4 y^2 + 4 (z + 1/2 ") + (side > 0 ? "+ " : "- ") + g + ")^2 - 1";
      SCOPED_TRACE(ell);
      const auto r = certify::surface_distance(drop, surf(ell), 15, false);
      ASSERT_EQ(r.status, certify::Status::Certified) << r.note;
      if (side < 0) {
        EXPECT_TRUE(certified_zero(r)) << r.lower() << " " << r.upper();
        continue;
      }
      EXPECT_TRUE(surfcert::testing::overlap_bounds(r, name, name))
          << r.lower() << " " << r.upper();
      EXPECT_EQ(r.minimizers, "1") << r.note;
    }
}

TEST(OffsetAudit, CuspUnderEveryPlacement) {
  // Where the cusp's exact box sits (a degenerate interval or not) depends on the placement.
  const core::Surface drop = surf("x^2 + y^2 - z^3 + z^4");
  const core::Surface ell = surf("x^2 + 4 y^2 + 4 (z + 1/2 + 1/10^20)^2 - 1");
  for (const auto placement : kPlacements) {
    const Placed placed(placement);
    SCOPED_TRACE(static_cast<int>(placement));
    const auto r = certify::surface_distance(drop, ell, 15, false);
    ASSERT_EQ(r.status, certify::Status::Certified) << r.note;
    EXPECT_TRUE(surfcert::testing::overlap_bounds(r, "1e-20", "1e-20"))
        << r.lower() << " " << r.upper();
    EXPECT_EQ(r.minimizers, "1") << r.note;
  }
}
