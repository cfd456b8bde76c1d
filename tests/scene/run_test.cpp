// Running scenes: the shipped examples at reduced length against closed forms,
// the outputs agreeing with each other, and interrupt + resume giving the same
// files as an uninterrupted run (through the library and through real signals).
#include <boost/test/unit_test.hpp>

#include <sstream>

#include <csignal>
#include <cmath>
#include <fstream>
#include <numbers>
#include <nlohmann/json.hpp>
#include <fcntl.h>
#include <fmt/format.h>
#include <thread>
#include <unistd.h>

#include "run_support.hpp"
#include "rheodda/core/energy.hpp"
#include "rheodda/scene/loader.hpp"
#include "rheodda/scene/output.hpp"
#include "rheodda/scene/run.hpp"


using namespace rheodda;
using namespace rheodda::test;
namespace fs = std::filesystem;

namespace {

struct Csv {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  int column(const std::string& name) const {
    for (std::size_t i = 0; i < header.size(); ++i)
      if (header[i] == name) return static_cast<int>(i);
    BOOST_FAIL("no column " << name);
    return -1;
  }
  double at(std::size_t row, const std::string& name) const { return std::stod(rows.at(row).at(column(name))); }
};

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::string cell;
  std::stringstream ss(line);
  while (std::getline(ss, cell, ',')) out.push_back(cell);
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

Csv read_csv(const fs::path& p) {
  const std::string text = read_text(p.string());
  BOOST_TEST_REQUIRE(!text.empty());
  BOOST_TEST(text.back() == '\n');  // every line complete
  Csv csv;
  std::stringstream in(text);
  std::string line;
  std::getline(in, line);
  BOOST_TEST(line.rfind("# units: ", 0) == 0u);
  std::getline(in, line);
  csv.header = split(line);
  while (std::getline(in, line)) {
    csv.rows.push_back(split(line));
    BOOST_TEST(csv.rows.back().size() == csv.header.size(), "row " << csv.rows.size() << ": " << line);
  }
  return csv;
}

scene::SceneDescription example(const std::string& name, double duration, double interval) {
  auto s = scene::load_scene(source_path("examples/" + name));
  s.analysis.duration = duration;
  s.analysis.output_interval = interval;
  return s;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(scene_run)

BOOST_AUTO_TEST_CASE(shear_creep_example_follows_the_burgers_closed_form_of_table1_row1) {
  const auto s = example("shear-creep-test.yaml", 10.0, 2.0);
  const fs::path out = fresh_dir("shear");
  const auto r = run(s, out);
  BOOST_TEST((r.status == scene::RunStatus::completed));
  BOOST_TEST(r.steps == 10);
  BOOST_TEST(r.time == 10.0);
  const Csv h = read_csv(out / "history.csv");
  BOOST_TEST_REQUIRE(h.rows.size() == 6u);  // t = 0 and each output time, 2 ... 10 h
  const std::size_t last = h.rows.size() - 1;
  BOOST_TEST(h.at(last, "time") == 10.0);
  // Equilibrium: the joint's contacts together carry the shear force F2 = 13.92 N/mm.
  const double n = h.at(last, "plane.contacts");
  BOOST_TEST(std::abs(n * h.at(last, "plane.shear_force")) == 13.92, boost::test_tools::tolerance(1e-6));
  // Joint shear displacement under constant tau (Table 1 row 1; the seed's eqs. 20-21):
  //   d(t) = tau/E1 + tau/E2 (1 - exp(-E2 t/eta2)) + tau t/eta1.
  const double tau = 0.232, E1 = 26.87, E2 = 192.43, eta1 = 34807.72, eta2 = 2141.23;
  for (std::size_t k = 1; k < h.rows.size(); ++k) {
    const double t = h.at(k, "time");
    const double exact = tau / E1 + tau / E2 * (1.0 - std::exp(-E2 * t / eta2)) + tau * t / eta1;
    BOOST_TEST(std::abs(h.at(k, "plane.shear_displacement")) == exact, boost::test_tools::tolerance(1e-3));
  }
  // summary.json repeats the units and agrees with the CSV.
  const auto sum = nlohmann::json::parse(read_text((out / "summary.json").string()));
  BOOST_TEST(sum.at("status").get<std::string>() == "completed");
  BOOST_TEST(sum.at("units").at("length").get<std::string>() == "mm");
  BOOST_TEST(sum.at("steps").get<int>() == 10);
  BOOST_TEST(sum.at("frames").get<int>() == 6);
  BOOST_TEST(sum.at("inputs").at("joint_sets").at("plane").at("law").at("E1").get<double>() == 26.87);
  // inputs.analysis echoes every analysis key of the scene format, defaults filled in.
  for (const auto& m : scene::scene_schema())
    if (m.path == "analysis")
      for (const auto& key : m.keys)
        BOOST_TEST(sum.at("inputs").at("analysis").contains(key), "summary.json inputs.analysis lacks " << key);
  BOOST_TEST(sum.at("inputs").at("analysis").at("time_integration").get<std::string>() == "shi");
  BOOST_TEST(sum.at("scene_text").get<std::string>() == read_text(s.file));
  BOOST_TEST(sum.at("warnings").empty());
  // Two blocks: automatic solves with CHOLMOD, one analysis, a solve per iterate.
  BOOST_TEST(sum.at("solver").at("used").get<std::string>() == "cholmod");
  BOOST_TEST(sum.at("solver").at("solves").get<long>() >= 10);
  BOOST_TEST(sum.at("solver").at("cg_iterations").get<long>() == 0);
  BOOST_TEST(sum.at("solver").at("analyses").get<long>() == 1);
  // contact_changes: every iterate but the last of each step changed something
  // (no cuts here), so the changes are at least the extra solves, and none
  // without them.
  const auto& changes = sum.at("contact_changes");
  long total = 0;
  for (const char* kind : {"closed", "opened", "slipped", "stuck", "refinements"})
    total += changes.at(kind).get<long>();
  BOOST_TEST(sum.at("cuts").get<int>() == 0);
  const long extra_solves = sum.at("solver").at("solves").get<long>() - 10;
  BOOST_TEST(total >= extra_solves);
  BOOST_TEST((total == 0) == (extra_solves == 0));
  // blocks.pvd lists every frame; each frame holds both blocks.
  const std::string pvd = read_text((out / "blocks.pvd").string());
  for (int k = 0; k < 6; ++k) {
    const std::string f = fmt::format("frames/blocks_{:06d}.vtp", k);
    BOOST_TEST(pvd.find(f) != std::string::npos);
    const auto blocks = scene::read_vtk_polydata((out / f).string());
    BOOST_TEST(blocks.size() == 2u);
    BOOST_TEST(blocks[1].vertices.size() == 4u);
  }
  // contacts.csv: rows at output times only, the joint's contacts all closed.
  const Csv c = read_csv(out / "contacts.csv");
  BOOST_TEST(!c.rows.empty());
  // The contact layer of each frame (frames/contacts_NNNNNN.vtp, listed by contacts.pvd):
  // one point per contacts.csv row of that frame, at (x, y), with its fields.
  const std::string cpvd = read_text((out / "contacts.pvd").string());
  auto numbers = [](const std::string& text, const std::string& name) {
    const std::size_t at = text.find("Name=\"" + name + "\"");
    BOOST_TEST_REQUIRE(at != std::string::npos, name);
    const std::size_t start = text.find('>', at) + 1;
    std::istringstream in(text.substr(start, text.find("</DataArray>", start) - start));
    std::vector<double> v;
    for (double x; in >> x;) v.push_back(x);
    return v;
  };
  for (int k = 0; k < 6; ++k) {
    const std::string f = fmt::format("frames/contacts_{:06d}.vtp", k);
    BOOST_TEST(cpvd.find(f) != std::string::npos, f);
    const std::string layer = read_text((out / f).string());
    const double t = 2.0 * k;
    std::vector<const std::vector<std::string>*> rows;
    for (const auto& row : c.rows)
      if (std::stod(row[c.column("time")]) == t) rows.push_back(&row);
    const auto pts = numbers(layer, "Points"), normal = numbers(layer, "normal_force"),
               creep = numbers(layer, "creep_displacement"), state = numbers(layer, "state");
    BOOST_TEST_REQUIRE(normal.size() == rows.size(), f);
    BOOST_TEST_REQUIRE(pts.size() == 3 * rows.size(), f);
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const auto& row = *rows[i];
      BOOST_TEST(pts[3 * i] == std::stod(row[c.column("x")]), boost::test_tools::tolerance(1e-9));
      BOOST_TEST(pts[3 * i + 1] == std::stod(row[c.column("y")]), boost::test_tools::tolerance(1e-9));
      BOOST_TEST(normal[i] == std::stod(row[c.column("normal_force")]), boost::test_tools::tolerance(1e-9));
      BOOST_TEST(creep[i] == std::stod(row[c.column("creep_displacement")]), boost::test_tools::tolerance(1e-9));
      BOOST_TEST(state[i] == (row[c.column("state")] == "locked" ? 2.0 : row[c.column("state")] == "sliding" ? 1.0 : 0.0));
    }
  }
  for (const auto& row : c.rows) {
    BOOST_TEST(row[c.column("joint_set")] == "plane");
    BOOST_TEST(row[c.column("state")] != "open");
    const double t = std::stod(row[c.column("time")]);
    BOOST_TEST(std::fmod(t, 2.0) == 0.0);
  }
}

BOOST_AUTO_TEST_CASE(sliding_block_example_follows_the_incline_closed_form) {
  const double t = 0.3;
  const auto s = example("sliding-block.yaml", t, 0.05);
  const fs::path out = fresh_dir("slide");
  const auto r = run(s, out);
  BOOST_TEST((r.status == scene::RunStatus::completed));
  const Csv h = read_csv(out / "history.csv");
  const std::size_t last = h.rows.size() - 1;
  BOOST_TEST(h.at(last, "time") == t, boost::test_tools::tolerance(1e-12));
  const double u = h.at(last, "centre.u"), v = h.at(last, "centre.v");
  const double pi = 3.14159265358979323846, a = 30.0 * pi / 180.0, phi = 20.0 * pi / 180.0;
  const double d = 0.5 * 9.81 * (std::sin(a) - std::cos(a) * std::tan(phi)) * t * t;  // dda.md
  BOOST_TEST(std::hypot(u, v) == d, boost::test_tools::tolerance(0.02));
  BOOST_TEST(std::atan2(-v, -u) == a, boost::test_tools::tolerance(0.01));  // along the slope, downwards
}

BOOST_AUTO_TEST_CASE(a_static_block_that_slides_is_reported_as_a_mechanism_and_one_that_stands_is_not) {
  // docs/reference/engine.md, "Mechanisms in static analysis": the sliding-block example in
  // static analysis. At friction 20 deg on the 30 deg incline nothing but the
  // inertia term of each static step holds the block: it takes the unbalanced
  // force's work, a share (tan 30 - tan 20) / tan 30 = 0.37 of gravity's along the
  // slope (less the normal settling); every step is a mechanism step and the run
  // warns. At 40 deg the contact holds it: the share is that of the inertia term
  // against the contact springs, about (2M/dt^2) / k, and no warning.
  for (const double phi : {20.0, 40.0}) {
    // The example as a user would change it: type, step and friction in its text.
    std::string text = read_text(source_path("examples/sliding-block.yaml"));
    for (const auto& [from, to] : {std::pair<std::string, std::string>{"type: dynamic", "type: static"},
                                   {"duration: 1 ", "duration: 0.5 "},
                                   {"dt: 0.001 ", "dt: 0.01 "},
                                   {"friction_angle: 20,", fmt::format("friction_angle: {},", phi)}}) {
      const auto at = text.find(from);
      BOOST_TEST_REQUIRE(at != std::string::npos, from);
      text.replace(at, from.size(), to);
    }
    const fs::path out = fresh_dir(fmt::format("static_phi{}", phi));
    const fs::path file = out.parent_path() / fmt::format("static_phi{}.yaml", phi);
    std::ofstream(file) << text;
    const auto s = scene::load_scene(file.string());
    const auto r = run(s, out);
    BOOST_TEST_REQUIRE((r.status == scene::RunStatus::completed));
    const auto sum = nlohmann::json::parse(read_text((out / "summary.json").string()));
    const auto& m = sum.at("static_mechanism");
    const Csv h = read_csv(out / "history.csv");
    const std::size_t last = h.rows.size() - 1;
    const double slip = std::hypot(h.at(last, "centre.u"), h.at(last, "centre.v"));
    bool warned = false, settle_hint = false;
    for (const auto& w : r.warnings) {
      warned = warned || w.find("moved as a mechanism") != std::string::npos;
      settle_hint = settle_hint || w.find("analysis.settle") != std::string::npos;
      // Short, and it says what to do (issue 52: warnings of 400-900 characters).
      BOOST_TEST(w.size() - file.string().size() < 450u, w);
      BOOST_TEST(w.find("Check with both halved (`rheodda check " + file.string() + " --refine`)") != std::string::npos, w);
    }
    if (phi == 20.0) {
      BOOST_TEST(slip > 1e-3);  // it slides
      BOOST_TEST(m.at("inertia_share").get<double>() > 0.2);
      BOOST_TEST(m.at("inertia_share").get<double>() < 0.5);
      BOOST_TEST(m.at("steps").get<int>() == r.steps);
      BOOST_TEST(m.at("first_time").get<double>() == s.analysis.dt, boost::test_tools::tolerance(1e-9));
      BOOST_TEST(h.at(last, "inertia_share") > core::kMechanismStepShare);
      BOOST_TEST(warned);
      BOOST_TEST(settle_hint);  // from its first step, with no settling stage: the remedy is named
    } else {
      BOOST_TEST(slip < 1e-5);  // it stands
      BOOST_TEST(m.at("inertia_share").get<double>() < core::kMechanismRunShare);
      BOOST_TEST(m.at("steps").get<int>() == 0);
      BOOST_TEST(m.at("first_time").is_null());
      BOOST_TEST(!warned);
    }
  }
  // A dynamic analysis has no static mechanism to report.
  const auto d = example("sliding-block.yaml", 0.05, 0.05);
  const fs::path out = fresh_dir("dynamic_mechanism");
  BOOST_TEST_REQUIRE((run(d, out).status == scene::RunStatus::completed));
  BOOST_TEST(nlohmann::json::parse(read_text((out / "summary.json").string())).at("static_mechanism").is_null());
}

BOOST_AUTO_TEST_CASE(a_static_slide_with_collapse_stages_follows_the_dynamics_and_lists_its_stages) {
  // docs/reference/engine.md, "Collapse stages": the static sliding block of the test
  // above (phi 20 deg on the 30 deg incline, dt 0.01 s), with a dynamic
  // settling stage of 0.01 s and collapse_dt 0.002 s. Every static step would
  // move as a mechanism, so the slide is taken in stages end to end: the slip
  // at 0.5 s is the dynamic closed form g (sin a - cos a tan phi) t^2 / 2
  // (the static run slid a share of it set by dt), and summary.json lists the
  // stages from the end of the settling stage on.
  std::string text = read_text(source_path("examples/sliding-block.yaml"));
  for (const auto& [from, to] :
       {std::pair<std::string, std::string>{"type: dynamic", "type: static"},
        {"duration: 1 ", "duration: 0.5 "},
        {"dt: 0.001 ", "dt: 0.01\n  settle: {type: dynamic, until: 0.01, dt: 0.001, collapse_dt: 0.002}\n  # "}}) {
    const auto at = text.find(from);
    BOOST_TEST_REQUIRE(at != std::string::npos, from);
    text.replace(at, from.size(), to);
  }
  const fs::path out = fresh_dir("static_collapse_stages");
  const fs::path file = out.parent_path() / "static_collapse_stages.yaml";
  std::ofstream(file) << text;
  const auto s = scene::load_scene(file.string());
  const auto r = run(s, out);
  BOOST_TEST_REQUIRE((r.status == scene::RunStatus::completed));
  const auto stages = nlohmann::json::parse(read_text((out / "summary.json").string()))
                          .at("static_mechanism")
                          .at("collapse_stages");
  BOOST_TEST_REQUIRE(stages.size() >= 1u);
  BOOST_TEST(stages[0].get<double>() == 0.01, boost::test_tools::tolerance(1e-9));
  BOOST_TEST(r.mechanism.collapse_stages.size() == stages.size());
  const Csv h = read_csv(out / "history.csv");
  const std::size_t last = h.rows.size() - 1;
  const double t = h.at(last, "time"), a = 30.0 * std::numbers::pi / 180.0, phi = 20.0 * std::numbers::pi / 180.0;
  const double slip = std::hypot(h.at(last, "centre.u"), h.at(last, "centre.v"));
  BOOST_TEST(slip == 0.5 * 9.81 * (std::sin(a) - std::cos(a) * std::tan(phi)) * t * t,
             boost::test_tools::tolerance(0.02));
}

BOOST_AUTO_TEST_CASE(the_toppling_example_settles_in_its_stage_then_converges_with_its_step_controls) {
  // docs/reference/engine.md, "Settling stage"; docs/notes/step-controls.md, "The shipped toppling
  // example": examples/goodman-toppling-creep.yaml settles in steps of at most
  // 5e-5 d to 0.01 d, then creeps with dt = 1/32 d. Its steps obey the stage; with
  // every step control halved (the stage's too: dt, max_displacement_ratio, the stage's dt and max_displacement_ratio) it
  // ends 100 d within the 0.5 % that the six levels of `check --refine` span
  // (block 10 at 3.276-3.281 m), neither run moving as a mechanism.
  auto s = example("goodman-toppling-creep.yaml", 100.0, 100.0);
  BOOST_TEST_REQUIRE(s.analysis.has_settle());
  BOOST_TEST(s.analysis.dt == 0.03125);
  BOOST_TEST(s.analysis.open_close_limit == 8);  // the static default
  std::vector<double> block10;
  for (const double f : {1.0, 0.5}) {
    auto level = s;
    level.analysis.dt *= f;
    level.analysis.max_displacement_ratio *= f;
    level.analysis.settle.dt *= f;
    level.analysis.settle.max_displacement_ratio *= f;
    const fs::path out = fresh_dir(fmt::format("settle_{}", f));
    const auto r = run(level, out);
    BOOST_TEST_REQUIRE((r.status == scene::RunStatus::completed));
    const Csv h = read_csv(out / "history.csv");  // output_interval 100: t = 0 and 100 only; steps from the reports
    const std::size_t last = h.rows.size() - 1;
    block10.push_back(std::hypot(h.at(last, "block10_top.u"), h.at(last, "block10_top.v")));
    const auto sum = nlohmann::json::parse(read_text((out / "summary.json").string()));
    BOOST_TEST(sum.at("static_mechanism").at("inertia_share").get<double>() < core::kMechanismRunShare);
    BOOST_TEST(sum.at("inputs").at("analysis").at("settle").at("until").get<double>() == 0.01);
    // The stage's steps (0.01 d / its dt, cuts allowed) and then (100 - 0.01) / dt creep steps.
    BOOST_TEST(r.steps >= static_cast<int>(std::floor(0.01 / level.analysis.settle.dt + 0.5)) +
                             static_cast<int>(std::floor((100.0 - 0.01) / level.analysis.dt)));
  }
  BOOST_TEST(std::abs(block10[0] - block10[1]) < 5e-3 * block10[1], block10[0] << " vs " << block10[1]);
  BOOST_TEST(block10[1] > 3.0);  // it creeps metres: a result, not a slope at rest
}

BOOST_AUTO_TEST_CASE(goodman_example_runs_its_first_days_with_finite_outputs) {
  const auto s = example("goodman-toppling.yaml", 2.0, 1.0);
  const fs::path out = fresh_dir("goodman");
  const auto r = run(s, out);
  BOOST_TEST((r.status == scene::RunStatus::completed));
  const Csv h = read_csv(out / "history.csv");
  for (const auto& row : h.rows)
    for (std::size_t k = 0; k < row.size(); ++k)
      if (!row[k].empty()) BOOST_TEST(std::isfinite(std::stod(row[k])), h.header[k]);
  // The base is held by its fixed points (`fixed: true`): its vertices stay put to within
  // 1e-5 of the model size, while the columns on it move.
  const auto frame = scene::read_vtk_polydata((out / "frames/blocks_000002.vtp").string());
  BOOST_TEST_REQUIRE(frame.size() == 17u);
  for (const auto& d : frame[0].displacement) BOOST_TEST(std::hypot(d[0], d[1]) < 1e-5 * 215.0);
  const std::size_t last = h.rows.size() - 1;
  BOOST_TEST(std::hypot(h.at(last, "block10_top.u"), h.at(last, "block10_top.v")) > 0.0);
}

BOOST_AUTO_TEST_CASE(interrupted_then_resumed_run_writes_the_same_files_as_an_uninterrupted_one) {
  const auto s = example("sliding-block.yaml", 0.1, 0.01);
  const fs::path whole = fresh_dir("whole"), split_dir = fresh_dir("split");
  BOOST_TEST((run(s, whole).status == scene::RunStatus::completed));

  const auto first = run(s, split_dir, 37);
  BOOST_TEST((first.status == scene::RunStatus::interrupted));
  BOOST_TEST(first.steps == 37);
  // Consistent up to the stop: whole lines only, one per output time (0, 0.01, 0.02,
  // 0.03 s), summary says so.
  const Csv partial = read_csv(split_dir / "history.csv");
  BOOST_TEST(partial.rows.size() == 4u);
  const auto sum = nlohmann::json::parse(read_text((split_dir / "summary.json").string()));
  BOOST_TEST(sum.at("status").get<std::string>() == "interrupted");

  const auto second = run(s, split_dir, -1, true);
  BOOST_TEST((second.status == scene::RunStatus::completed));
  BOOST_TEST(second.resumed_from_step == 37);
  BOOST_TEST(second.steps == run(s, fresh_dir("whole2")).steps);
  for (const char* f : {"history.csv", "contacts.csv", "blocks.pvd", "frames/blocks_000010.vtp", "frames/blocks_000004.vtp"})
    BOOST_TEST(read_text((split_dir / f).string()) == read_text((whole / f).string()), f);
}

BOOST_AUTO_TEST_CASE(step_tolerance_runs_the_shear_creep_example_on_the_closed_form_in_growing_steps) {
  // Constant load: the doubled and the halved steps agree, the step doubles
  // from dt = 0.1 h; every step is extrapolated; the joint follows eqs. 20-21
  // as a fixed-step run does (to ~1e-5 at any step: the model's own
  // departure, docs/reference/outputs.md) and ends where a fixed-step run ends.
  const auto fixed_scene = example("shear-creep-test.yaml", 200.0, 50.0);
  const fs::path fixed_out = fresh_dir("shear-fixed");
  BOOST_TEST_REQUIRE((run(fixed_scene, fixed_out).status == scene::RunStatus::completed));
  const Csv fixed = read_csv(fixed_out / "history.csv");
  auto s = fixed_scene;
  s.analysis.dt = 0.1;
  s.analysis.step_tolerance = 1e-6;  // [mm]
  const fs::path out = fresh_dir("shear-doubling");
  const auto r = run(s, out);
  BOOST_TEST((r.status == scene::RunStatus::completed));
  BOOST_TEST(r.steps < 30);  // 2000 steps of dt
  const Csv h = read_csv(out / "history.csv");
  const double tau = 0.232, E1 = 26.87, E2 = 192.43, eta1 = 34807.72, eta2 = 2141.23;
  for (std::size_t k = 1; k < h.rows.size(); ++k) {
    const double t = h.at(k, "time");
    const double exact = tau / E1 + tau / E2 * (1.0 - std::exp(-E2 * t / eta2)) + tau * t / eta1;
    BOOST_TEST(std::abs(h.at(k, "plane.shear_displacement")) == exact, boost::test_tools::tolerance(3e-5));
    if (k > 1 && h.at(k - 1, "time") > 0.0 && std::fmod(h.at(k - 1, "time"), 50.0) != 0.0 &&
        std::fmod(t, 50.0) != 0.0)
      BOOST_TEST(h.at(k, "dt") == 2 * h.at(k - 1, "dt"), boost::test_tools::tolerance(1e-12));
  }
  BOOST_TEST(h.at(h.rows.size() - 1, "time") == 200.0);
  BOOST_TEST(h.at(h.rows.size() - 1, "plane.shear_displacement") ==
                 fixed.at(fixed.rows.size() - 1, "plane.shear_displacement"),
             boost::test_tools::tolerance(1e-8));
  const auto sum = nlohmann::json::parse(read_text((out / "summary.json").string()));
  BOOST_TEST(sum.at("extrapolated_steps").get<int>() == r.steps);
  BOOST_TEST(sum.at("redone").get<int>() == 0);
  BOOST_TEST(sum.at("inputs").at("analysis").at("step_tolerance").get<double>() == 1e-6);
  BOOST_TEST(sum.at("inputs").at("analysis").at("step_extrapolation").get<bool>());
}

BOOST_AUTO_TEST_CASE(a_step_doubling_run_interrupted_and_resumed_writes_the_same_files) {
  // The creeping slope from its unsettled start: settling at dt, then creep in
  // growing doubled steps; stopped after 8 steps and resumed.
  auto s = example("goodman-toppling-creep.yaml", 10.0, 5.0);
  s.analysis.dt = 0.01;
  s.analysis.step_tolerance = 1e-3;  // [m]
  const fs::path whole = fresh_dir("doubling-whole"), split_dir = fresh_dir("doubling-split");
  const auto all = run(s, whole);
  BOOST_TEST_REQUIRE((all.status == scene::RunStatus::completed));
  BOOST_TEST(all.steps > 8);
  const auto sum = nlohmann::json::parse(read_text((whole / "summary.json").string()));
  BOOST_TEST(sum.at("extrapolated_steps").get<int>() > 0);
  BOOST_TEST(sum.at("extrapolated_steps").get<int>() <= all.steps);
  BOOST_TEST((run(s, split_dir, 8).status == scene::RunStatus::interrupted));
  const auto second = run(s, split_dir, -1, true);
  BOOST_TEST((second.status == scene::RunStatus::completed));
  BOOST_TEST(second.steps == all.steps);
  for (const char* f : {"history.csv", "contacts.csv", "blocks.pvd", "frames/blocks_000002.vtp"})
    BOOST_TEST(read_text((split_dir / f).string()) == read_text((whole / f).string()), f);
}

BOOST_AUTO_TEST_CASE(resume_refuses_a_scene_that_changed_since_the_checkpoint) {
  auto s = example("sliding-block.yaml", 0.05, 0.01);
  const fs::path out = fresh_dir("changed");
  BOOST_TEST((run(s, out, 10).status == scene::RunStatus::interrupted));
  scene::RunOptions o;
  o.out_dir = out.string();
  o.resume = true;
  BOOST_CHECK_THROW(scene::run_scene(s, read_text(s.file) + "# edited\n", o), std::invalid_argument);
}

BOOST_AUTO_TEST_CASE(sigterm_stops_the_command_between_steps_and_resume_completes_it) {
  // The full sliding-block example (1000 steps) through the real binary.
  const fs::path whole = fresh_dir("sig-whole"), cut = fresh_dir("sig-cut");
  const std::string scene = source_path("examples/sliding-block.yaml");
  BOOST_TEST_REQUIRE(run_rheodda("run " + scene + " -o " + whole.string()).exit_code == 0);

  const pid_t pid = spawn_rheodda({"run", scene, "-o", cut.string()});
  // Wait (by watching the file, not the clock) until some steps are written, then signal.
  int status = 0;
  for (;;) {
    std::error_code ec;
    if (fs::exists(cut / "history.csv", ec) && fs::file_size(cut / "history.csv", ec) > 3000) break;
    BOOST_TEST_REQUIRE(::waitpid(pid, &status, WNOHANG) == 0, "the run ended before it could be signalled");
    std::this_thread::yield();
  }
  ::kill(pid, SIGTERM);
  ::waitpid(pid, &status, 0);
  BOOST_TEST_REQUIRE(WIFEXITED(status));
  BOOST_TEST(WEXITSTATUS(status) == 128 + SIGTERM);
  const auto sum = nlohmann::json::parse(read_text((cut / "summary.json").string()));
  BOOST_TEST(sum.at("status").get<std::string>() == "interrupted");
  const Csv partial = read_csv(cut / "history.csv");
  BOOST_TEST(partial.rows.size() < 1001u);

  const auto resumed = run_rheodda("run " + scene + " -o " + cut.string() + " --resume");
  BOOST_TEST(resumed.exit_code == 0, resumed.output);
  for (const char* f : {"history.csv", "contacts.csv", "blocks.pvd", "frames/blocks_000050.vtp"})
    BOOST_TEST(read_text((cut / f).string()) == read_text((whole / f).string()), f);
}

BOOST_AUTO_TEST_SUITE_END()
