// A downstream program of the installed rheodda package (docs/guide/library.md): it
// uses the libraries through find_package(rheodda) only, and checks that they work.
//   1. rheodda::laws: a Burgers law from the registry, ten creep steps under a
//      constant force, against the closed form (docs/reference/laws.md, "burgers"):
//        d(t) = F/E1 + F/E2 (1 - exp(-E2 t/eta2)) + F t/eta1.
//   2. rheodda::scene + rheodda::core: a tiny scene file loaded, built and run
//      step by step by core::Engine; the joint's shear displacement against the
//      same closed form (the seed's eqs. 20-21, Table 1 row 1).
//   3. the installed `rheodda` command checks the same scene and prints the version
//      of the package and of rheodda/version.hpp.
// Usage: rheodda_package_app SCENE.yaml; exit 0 when every check passes, 1 otherwise.
#include <rheodda/contact/contact_system.hpp>
#include <rheodda/core/contact_adapter.hpp>
#include <rheodda/core/engine.hpp>
#include <rheodda/laws/registry.hpp>
#include <rheodda/scene/build.hpp>
#include <rheodda/scene/loader.hpp>
#include <rheodda/version.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

// This project sets no C++ standard: the rheodda targets' cxx_std_20 must have made it C++20.
static_assert(__cplusplus >= 202002L, "the rheodda targets should require C++20 (cxx_std_20) of their consumers");

namespace {

int failures = 0;

void expect_close(const char* what, double got, double expected, double rel_tol) {
  const double err = std::abs(got - expected) / std::abs(expected);
  const bool ok = err <= rel_tol;
  std::printf("%s %s: %.10g, closed form %.10g (relative error %.2e, tolerance %.0e)\n", ok ? "ok  " : "FAIL", what,
              got, expected, err, rel_tol);
  if (!ok) ++failures;
}

/// Burgers creep under a constant force F applied at t = 0 (docs/reference/laws.md, "burgers"):
/// F/E1 + F/E2 (1 - exp(-E2 t/eta2)) + F t/eta1 [length].
double burgers_closed_form(double F, double E1, double E2, double eta1, double eta2, double t) {
  return F / E1 + F / E2 * (1.0 - std::exp(-E2 * t / eta2)) + F * t / eta1;
}

// Table 1 row 1 of the seed: MPa/mm, MPa*h/mm; tau = 0.232 MPa.
constexpr double kE1 = 26.87, kE2 = 192.43, kEta1 = 34807.72, kEta2 = 2141.23, kTau = 0.232;

void law_steps() {
  using namespace rheodda::laws;
  const auto law =
      LawRegistry::builtin().create("burgers", {{"E1", kE1}, {"E2", kE2}, {"eta1", kEta1}, {"eta2", kEta2}});
  // Exponential-linear steps are exact for a constant force (docs/reference/laws.md, "Schemes").
  const double dt = 2.0;  // h
  const StepConstants k = law->step_constants(dt, Scheme::exponential_linear);
  RheologyState state, next;
  for (int i = 0; i < 10; ++i) {
    law->advance(k, state, kTau, kTau, next);
    state = next;
  }
  expect_close("burgers law, 10 steps of 2 h: d(20 h) [mm]", kTau / kE1 + state.creep(),
               burgers_closed_form(kTau, kE1, kE2, kEta1, kEta2, 20.0), 1e-12);
}

void scene_run(const std::string& file) {
  using namespace rheodda;
  const scene::SceneDescription s = scene::load_scene(file);
  scene::BuiltScene built = scene::build_scene(s);
  contact::ContactSystem contacts(built.joint_sets, built.contact_settings);
  core::ContactAdapter adapter(contacts);
  core::Engine engine(built.model, adapter);
  engine.run_until(s.analysis.duration);
  std::printf("scene %s: %d steps to t = %g h\n", file.c_str(), engine.step_count(), engine.time());
  if (engine.time() != s.analysis.duration) ++failures;
  // Mean shear displacement of the closed contacts of the joint set "plane" (index 0),
  // as history.csv's plane.shear_displacement (docs/reference/outputs.md).
  double sum = 0.0;
  int n = 0;
  for (const auto& c : contacts.contacts())
    if (c.joint_set == 0 && c.state != contact::ContactState::open) {
      sum += c.shear_displacement;
      ++n;
    }
  if (n == 0) {
    std::printf("FAIL no closed contact on the joint\n");
    ++failures;
    return;
  }
  // Same tolerance as tests/scene/run_test.cpp on the full example.
  expect_close("scene joint shear displacement at 20 h [mm]", std::abs(sum / n),
               burgers_closed_form(kTau, kE1, kE2, kEta1, kEta2, s.analysis.duration), 1e-3);
}

void installed_command(const std::string& file) {
  const std::string check = std::string(RHEODDA_INSTALLED_BINARY) + " check '" + file + "' > /dev/null";
  const int status = std::system(check.c_str());
  std::printf("%s %s\n", status == 0 ? "ok  " : "FAIL", check.c_str());
  if (status != 0) ++failures;
  // `rheodda --version` == "rheodda " + the find_package version == rheodda::kProgramVersion.
  std::string printed;
  if (FILE* p = ::popen((std::string(RHEODDA_INSTALLED_BINARY) + " --version").c_str(), "r")) {
    char buf[256];
    while (std::fgets(buf, sizeof buf, p)) printed += buf;
    ::pclose(p);
  }
  const std::string expected = std::string("rheodda ") + RHEODDA_PACKAGE_VERSION + "\n";
  const bool ok = printed == expected && expected == std::string(rheodda::kProgramVersion) + "\n";
  std::printf("%s rheodda --version: %s", ok ? "ok  " : "FAIL", printed.c_str());
  if (!ok) ++failures;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s SCENE.yaml\n", argv[0]);
    return 2;
  }
  try {
    law_steps();
    scene_run(argv[1]);
    installed_command(argv[1]);
  } catch (const std::exception& e) {
    std::printf("FAIL %s\n", e.what());
    return 1;
  }
  std::printf("%s\n", failures == 0 ? "all checks passed" : "some checks FAILED");
  return failures == 0 ? 0 : 1;
}
