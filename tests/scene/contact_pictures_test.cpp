// Where creep and slip act (docs/reference/outputs.md, "contacts.csv" and "Pictures:
// rheodda plot"): contacts.csv's shear_strength is the Mohr-Coulomb strength
// N tan(phi) + c l, its tributary_length the joint length each contact stands for,
// and `rheodda plot` draws the contacts by state and column and the joint stress
// against strength at each drawn frame.
#include <boost/test/unit_test.hpp>

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>

#include "run_support.hpp"
#include "rheodda/scene/loader.hpp"
#include "rheodda/scene/plot.hpp"
#include "rheodda/scene/run.hpp"

using namespace rheodda;
using namespace rheodda::test;
namespace fs = std::filesystem;

namespace {

/// contacts.csv's rows, each as a map from column to cell.
std::vector<std::map<std::string, std::string>> contact_rows(const fs::path& out) {
  std::istringstream in(read_text((out / "contacts.csv").string()));
  std::string line;
  std::vector<std::string> header;
  std::vector<std::map<std::string, std::string>> rows;
  auto cells = [](const std::string& l) {
    std::vector<std::string> c;
    std::string x;
    std::stringstream ss(l);
    while (std::getline(ss, x, ',')) c.push_back(x);
    return c;
  };
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (header.empty()) {
      header = cells(line);
      continue;
    }
    const auto c = cells(line);
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < header.size() && i < c.size(); ++i) row[header[i]] = c[i];
    rows.push_back(std::move(row));
  }
  return rows;
}

double num(const std::map<std::string, std::string>& row, const std::string& column) {
  BOOST_TEST_REQUIRE(row.count(column) == 1u, "contacts.csv has no column " << column);
  return std::stod(row.at(column));
}

/// A 1 m x 0.5 m block (2600 kg/m^3) resting on a wide fixed base: static, 2 steps.
std::string resting_block(double friction_deg, double cohesion) {
  return fmt::format(R"(title: resting block
units: {{length: m, force: N, time: s}}
analysis: {{type: static, duration: 2, dt: 1, gravity: [0, -9.81]}}
materials:
  rock: {{density: 2600, young_modulus: 5.0e9, poisson_ratio: 0.25}}
joint_sets:
  bed: {{friction_angle: {}, cohesion: {}}}
blocks:
  - {{name: base, polygon: [[-2, -1], [3, -1], [3, 0], [-2, 0]], fixed: true}}
  - {{name: block, polygon: [[0, 0], [1, 0], [1, 0.5], [0, 0.5]]}}
)",
                     friction_deg, cohesion);
}

}  // namespace

BOOST_AUTO_TEST_SUITE(contact_pictures)

BOOST_AUTO_TEST_CASE(shear_strength_is_mohr_coulomb_and_tributary_lengths_cover_the_joint) {
  // At rest on a horizontal joint: the normal forces carry the weight W = rho g A, the
  // strengths add up to W tan(phi) + c b (b = 1 m, the joint's length, which the
  // tributary lengths of the contacts cover), and each row's strength is its own
  // N tan(phi) + c l.
  const fs::path dir = fresh_dir("contact-strength");
  const fs::path file = dir / "resting.yaml";
  std::ofstream(file) << resting_block(30.0, 1.0e4);
  const auto s = scene::load_scene(file.string());
  BOOST_TEST_REQUIRE((run(s, dir / "out").status == scene::RunStatus::completed));
  const double W = 2600.0 * 9.81 * 0.5, tan_phi = std::tan(30.0 * std::numbers::pi / 180.0);
  double n = 0.0, strength = 0.0, tributary = 0.0;
  int closed = 0;
  for (const auto& r : contact_rows(dir / "out")) {
    if (num(r, "time") != 2.0 || r.at("state") == "open") continue;
    ++closed;
    n += num(r, "normal_force");
    strength += num(r, "shear_strength");
    tributary += num(r, "tributary_length");
    BOOST_TEST(num(r, "shear_strength") ==
                   std::max(num(r, "normal_force"), 0.0) * tan_phi + 1.0e4 * num(r, "length"),
               boost::test_tools::tolerance(1e-9));
    BOOST_TEST(r.at("state") == "locked");
    BOOST_TEST(std::abs(num(r, "shear_force")) < num(r, "shear_strength"));
  }
  BOOST_TEST_REQUIRE(closed > 0);
  // To the block's strain: DDA loads gravity over the block's current area and the
  // contacts have its current length, both changed by about sigma / E = 12 753 Pa / 5 GPa
  // = 2.6e-6 of theirs under its own weight (the normal forces add up to 1 - 1.05e-6 of W,
  // the tributary lengths to 1 + 2.5e-8 m).
  BOOST_TEST(n == W, boost::test_tools::tolerance(1e-5));
  BOOST_TEST(strength == W * tan_phi + 1.0e4 * 1.0, boost::test_tools::tolerance(1e-5));
  BOOST_TEST(tributary == 1.0, boost::test_tools::tolerance(1e-5));
}

