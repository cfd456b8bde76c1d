// Portable elementary functions and distributions (random.hpp says why).
#include "rheodda/rockmass/random.hpp"

#include <cmath>

namespace rheodda::rockmass {

namespace {
constexpr double kLn2 = 0.69314718055994530942;
constexpr double kPi = 3.14159265358979323846;
}  // namespace

double portable_log(double x) {
  int e = 0;
  double m = std::frexp(x, &e);  // x = m 2^e, m in [0.5, 1): exact
  if (m < 0.70710678118654752440) {
    m *= 2.0;  // exact
    --e;
  }
  // ln m = 2 (s + s^3/3 + s^5/5 + ...), |s| <= 0.172, s^2 <= 0.0295: 14 terms reach 1e-22.
  const double s = (m - 1.0) / (m + 1.0);
  const double s2 = s * s;
  double term = s, sum = 0.0;
  for (int k = 0; k < 14; ++k) {
    sum += term / double(2 * k + 1);
    term *= s2;
  }
  return double(e) * kLn2 + 2.0 * sum;
}

double portable_exp(double x) {
  const double k = std::floor(x / kLn2 + 0.5);
  const double r = x - k * kLn2;  // |r| <= 0.35
  // Taylor series of e^r: 24 terms, 0.35^24/24! < 1e-34.
  double term = 1.0, sum = 1.0;
  for (int n = 1; n < 24; ++n) {
    term *= r / double(n);
    sum += term;
  }
  return std::ldexp(sum, static_cast<int>(k));
}

namespace {
/// x reduced to [-pi, pi] by whole turns.
double reduce(double x) {
  const double turns = std::floor(x / (2.0 * kPi) + 0.5);
  return x - turns * (2.0 * kPi);
}
}  // namespace

double portable_sin(double x) {
  const double r = reduce(x);
  // sin r = r - r^3/3! + ...: 30 terms, pi^61/61! < 1e-50.
  double term = r, sum = r;
  for (int n = 1; n < 30; ++n) {
    term *= -r * r / double((2 * n) * (2 * n + 1));
    sum += term;
  }
  return sum;
}

double portable_cos(double x) {
  const double r = reduce(x);
  double term = 1.0, sum = 1.0;
  for (int n = 1; n < 30; ++n) {
    term *= -r * r / double((2 * n - 1) * (2 * n));
    sum += term;
  }
  return sum;
}

double PortableRandom::uniform() {
  // 53 random bits k: (k + 1/2) 2^-53 is in (0, 1), never 0 (log-safe), never 1.
  const std::uint64_t k = engine_() >> 11;
  return (double(k) + 0.5) * 0x1.0p-53;
}

double PortableRandom::normal() {
  // Box-Muller: Z = sqrt(-2 ln U1) cos(2 pi U2) (Box & Muller 1958).
  const double u1 = uniform(), u2 = uniform();
  return std::sqrt(-2.0 * portable_log(u1)) * portable_cos(2.0 * kPi * u2);
}

double PortableRandom::exponential(double mean) { return -mean * portable_log(uniform()); }

double PortableRandom::log_normal(double mean, double deviation) {
  const double sigma2 = portable_log(1.0 + (deviation * deviation) / (mean * mean));
  const double mu = portable_log(mean) - 0.5 * sigma2;
  return portable_exp(mu + std::sqrt(sigma2) * normal());
}

}  // namespace rheodda::rockmass
