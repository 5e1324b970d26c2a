#include "fit/sollya_fit.h"

#include <sollya.h>

#include <chrono>
#include <cmath>
#include <mutex>
#include <utility>

namespace glint {

namespace {

// Every message of Sollya's core (warnings of non-convergence, of rounding) would go to stdout,
// in the middle of glint's reports: callers get failures as values instead.
int silence(sollya_msg_t, void*) {
  return 0;
}

std::mutex& sollya_lock() {
  static std::mutex m;
  return m;
}

// Under sollya_lock(). Never closed: the library stays up for the process, as glint's memo of fits
// does.
void ensure_sollya() {
  static const bool ready = [] {
    sollya_lib_init();
    sollya_lib_install_msg_callback(silence, nullptr);
    return true;
  }();
  (void)ready;
}

// Owns one Sollya object (cleared on scope exit unless released into a "use up" builder).
class Obj {
 public:
  explicit Obj(sollya_obj_t o = nullptr) : o_(o) {}
  Obj(const Obj&) = delete;
  Obj& operator=(const Obj&) = delete;
  ~Obj() {
    if (o_ != nullptr) sollya_lib_clear_obj(o_);
  }
  sollya_obj_t get() const { return o_; }
  sollya_obj_t release() { return std::exchange(o_, nullptr); }
  bool error() const { return o_ == nullptr || sollya_lib_obj_is_error(o_); }