BOOST_AUTO_TEST_CASE(a_sliding_contact_mobilises_its_whole_strength_and_point_contacts_have_a_tributary_length) {
  // The block sliding down 30 deg at phi = 20 deg (examples/sliding-block.yaml): every
  // sliding contact carries its strength, |F_s| = N tan(20 deg); contacts of length 0
  // (vertex-edge) stand for a joint length > 0.
  const fs::path out = fresh_dir("contact-sliding");
  BOOST_TEST_REQUIRE((run(sliding(0.2, 0.05), out).status == scene::RunStatus::completed));
  const double tan_phi = std::tan(20.0 * std::numbers::pi / 180.0);
  int slid = 0;
  for (const auto& r : contact_rows(out)) {
    if (num(r, "time") == 0.0 || r.at("state") == "open") continue;
    BOOST_TEST(num(r, "tributary_length") > 0.0);
    if (num(r, "length") > 0.0) BOOST_TEST(num(r, "tributary_length") == num(r, "length"));
    if (r.at("state") != "sliding") continue;
    ++slid;
    BOOST_TEST(num(r, "shear_strength") == num(r, "normal_force") * tan_phi, boost::test_tools::tolerance(1e-9));
    BOOST_TEST(std::abs(num(r, "shear_force")) == num(r, "shear_strength"), boost::test_tools::tolerance(1e-9));
  }
  BOOST_TEST(slid > 0);
}

BOOST_AUTO_TEST_CASE(plot_draws_contacts_and_strength_at_each_frame_within_the_window) {
  const fs::path out = fresh_dir("contact-plot");
  BOOST_TEST_REQUIRE((run(sliding(0.2, 0.05), out).status == scene::RunStatus::completed));
  scene::PlotOptions po;
  po.out_dir = out.string();
  po.from = 0.05;
  po.to = 0.15;
  po.contact_column = "mobilised_friction";
  const auto pictures = scene::plot_run(po);
  // Frames at 0, 0.05, ..., 0.2 s: the window holds 0.05, 0.1 and 0.15 s (numbers 1-3).
  for (const char* f : {"blocks_000001.png", "blocks_000002.png", "blocks_000003.png", "contacts_000001.png",
                        "contacts_000003.png", "strength_000001.png", "strength_000003.png", "history.png"}) {
    BOOST_TEST(fs::file_size(out / "plots" / f) > 1000u, f);
    BOOST_TEST((std::find(pictures.begin(), pictures.end(), (out / "plots" / f).string()) != pictures.end()), f);
  }
  BOOST_TEST(!fs::exists(out / "plots" / "blocks_000000.png"));
  BOOST_TEST(!fs::exists(out / "plots" / "contacts_000004.png"));
  // The history's axis spans the window.
  BOOST_TEST(read_text((out / "plots" / "history.gp").string()).find("set xrange [0.050000000000000003:0.14999999999999999]") !=
             std::string::npos);
  // The contacts picture's data: a row per contact of the frame, coloured by |F_s| / strength.
  BOOST_TEST(read_text((out / "plots" / "contacts_000002.gp").string()).find("mobilised_friction [-]") != std::string::npos);

  scene::PlotOptions bad = po;
  bad.contact_column = "colour";
  BOOST_CHECK_THROW(scene::plot_run(bad), std::invalid_argument);
  bad = po;
  bad.from = 0.15;
  bad.to = 0.05;
  BOOST_CHECK_THROW(scene::plot_run(bad), std::invalid_argument);
  bad = po;
  bad.from = 5.0;
  bad.to = 6.0;
  BOOST_CHECK_THROW(scene::plot_run(bad), std::invalid_argument);
}

BOOST_AUTO_TEST_SUITE_END()
