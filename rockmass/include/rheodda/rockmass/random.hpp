// Portable random numbers for joint generation: the same seed gives the same
// traces, bit for bit, on every machine.
//
// Why not <random>'s distributions: the standard fixes the engines
// (std::mt19937_64's output for a seed is specified) but not the distributions
// (std::normal_distribution differs between libstdc++, libc++ and MSVC), and
// std::log/std::exp/std::sin may differ in the last bit between C libraries.
// So the engine is std::mt19937_64 and everything after it is written here with
// + - * / and std::ldexp/std::frexp only (IEEE 754 exact rounding, no
// contraction: the library is compiled with -ffp-contract=off).
#pragma once

#include <cstdint>
#include <random>

namespace rheodda::rockmass {

/// Natural logarithm of x > 0 [-]: x = m 2^e with m in [sqrt(1/2), sqrt(2)),
/// ln m = 2 atanh(s), s = (m - 1)/(m + 1) (Abramowitz & Stegun 4.1.27), summed to
/// 1e-17; error below 2 ulp.
double portable_log(double x);
/// e^x for |x| < 700: x = k ln 2 + r, |r| <= ln2 / 2, Taylor series of e^r (A&S 4.2.1), times 2^k.
double portable_exp(double x);
/// sin and cos of x [rad] for |x| < 1e3: reduced to [-pi, pi], Taylor series (A&S 4.3.65, 4.3.66).
double portable_sin(double x);
double portable_cos(double x);

/// std::mt19937_64 and the distributions joint generation needs.
class PortableRandom {
 public:
  explicit PortableRandom(std::uint64_t seed) : engine_(seed) {}
  /// Uniform in (0, 1): the top 53 bits of one draw, + 1/2 ulp.
  double uniform();
  /// Standard normal N(0, 1) by Box-Muller (one draw of the pair, two uniforms).
  double normal();
  /// Exponential with the given mean: -mean ln U (inverse transform).
  double exponential(double mean);
  /// Log-normal with the given mean and standard deviation of the variable itself:
  /// sigma^2 = ln(1 + sd^2/mean^2), mu = ln(mean) - sigma^2/2, X = exp(mu + sigma Z).
  double log_normal(double mean, double deviation);

 private:
  std::mt19937_64 engine_;
};

}  // namespace rheodda::rockmass
