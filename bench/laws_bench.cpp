// laws_bench: cost of the rheology laws per contact-step, as a DDA host pays it.
//
// Sample run (Release build):
//   build/bench/laws_bench
//
// 1. Per contact-step cost of advance() (and of linearize(), which assembly
//    calls) for every law and scheme: 1e5 contacts x 100 steps, state kept by
//    the host in contiguous old/new arrays, step_constants() once per step,
//    one virtual call per contact through `const ContactRheology&`.
// 2. Why the recurrence matters: the seed's naive hereditary sum
//    d_c(t_n) = sum_i dF_i C(t_n - t_i) (eqs. 4-6) costs O(n) at step n, the
//    state-variable update O(1), whatever the history length.
// 3. Round-off drift of 1e6 steps of Burgers against the closed form.
// Times are thread CPU time (CLOCK_THREAD_CPUTIME_ID), best of 5 runs.
// Prints figures only; asserts nothing.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <ctime>
#include <memory>
#include <vector>

#include "rheodda/laws/registry.hpp"

using namespace rheodda::laws;

namespace {
// CPU time of this thread [s]: the machine is shared, and wall-clock time would
// count the time slices other processes take.
struct Clock {
  using time_point = double;
  static double now() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
  }
};
double seconds_since(double t0) { return Clock::now() - t0; }

// Table 1 row 1 of the seed (MPa, mm, h); the other laws take the relevant subset.
std::unique_ptr<ContactRheology> make(const std::string& name) {
  const double e1 = 26.87, e2 = 192.43, eta1 = 34807.72, eta2 = 2141.23;
  ParameterValues p;
  if (name == "burgers") p = {{"E1", e1}, {"E2", e2}, {"eta1", eta1}, {"eta2", eta2}};
  if (name == "maxwell") p = {{"E1", e1}, {"eta1", eta1}};
  if (name == "kelvin") p = {{"E2", e2}, {"eta2", eta2}};
  if (name == "nishihara") p = {{"E1", e1}, {"E2", e2}, {"eta2", eta2}, {"eta3", eta1}, {"Fs", 0.2}};
  if (name == "generalized-kelvin")
    p = {{"E1", e1}, {"E2", e2}, {"eta2", eta2}, {"E3", 0.5 * e2}, {"eta3", eta1}};
  // Nonlinear laws (docs/reference/laws.md): Norton A = tau_ref/eta1, n = 4; damage t_r = 234 h, r = 3.
  if (name == "power-law") p = {{"E1", e1}, {"A", 0.2 / eta1}, {"tau_ref", 0.2}, {"n", 4.0}};
  if (name == "power-law-burgers")
    p = {{"E1", e1}, {"E2", e2}, {"eta2", eta2}, {"A", 0.2 / eta1}, {"tau_ref", 0.2}, {"n", 4.0}};
  if (name == "damage-burgers")
    p = {{"E1", e1}, {"E2", e2}, {"eta2", eta2}, {"A", 0.2 / eta1}, {"tau_ref", 0.2}, {"n", 4.0},
         {"t_r", 234.0}, {"r", 3.0}};
  return LawRegistry::builtin().create(name, p);
}

volatile double g_sink = 0.0;  // keeps results alive

// ns per contact-step of advance() and of linearize(), best of 5 runs.
struct Cost { double advance_ns, linearize_ns; };
Cost contact_step_cost(const ContactRheology& law, Scheme scheme, std::size_t contacts, int steps) {
  std::vector<RheologyState> old_state(contacts), new_state(contacts);
  std::vector<double> f_start(contacts), f_end(contacts);
  for (std::size_t i = 0; i < contacts; ++i) {  // forces spread around the threshold 0.2
    f_start[i] = 0.1 + 0.2 * static_cast<double>(i % 1000) / 1000.0;
    f_end[i] = f_start[i] * 1.01;
  }
  const double dt = 0.5;  // [h]
  double best_adv = 1e300, best_lin = 1e300;
  for (int rep = 0; rep < 5; ++rep) {
    std::fill(old_state.begin(), old_state.end(), RheologyState{});
    double acc = 0.0;
    auto t0 = Clock::now();
    for (int s = 0; s < steps; ++s) {
      const StepConstants k = law.step_constants(dt, scheme);  // once per step
      for (std::size_t i = 0; i < contacts; ++i)
        acc += law.advance(k, old_state[i], f_start[i], f_end[i], new_state[i]);
      old_state.swap(new_state);
    }
    best_adv = std::min(best_adv, seconds_since(t0));
    t0 = Clock::now();
    for (int s = 0; s < steps; ++s) {
      const StepConstants k = law.step_constants(dt, scheme);
      for (std::size_t i = 0; i < contacts; ++i) {
        const Linearization l = law.linearize(k, old_state[i], f_start[i], f_end[i]);
        acc += l.h + l.c;
      }
    }
    best_lin = std::min(best_lin, seconds_since(t0));
    g_sink = g_sink + acc;
  }
  const double n = static_cast<double>(contacts) * steps;
  return {best_adv / n * 1e9, best_lin / n * 1e9};
}