 private:
  sollya_obj_t o_;
};

// raw 2^-frac_bits, exactly (64 bits of mantissa hold any int64).
sollya_obj_t dyadic(std::int64_t raw, int frac_bits) {
  mpfr_t v;
  mpfr_init2(v, 64);
  mpfr_set_sj(v, raw, MPFR_RNDN);
  mpfr_mul_2si(v, v, -frac_bits, MPFR_RNDN);
  sollya_obj_t o = sollya_lib_constant(v);
  mpfr_clear(v);
  return o;
}

sollya_obj_t x() {
  return sollya_lib_build_function_free_variable();
}

// t(v)^n with t = tau + (1 - tau) v (kU) or v (kT); tau and n are doubles, taken exactly.
sollya_obj_t target(FitVariable variable, double shininess, double tau) {
  sollya_obj_t t = x();
  if (variable == FitVariable::kU) {
    sollya_obj_t span = sollya_lib_build_function_sub(sollya_lib_constant_from_int(1),
                                                      sollya_lib_constant_from_double(tau));
    t = sollya_lib_build_function_add(sollya_lib_constant_from_double(tau),
                                      sollya_lib_build_function_mul(span, t));
  }
  return sollya_lib_build_function_pow(t, sollya_lib_constant_from_double(shininess));
}

// (a + (b - a) v)^n, a, b and n doubles taken exactly (b - a is exact: a segment's ends are
// dyadic).
sollya_obj_t segment_target(double shininess, double a, double b) {
  sollya_obj_t t = sollya_lib_build_function_add(
      sollya_lib_constant_from_double(a),
      sollya_lib_build_function_mul(sollya_lib_constant_from_double(b - a), x()));
  return sollya_lib_build_function_pow(t, sollya_lib_constant_from_double(shininess));
}

// sum raw_k 2^-frac_bits v^k in Horner form.
sollya_obj_t polynomial(const std::vector<std::int64_t>& raw, int frac_bits) {
  sollya_obj_t p = dyadic(raw.back(), frac_bits);
  for (std::size_t k = raw.size() - 1; k-- > 0;)
    p = sollya_lib_build_function_add(dyadic(raw[k], frac_bits),
                                      sollya_lib_build_function_mul(x(), p));
  return p;
}

// The coefficient of v^k of p as an integer multiple of 2^-frac_bits; false if it is none.
bool coefficient_raw(sollya_obj_t p, int k, int frac_bits, std::int64_t* out) {
  Obj degree(sollya_lib_constant_from_int(k));
  Obj c(sollya_lib_coeff(p, degree.get()));
  if (c.error()) return false;
  mpfr_t v;
  mpfr_init2(v, 512);
  bool ok = sollya_lib_get_constant(v, c.get()) != 0;
  if (ok) {
    mpfr_mul_2si(v, v, frac_bits, MPFR_RNDN);
    ok = mpfr_integer_p(v) && mpfr_fits_intmax_p(v, MPFR_RNDN);
    if (ok) *out = static_cast<std::int64_t>(mpfr_get_sj(v, MPFR_RNDN));
  }
  mpfr_clear(v);
  return ok;
}

// A Sollya list of `v`'s objects, which it takes (v is left empty).
sollya_obj_t take_list(std::vector<sollya_obj_t>& v) {
  Obj l(sollya_lib_list(v.data(), static_cast<int>(v.size())));
  for (sollya_obj_t e : v) sollya_lib_clear_obj(e);
  v.clear();
  return l.release();
}

// fpminimax's polynomial of `degree` as raw coefficients in r.raw; false, with r.failure, if it
// failed or a coefficient is off the grid.
bool read_raw(const Obj& fit, int degree, int frac_bits, FixedPointFit& r) {
  if (fit.error()) {
    r.failure = "fpminimax failed";
    return false;
  }
  r.raw.assign(static_cast<std::size_t>(degree) + 1, 0);
  for (int k = 0; k <= degree; ++k) {
    if (!coefficient_raw(fit.get(), k, frac_bits, &r.raw[static_cast<std::size_t>(k)])) {
      r.failure = "a coefficient off the fixed-point grid";
      return false;
    }
  }
  return true;
}

// The fit's raw coefficients as doubles (exact: each within a double's mantissa), or why not.
FixedPointFit with_coefficients(FixedPointFit r, int frac_bits) {
  for (std::int64_t c : r.raw) {
    if (c >= (std::int64_t{1} << 53) || c <= -(std::int64_t{1} << 53)) {
      r.failure = "a coefficient wider than a double's mantissa";
      return r;
    }
    r.coeffs.push_back(std::ldexp(static_cast<double>(c), -frac_bits));
  }
  r.ok = true;
  return r;
}

double elapsed_ms(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

}  // namespace

FixedPointFit fit_power_fixed_point(const FitOptions& o, int frac_bits,
                                    const std::vector<double>& start,
                                    const std::vector<double>* points) {
  FixedPointFit r;
  const int p = o.degree;
  if (o.domain != FitDomain::kTau || o.method != FitMethod::kMinimax) {
    r.failure = "fpminimax is used for the minimax fit on the tau domain only";
    return r;
  }
  if (o.constrain_zero != o.constrain_one) {
    r.failure = "one end constrained without the other";
    return r;
  }
  if (static_cast<int>(start.size()) != p + 1) {
    r.failure = "the start polynomial's degree differs";
    return r;
  }
  const bool constrained = o.constrain_one;
  // The free coefficients: with P(0) = 0 and P(1) = 1, P = v + sum_{k>=2} a_k (v^k - v) holds
  // both exactly for any a_k, and c_k = a_k, c_1 = 1 - sum a_k stay on the grid.
  const int first = constrained ? 2 : 0;
  if (first > p) {
    r.failure = "no free coefficient (degree 1 with both ends fixed is P = u)";
    return r;
  }
  if (frac_bits < 0 || frac_bits > 60) {
    r.failure = "fraction bits outside 0..60";
    return r;
  }
  if (points != nullptr && points->size() < static_cast<std::size_t>(p + 1 - first)) {
    r.failure = "fewer interpolation points than free coefficients";
    return r;
  }
  const auto clock = std::chrono::steady_clock::now();
  const std::lock_guard<std::mutex> lock(sollya_lock());
  ensure_sollya();

  std::vector<sollya_obj_t> basis, formats, start_coeffs;
  for (int k = first; k <= p; ++k) {
    sollya_obj_t g = sollya_lib_build_function_pow(x(), sollya_lib_constant_from_int(k));
    if (constrained) g = sollya_lib_build_function_sub(g, x());
    basis.push_back(g);
    formats.push_back(sollya_lib_constant_from_int(frac_bits));
    start_coeffs.push_back(sollya_lib_constant_from_double(start[static_cast<std::size_t>(k)]));
  }
  Obj f(target(FitVariable::kU, o.shininess, o.tau));
  Obj g(take_list(basis)), fmt(take_list(formats)), lc(take_list(start_coeffs));
  std::vector<sollya_obj_t> where;
  if (points != nullptr) {
    for (double v : *points) where.push_back(sollya_lib_constant_from_double(v));
  }
  Obj range(points != nullptr ? take_list(where) : sollya_lib_parse_string("[0;1]"));
  Obj absolute(sollya_lib_absolute()), fixed(sollya_lib_fixed());
  Obj q(constrained ? x() : sollya_lib_constant_from_int(0));
  Obj fit(sollya_lib_fpminimax(f.get(), g.get(), fmt.get(), range.get(), absolute.get(),
                               fixed.get(), q.get(), lc.get(), nullptr));
  r.milliseconds = elapsed_ms(clock);
  if (!read_raw(fit, p, frac_bits, r)) return r;
  if (constrained) {
    std::int64_t sum = 0;
    for (std::int64_t c : r.raw) sum += c;
    if (r.raw[0] != 0 || sum != (std::int64_t{1} << frac_bits)) {
      r.failure = "the constraints P(0) = 0, P(1) = 1 do not hold";
      return r;
    }
  }
  return with_coefficients(std::move(r), frac_bits);
}

namespace {

// Under sollya_lock(): Sollya's supnorm of p - f on [0, 1], both taken (cleared here).
CertifiedSupNorm sup_norm_of(sollya_obj_t polynomial_obj, sollya_obj_t target_obj,
                             std::chrono::steady_clock::time_point clock) {
  CertifiedSupNorm r;
  Obj p(polynomial_obj);
  Obj f(target_obj);
  Obj range(sollya_lib_parse_string("[0;1]"));
  Obj absolute(sollya_lib_absolute());
  // Enclosure within 2^-12 of its own width: three digits of the bound.
  Obj accuracy(sollya_lib_parse_string("2^-12"));
  Obj norm(sollya_lib_supnorm(p.get(), f.get(), range.get(), absolute.get(), accuracy.get()));
  r.milliseconds = elapsed_ms(clock);
  if (norm.error()) return r;
  mpfr_t lo, hi;
  mpfr_init2(lo, 128);
  mpfr_init2(hi, 128);
  if (sollya_lib_get_bounds_from_range(lo, hi, norm.get())) {
    r.ok = true;
    r.lo = mpfr_get_d(lo, MPFR_RNDD);
    r.hi = mpfr_get_d(hi, MPFR_RNDU);
  }
  mpfr_clear(lo);
  mpfr_clear(hi);
  return r;
}

}  // namespace

CertifiedSupNorm certified_sup_norm(const std::vector<std::int64_t>& raw, int frac_bits,
                                    FitVariable variable, double shininess, double tau) {
  if (raw.empty()) return {};
  const auto clock = std::chrono::steady_clock::now();
  const std::lock_guard<std::mutex> lock(sollya_lock());
  ensure_sollya();
  return sup_norm_of(polynomial(raw, frac_bits), target(variable, shininess, tau), clock);
}

CertifiedSupNorm certified_segment_sup_norm(const std::vector<std::int64_t>& raw, int frac_bits,
                                            double shininess, double a, double b) {
  if (raw.empty() || !(b > a)) return {};
  const auto clock = std::chrono::steady_clock::now();
  const std::lock_guard<std::mutex> lock(sollya_lock());
  ensure_sollya();
  return sup_norm_of(polynomial(raw, frac_bits), segment_target(shininess, a, b), clock);
}

FixedPointFit fit_segment_fixed_point(double shininess, double a, double b, int degree,
                                      int frac_bits, std::int64_t end0_raw, std::int64_t end1_raw,
                                      const std::vector<double>& start,
                                      const std::vector<double>& points) {
  FixedPointFit r;
  if (degree < 2) {
    r.failure = "no free coefficient (degree 1 with both ends fixed is the chord)";
    return r;
  }
  if (static_cast<int>(start.size()) != degree + 1) {
    r.failure = "the start polynomial's degree differs";
    return r;
  }
  if (frac_bits < 0 || frac_bits > 60 || !(b > a)) {
    r.failure = "fraction bits outside 0..60 or an empty segment";
    return r;
  }
  if (!points.empty() && static_cast<int>(points.size()) < degree - 1) {
    r.failure = "fewer interpolation points than free coefficients";
    return r;
  }
  const auto clock = std::chrono::steady_clock::now();
  const std::lock_guard<std::mutex> lock(sollya_lock());
  ensure_sollya();
  std::vector<sollya_obj_t> basis, formats, start_coeffs;
  for (int k = 2; k <= degree; ++k) {
    basis.push_back(sollya_lib_build_function_sub(
        sollya_lib_build_function_pow(x(), sollya_lib_constant_from_int(k)), x()));
    formats.push_back(sollya_lib_constant_from_int(frac_bits));
    start_coeffs.push_back(sollya_lib_constant_from_double(start[static_cast<std::size_t>(k)]));
  }
  Obj f(segment_target(shininess, a, b));
  Obj g(take_list(basis)), fmt(take_list(formats)), lc(take_list(start_coeffs));
  std::vector<sollya_obj_t> where;
  for (double v : points) where.push_back(sollya_lib_constant_from_double(v));
  Obj range(points.empty() ? sollya_lib_parse_string("[0;1]") : take_list(where));
  Obj absolute(sollya_lib_absolute()), fixed(sollya_lib_fixed());
  // The fixed part: the line through both ends, exactly on the grid.
  Obj q(sollya_lib_build_function_add(
      dyadic(end0_raw, frac_bits),
      sollya_lib_build_function_mul(dyadic(end1_raw - end0_raw, frac_bits), x())));
  Obj fit(sollya_lib_fpminimax(f.get(), g.get(), fmt.get(), range.get(), absolute.get(),
                               fixed.get(), q.get(), lc.get(), nullptr));
  r.milliseconds = elapsed_ms(clock);
  if (!read_raw(fit, degree, frac_bits, r)) return r;
  std::int64_t sum = 0;
  for (std::int64_t c : r.raw) sum += c;
  if (r.raw[0] != end0_raw || sum != end1_raw) {
    r.failure = "the segment's ends moved";
    return r;
  }
  return with_coefficients(std::move(r), frac_bits);
}

}  // namespace glint
