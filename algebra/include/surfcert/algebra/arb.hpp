// surfcert's one door to Arb (ball arithmetic): the Arb headers, and the value types over
// Arb's raw structs that the rest of the code uses (Ball, BallVec, Arf; ComplexBallVec and
// ComplexBallPoly for Arb's complex root finder).
//
// Why one header: FLINT 3 merged Arb into FLINT, which moved every Arb module from the flat
// <arb.h> of the separate Arb 2.x library to <flint/arb.h>. Every file that needs Arb
// includes this header and nothing of Arb's own, so that change is made here once.
//
// Contract of the types:
// - Ball is a value (copies are deep, moves swap) over arb_t. `.v` is the raw arb_t for Arb's
//   C functions, which take the working precision as an argument: that is how most code uses
//   it, and nothing in that use depends on PrecisionScope.
// - Ball's arithmetic operators (+ - * /, +=) exist for generic code written once for Arb
//   balls and for other interval types (nested_convex's templates over CGAL's double
//   intervals). An operator has no precision argument, so they round at the precision of the
//   innermost live PrecisionScope on the calling thread (ball_precision(); 128 bits outside
//   any scope). Every result encloses the exact result of the operation on the operands.
// - Ball(double) is explicit and exact (a double is a dyadic rational: zero radius), so the
//   generic code writes I(0), I(0.5) for either interval type; it never converts silently.
// - BallVec owns a contiguous _arb_vec (Arb's vector functions and matrix rows take arb_ptr).
// - Arf is a value over arf_t: an exact binary floating-point number (no radius, no
//   precision of its own).
#pragma once

#if __has_include(<flint/arb.h>)
// FLINT >= 3: Arb is part of FLINT.
#include <flint/acb.h>
#include <flint/arb.h>
#include <flint/arb_fmpz_poly.h>
#include <flint/arb_mat.h>
#include <flint/arf.h>
#include <flint/mag.h>
#else
// FLINT 2.x with the separate Arb 2.x library (Debian 12: libflint-arb-dev).
#include <acb.h>
#include <arb.h>
#include <arb_fmpz_poly.h>
#include <arb_mat.h>
#include <arf.h>
#include <mag.h>
#endif

namespace surfcert::algebra {

namespace detail {
// The precision of Ball's operators on this thread (see PrecisionScope).
inline thread_local long ball_prec = 128;
} // namespace detail

/// The precision (bits) at which Ball's operators round on this thread.
inline long ball_precision() noexcept {
  return detail::ball_prec;
}

/// Sets ball_precision() on this thread for its lifetime and restores the previous value
/// after (scopes nest).
class PrecisionScope {
public:
  explicit PrecisionScope(long prec) : saved_(detail::ball_prec) { detail::ball_prec = prec; }
  ~PrecisionScope() { detail::ball_prec = saved_; }
  PrecisionScope(const PrecisionScope&) = delete;
  PrecisionScope& operator=(const PrecisionScope&) = delete;

private:
  long saved_;
};

/// An Arb ball with value semantics (RAII over arb_t; exact 0 when default-constructed).
struct Ball {
  arb_t v;
  Ball() { arb_init(v); }
  /// Exactly d (zero radius).
  explicit Ball(double d) {
    arb_init(v);
    arb_set_d(v, d);
  }
  Ball(const Ball& o) {
    arb_init(v);
    arb_set(v, o.v);
  }
  Ball(Ball&& o) noexcept {
    arb_init(v);
    arb_swap(v, o.v);
  }
  Ball& operator=(const Ball& o) {
    arb_set(v, o.v);
    return *this;
  }
  Ball& operator=(Ball&& o) noexcept {
    arb_swap(v, o.v);
    return *this;
  }
  ~Ball() { arb_clear(v); }
};

// Arithmetic at ball_precision() (see the contract above).
inline Ball operator+(const Ball& a, const Ball& b) {
  Ball r;
  arb_add(r.v, a.v, b.v, ball_precision());
  return r;
}
inline Ball operator-(const Ball& a, const Ball& b) {
  Ball r;
  arb_sub(r.v, a.v, b.v, ball_precision());
  return r;
}
inline Ball operator-(const Ball& a) {
  Ball r;
  arb_neg(r.v, a.v); // exact
  return r;
}
inline Ball operator*(const Ball& a, const Ball& b) {
  Ball r;
  arb_mul(r.v, a.v, b.v, ball_precision());
  return r;
}
inline Ball operator/(const Ball& a, const Ball& b) {
  Ball r;
  arb_div(r.v, a.v, b.v, ball_precision());
  return r;
}
inline Ball& operator+=(Ball& a, const Ball& b) {
  arb_add(a.v, a.v, b.v, ball_precision());
  return a;
}

/// n balls in one contiguous Arb vector, all exact 0 at first; `.v` is the arb_ptr.
struct BallVec {
  arb_ptr v;
  slong n;
  explicit BallVec(slong k) : v(_arb_vec_init(k)), n(k) {}
  BallVec(const BallVec&) = delete;
  BallVec& operator=(const BallVec&) = delete;
  ~BallVec() { _arb_vec_clear(v, n); }
};

/// n complex balls (acb) in one contiguous Arb vector, all exact 0 at first; `.v` is the acb_ptr.
struct ComplexBallVec {
  acb_ptr v;
  slong n;
  explicit ComplexBallVec(slong k) : v(_acb_vec_init(k)), n(k) {}
  ComplexBallVec(const ComplexBallVec&) = delete;
  ComplexBallVec& operator=(const ComplexBallVec&) = delete;
  ~ComplexBallVec() { _acb_vec_clear(v, n); }
};

/// RAII over arb_poly_t (a polynomial with real ball coefficients; 0 at first).
struct BallPoly {
  arb_poly_t v;
  BallPoly() { arb_poly_init(v); }
  BallPoly(const BallPoly&) = delete;
  BallPoly& operator=(const BallPoly&) = delete;
  ~BallPoly() { arb_poly_clear(v); }
};

/// RAII over acb_poly_t (a polynomial with complex ball coefficients; 0 at first).
struct ComplexBallPoly {
  acb_poly_t v;
  ComplexBallPoly() { acb_poly_init(v); }
  ComplexBallPoly(const ComplexBallPoly&) = delete;
  ComplexBallPoly& operator=(const ComplexBallPoly&) = delete;
  ~ComplexBallPoly() { acb_poly_clear(v); }
};

/// RAII over arf_t (copyable: an exact binary floating-point number).
class Arf {
public:
  Arf() { arf_init(v); }
  Arf(const Arf& o) {
    arf_init(v);
    arf_set(v, o.v);
  }
  Arf& operator=(const Arf& o) {
    arf_set(v, o.v);
    return *this;
  }
  Arf(Arf&& o) noexcept {
    arf_init(v);
    arf_swap(v, o.v);
  }
  Arf& operator=(Arf&& o) noexcept {
    arf_swap(v, o.v);
    return *this;
  }
  ~Arf() { arf_clear(v); }
  arf_t v;
};

} // namespace surfcert::algebra