// The naive hereditary sum at history length n for Burgers, ns per evaluation.
double naive_sum_ns(std::size_t n) {
  const double e2 = 192.43, eta1 = 34807.72, eta2 = 2141.23, dt = 0.5;
  std::vector<double> df(n), t(n);
  for (std::size_t i = 0; i < n; ++i) {
    df[i] = (i % 7 == 0) ? 0.01 : 0.0;
    t[i] = static_cast<double>(i) * dt;
  }
  const double tn = static_cast<double>(n) * dt;
  const int reps = static_cast<int>(std::max<std::size_t>(1, 20000000 / n));
  double acc = 0.0;
  const auto t0 = Clock::now();
  for (int r = 0; r < reps; ++r) {
    double d = 0.0;
    for (std::size_t i = 0; i < n; ++i)  // every increment, not only the non-zero ones
      d += df[i] * (-std::expm1(-e2 * (tn - t[i]) / eta2) / e2 + (tn - t[i]) / eta1);
    acc += d;
  }
  const double s = seconds_since(t0);
  g_sink = g_sink + acc;
  return s / reps * 1e9;
}

// The recurrence over n steps for one contact, ns per step.
double recurrence_ns(const ContactRheology& law, std::size_t n) {
  const StepConstants k = law.step_constants(0.5, Scheme::lagged);
  const int reps = static_cast<int>(std::max<std::size_t>(1, 20000000 / n));
  double acc = 0.0;
  const auto t0 = Clock::now();
  for (int r = 0; r < reps; ++r) {
    RheologyState state, next;
    double f = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      if (i % 7 == 0) f += 0.01;
      law.advance(k, state, f, f, next);
      state = next;
    }
    acc += state.creep();
  }
  const double s = seconds_since(t0);
  g_sink = g_sink + acc;
  return s / (static_cast<double>(reps) * static_cast<double>(n)) * 1e9;
}
}  // namespace

int main() {
  const std::size_t contacts = 100000;
  const int steps = 100;
  fmt::print("Rheology laws: cost per contact-step ({} contacts x {} steps, thread CPU time, best of 5)\n\n", contacts, steps);
  fmt::print(
      "The 1e5-contact arrays (8 MB) stream from memory; the 1e3-contact column (1e3 contacts x\n"
      "1e4 steps) stays in cache and shows the arithmetic alone.\n\n");
  fmt::print(
      "| law | scheme | advance [ns] | linearize [ns] | advance, in cache [ns] |\n"
      "|---|---|---|---|---|\n");
  for (const char* name : {"burgers", "maxwell", "kelvin", "nishihara", "generalized-kelvin", "power-law",
                           "power-law-burgers", "damage-burgers"}) {
    const auto law = make(name);
    for (Scheme scheme : {Scheme::lagged, Scheme::implicit, Scheme::exponential_linear}) {
      const Cost c = contact_step_cost(*law, scheme, contacts, steps);
      const Cost hot = contact_step_cost(*law, scheme, 1000, 10000);
      fmt::print("| {} | {} | {:.2f} | {:.2f} | {:.2f} |\n", name, scheme_name(scheme), c.advance_ns,
                 c.linearize_ns, hot.advance_ns);
    }
  }

  fmt::print(
      "\nBurgers, one contact: naive hereditary sum (seed eqs. 4-6) at step n vs the recurrence\n"
      "(one contact alone is latency-bound: each step waits for the previous state)\n\n");
  fmt::print("| n (history length) | naive sum at step n [ns] | recurrence per step [ns] | ratio |\n|---|---|---|---|\n");
  const auto burgers = make("burgers");
  g_sink = g_sink + naive_sum_ns(100000);  // warm-up (clock frequency, caches)
  for (std::size_t n : {1000u, 10000u, 100000u}) {
    const double naive = naive_sum_ns(n), rec = recurrence_ns(*burgers, n);
    fmt::print("| {} | {:.0f} | {:.2f} | {:.0f} |\n", n, naive, rec, naive / rec);
  }

  fmt::print("\nBurgers, 1e6 steps of 0.01 h at 0.232 MPa: relative drift from the closed form\n\n");
  for (Scheme scheme : {Scheme::lagged, Scheme::implicit, Scheme::exponential_linear}) {
    const StepConstants k = burgers->step_constants(0.01, scheme);
    RheologyState state, next;
    for (int i = 0; i < 1000000; ++i) {
      burgers->advance(k, state, 0.232, 0.232, next);
      state = next;
    }
    const double exact = burgers->creep_closed_form(0.232, 1e4);
    fmt::print("  {:<20} {:.2e}\n", scheme_name(scheme), std::abs(state.creep() - exact) / exact);
  }
  return 0;
}
