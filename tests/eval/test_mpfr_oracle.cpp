// A high-precision oracle (MPFR, 200 bits) for what the accuracy contract measures in double:
// the reference lobes (t^n and Källberg's eq.7 Gaussian) and every unit's two real-valued models,
// model() at an input code (the unit's function at its quantized parameters) and float_model() at
// a real t (at the exact parameters). slot_contract() (eval/contract.h) takes its input, parameter
// and approximation parts from these doubles; the oracle shows each is within
//   |double - exact| <= 1e-13 |exact|  or  <= 1e-12 absolute (in units of the lobe's peak, the
//   unit every part of the contract is stated in)
// at random and edge points, i.e. the measurement error is at least 6 orders of magnitude below
// the smallest output ulp glint accepts (2^-20 ~ 9.5e-7), so the bounds built from it are not an
// artefact of double rounding. The absolute term is needed: Schlick's n - n t + t and Hast's
// 1/(1 - tau)^d cancel or amplify, costing up to ~n 2^-53 relative (7e-13 at n = 1e4), and the
// Gaussian's exp(-a^2) multiplies acos's rounding by 2 a^2. Each test prints its worst errors.
//
// The exact values are computed from what the unit states about itself: the JSON describe()
// (quantized n, root, k, raw coefficients and their format) through the SpecularUnit interface;
// lut's table entries are not in its description, so its datapath class is built beside the
// catalogue unit (and proven the same unit on every input code first).
#include <gtest/gtest.h>
#include <mpfr.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "eval/evaluate.h"
#include "reference/reference.h"
#include "units/catalogue.h"
#include "units/lut/datapath.h"

namespace glint {
namespace {

constexpr mpfr_prec_t kBits = 200;

// An MPFR number at 200 bits (RAII), with the few operations the models need, all rounded to
// nearest. Every intermediate is far more precise than the doubles under test.
class Mp {
 public:
  Mp() { mpfr_init2(v_, kBits); }
  Mp(double d) : Mp() { mpfr_set_d(v_, d, MPFR_RNDN); }  // NOLINT: implicit, for brevity
  Mp(const Mp& o) : Mp() { mpfr_set(v_, o.v_, MPFR_RNDN); }
  Mp& operator=(const Mp& o) {
    mpfr_set(v_, o.v_, MPFR_RNDN);
    return *this;
  }
  ~Mp() { mpfr_clear(v_); }

  friend Mp operator+(const Mp& a, const Mp& b) { return op(mpfr_add, a, b); }
  friend Mp operator-(const Mp& a, const Mp& b) { return op(mpfr_sub, a, b); }
  friend Mp operator*(const Mp& a, const Mp& b) { return op(mpfr_mul, a, b); }
  friend Mp operator/(const Mp& a, const Mp& b) { return op(mpfr_div, a, b); }
  friend Mp pow(const Mp& a, const Mp& b) { return op(mpfr_pow, a, b); }
  friend Mp acos(const Mp& a) { return op1(mpfr_acos, a); }
  friend Mp exp(const Mp& a) { return op1(mpfr_exp, a); }
  friend Mp floor(const Mp& a) {
    Mp r;
    mpfr_floor(r.v_, a.v_);
    return r;
  }
  friend bool operator<=(const Mp& a, const Mp& b) { return mpfr_lessequal_p(a.v_, b.v_) != 0; }
  friend Mp min(const Mp& a, const Mp& b) { return a <= b ? a : b; }
  friend Mp max(const Mp& a, const Mp& b) { return a <= b ? b : a; }
  static Mp ldexp(double d, long e) {
    Mp r(d);
    mpfr_mul_2si(r.v_, r.v_, e, MPFR_RNDN);
    return r;
  }
  double to_double() const { return mpfr_get_d(v_, MPFR_RNDN); }

 private:
  template <class F>
  static Mp op(F f, const Mp& a, const Mp& b) {
    Mp r;
    f(r.v_, a.v_, b.v_, MPFR_RNDN);
    return r;
  }
  template <class F>
  static Mp op1(F f, const Mp& a) {
    Mp r;
    f(r.v_, a.v_, MPFR_RNDN);
    return r;
  }
  mpfr_t v_;
};

// The oracle's tolerance (see the file comment). The error itself is computed in MPFR: got is a
// double, so got - exact is exact at 200 bits.
constexpr double kRelative = 1e-13, kAbsolute = 1e-12;

struct Worst {
  double rel = 0, abs = 0;
};

::testing::AssertionResult close(double got, const Mp& exact, Worst& worst) {
  const double err = std::fabs((Mp(got) - exact).to_double());
  const double ex = std::fabs(exact.to_double());
  const double rel = ex > 0 ? err / ex : (err > 0 ? INFINITY : 0.0);
  worst.abs = std::max(worst.abs, err);
  if (ex > 1e-300) worst.rel = std::max(worst.rel, rel);
  if (err <= kAbsolute || rel <= kRelative) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "double " << got << " vs exact " << exact.to_double()
                                       << ": error " << err << " (relative " << rel << ")";
}

// Random and edge real t in [0, 1]: 0, the smallest doubles, 1 - 2^-k, 1, near tau.
std::vector<double> real_points(std::mt19937_64& rng, double tau) {
  std::vector<double> t{0.0, 1e-300, 1e-12, 0.5, 1.0, std::nextafter(1.0, 0.0)};
  for (int k = 1; k <= 52; k += 3) t.push_back(1.0 - std::ldexp(1.0, -k));
  if (tau > 0 && tau < 1) {
    for (double d : {0.0, 1e-15, 1e-9, 1e-6, 1e-3}) t.push_back(std::min(1.0, tau + d));
  }
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int k = 0; k < 300; ++k) t.push_back(u(rng));
  // Dense near 1, where the lobes of large n live.
  for (int k = 0; k < 300; ++k) t.push_back(1.0 - std::pow(10.0, -8.0 * u(rng)));
  return t;
}

// Random and edge input codes: 0, 1, the threshold and its neighbours, 1.0 and beyond.
std::vector<std::int64_t> codes(std::mt19937_64& rng, const QFormat& in, std::int64_t threshold) {
  const std::int64_t one = in.raw_one(), top = in.raw_max();
  std::vector<std::int64_t> c{0, 1, 2, one - 2, one - 1, one, one + 1, top};
  for (std::int64_t d = -2; d <= 2; ++d)
    if (threshold + d >= 0 && threshold + d <= top) c.push_back(threshold + d);
  std::uniform_int_distribution<std::int64_t> all(0, top),
      high(std::max<std::int64_t>(0, threshold), one);
  for (int k = 0; k < 300; ++k) c.push_back(all(rng));
  for (int k = 0; k < 300; ++k) c.push_back(high(rng));
  return c;
}

// The materials: n from 0.3 to 1e4 and two luminances (c_y = 0.05 moves tau down).
std::vector<MaterialParams> materials() {
  std::vector<MaterialParams> out;
  for (double n : {0.3, 0.5, 1.0, 1.03, 2.0, 7.7, 20.0, 64.0, 128.0, 1000.0, 4096.0, 1e4}) {
    for (double cy : {1.0, 0.05}) {
      const TauResult t = tau_power(n, 1e-3, cy);
      MaterialParams m(n, t.tau, t.always_skip);
      m.level = t.eps / cy;
      out.push_back(m);
    }
  }
  return out;
}

// The quantized input as a real: min(code, 1.0) 2^-F.
Mp input(std::int64_t code, const QFormat& in) {
  return Mp::ldexp(static_cast<double>(std::min(code, in.raw_one())), -in.frac_bits);
}

// The u scaler's exact value (units/u_scaler.h): min(1, (t_q - root_q) k_q), 0 at or below the
// root, from the root and k the unit describes.
Mp u_exact(std::int64_t code, const QFormat& in, const nlohmann::json& slot) {
  const auto root = slot["root_raw"].get<std::int64_t>();
  if (code <= root) return Mp(0.0);
  const Mp k(slot["k"].get<double>());  // k_raw 2^-k_frac: exact in a double
  return min(Mp(1.0), (input(code, in) - Mp::ldexp(static_cast<double>(root), -in.frac_bits)) * k);
}

Mp horner_exact(const std::vector<Mp>& c, const Mp& u) {
  Mp acc(0.0);
  for (std::size_t k = c.size(); k-- > 0;) acc = acc * u + c[k];
  return min(Mp(1.0), max(Mp(0.0), acc));
}

TEST(MpfrOracle, ReferenceLobes) {
  std::mt19937_64 rng(7);
  Worst w;
  for (const MaterialParams& m : materials()) {
    for (double t : real_points(rng, m.tau)) {
      EXPECT_TRUE(close(glossy_scalar(t, m.shininess), pow(Mp(t), Mp(m.shininess)), w))
          << "t^n at t = " << t << ", n = " << m.shininess;
    }
  }
  // Källberg eq.7 down to lobes narrower than one input step of uq1.20.
  for (double omega : {1e-3, 3e-3, 0.01, 0.05, 0.2, 0.5, 1.0}) {
    for (double t : real_points(rng, -1)) {
      const Mp a = acos(Mp(t)) / Mp(omega);
      EXPECT_TRUE(close(gaussian_lobe(t, omega), exp(Mp(0.0) - a * a), w))
          << "Gaussian lobe at t = " << t << ", omega = " << omega;
    }
  }
  std::cout << "reference lobes: worst relative error " << w.rel << ", absolute " << w.abs << "\n";
}

// Every unit's model() and float_model() on every material, for several specs per unit.
class MpfrUnits : public ::testing::TestWithParam<const char*> {};

TEST_P(MpfrUnits, ModelsMatchTheOracle) {
  const std::string spec_text = GetParam();
  const std::vector<MaterialParams> mats = materials();
  const auto u = make_unit(parse_unit_spec(spec_text), mats);
  const nlohmann::json d = u->describe();
  const nlohmann::json& cfg = d["config"];
  const std::string name = u->name();
  const QFormat in = u->in_format();
  std::mt19937_64 rng(11);
  Worst wm, wf;
  for (std::size_t s = 0; s < mats.size(); ++s) {
    const MaterialParams& m = mats[s];
    const nlohmann::json& slot = d["slots"][s];
    const double tau = std::clamp(m.tau, 0.0, 1.0);
    const std::string what = spec_text + " n = " + std::to_string(m.shininess);

    // model(code) against the exact function at the parameters the unit states.
    std::function<Mp(std::int64_t)> model_exact;
    std::function<Mp(double)> float_exact;
    if (name == "pow") {
      const Mp nq(slot["n"].get<double>());
      model_exact = [&, nq](std::int64_t c) { return c <= 0 ? Mp(0.0) : pow(input(c, in), nq); };
      float_exact = [&](double t) { return t <= 0 ? Mp(0.0) : pow(Mp(t), Mp(m.shininess)); };
    } else if (name == "schlick") {
      const Mp nq(slot["n_q"].get<double>());
      const double n_prime = slot["n_prime"].get<double>();  // match=: Schlick's n' for this n
      const auto s_exact = [](const Mp& t, const Mp& n) { return t / (n - n * t + t); };
      model_exact = [&, nq, s_exact](std::int64_t c) {
        return c <= 0 ? Mp(0.0) : s_exact(input(c, in), nq);
      };
      float_exact = [&, s_exact, n_prime](double t) {
        return t <= 0 ? Mp(0.0) : s_exact(Mp(t), Mp(n_prime));
      };
    } else if (name == "hast") {
      const double dd = slot["d"].get<int>();
      model_exact = [&, dd](std::int64_t c) { return pow(u_exact(c, in, slot), Mp(dd)); };
      const bool dead = slot["root_raw"].get<std::int64_t>() >= in.raw_one();
      const double root = slot["root"].get<double>();  // Hast's tau: the exact root
      float_exact = [&, dd, dead, tau = root](double t) {
        if (dead || t <= tau) return Mp(0.0);
        return pow((Mp(t) - Mp(tau)) / (Mp(1.0) - Mp(tau)), Mp(dd));
      };
    } else if (name == "horner") {
      const int fh = parse_q_format(slot["coefficient_format"].get<std::string>()).frac_bits;
      std::vector<Mp> cq, cf;
      for (const auto& c : slot["coefficients_raw"])
        cq.push_back(Mp::ldexp(static_cast<double>(c.get<std::int64_t>()), -fh));
      for (const auto& c : slot["coefficients"]) cf.push_back(Mp(c.get<double>()));
      const bool tau_domain = cfg["domain"] == "tau";
      // The fit's domain is the u scaler's: [root code's value, 1].
      const double fit_tau = input(slot["root_raw"].get<std::int64_t>(), in).to_double();
      model_exact = [&, cq](std::int64_t c) { return horner_exact(cq, u_exact(c, in, slot)); };
      float_exact = [&, cf, tau_domain, tau = fit_tau](double t) {
        if (!tau_domain) return horner_exact(cf, Mp(t));
        if (t <= tau) return Mp(0.0);
        return horner_exact(cf, (Mp(t) - Mp(tau)) / (Mp(1.0) - Mp(tau)));
      };
    } else if (name == "lut") {
      // The datapath class beside the catalogue unit, for its table; the same unit on every code.
      LutConfig lc{in, u->out_format(), cfg["bits"].get<int>(), cfg["table_frac"].get<int>(),
                   cfg["skip"] == "on"};
      const auto lut = std::make_shared<LutUnit>(lc, m);
      for (std::int64_t c = 0; c <= in.raw_max(); ++c)
        ASSERT_EQ(lut->eval(c), u->eval(s, c)) << what << " code " << c;
      const Mp t0 = input(lut->t0_raw(), in);
      const double segs = std::ldexp(1.0, lc.bits);
      // Linear interpolation of node values f(j) at position (t - t0) / (1 - t0) 2^bits.
      const auto interp = [t0, segs](const Mp& t, const std::function<Mp(std::int64_t)>& node) {
        if (t <= t0 || Mp(1.0) <= t0) return Mp(0.0);
        const Mp pos = (min(t, Mp(1.0)) - t0) / (Mp(1.0) - t0) * Mp(segs);
        const Mp j = min(floor(pos), Mp(segs - 1));
        const auto ji = static_cast<std::int64_t>(j.to_double());
        const Mp a = node(ji), b = node(ji + 1);
        return a + (b - a) * (pos - j);
      };
      const int tf = lc.table_frac;
      model_exact = [&, lut, interp, tf](std::int64_t c) {
        return interp(input(c, in), [&](std::int64_t j) {
          return Mp::ldexp(static_cast<double>(lut->entry(j)), -tf);
        });
      };
      float_exact = [&, interp, t0, segs](double t) {
        return interp(Mp(t), [&](std::int64_t j) {
          const Mp node = static_cast<double>(j) == segs
                              ? Mp(1.0)
                              : t0 + (Mp(1.0) - t0) / Mp(segs) * Mp(static_cast<double>(j));
          return pow(node, Mp(m.shininess));
        });
      };
    } else {
      FAIL() << "no oracle for unit " << name;
    }
    for (std::int64_t c : codes(rng, in, u->tau_raw(s)))
      EXPECT_TRUE(close(u->model(s, c), model_exact(c), wm)) << what << ": model at code " << c;
    for (double t : real_points(rng, tau))
      EXPECT_TRUE(close(u->float_model(s, t), float_exact(t), wf))
          << what << ": float_model at t = " << t;
  }
  std::cout << spec_text << ": model worst relative " << wm.rel << ", absolute " << wm.abs
            << "; float_model worst relative " << wf.rel << ", absolute " << wf.abs << "\n";
}

INSTANTIATE_TEST_SUITE_P(Specs, MpfrUnits,
                         ::testing::Values("pow", "pow:in=uq1.18,n=uq14.8", "schlick",
                                           "schlick:n=uq16.8,out=uq1.20", "hast", "hast:d=1",
                                           "hast:d=16,in=uq1.12", "horner",
                                           "horner:degree=6,domain=full",
                                           "horner:degree=3,method=ls,out=uq1.20", "lut",
                                           "lut:bits=10,table_frac=24", "lut:skip=off,in=uq1.12"));

}  // namespace
}  // namespace glint
