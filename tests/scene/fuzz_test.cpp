// Fuzzing the inputs: deterministic, seeded mutations (deleted, duplicated and
// swapped lines, swapped characters, random numbers, truncations) of the shipped
// examples, of rock-mass scenes (rock_mass keys, explicit traces, holes), of study
// files with sweeps, of `rheodda fit --json` reports (broken covariance: not
// positive definite, null, wrong size) and of creep-data CSVs. Every mutant must
// either load or fail with a clean error naming the file and its line and column
// (a JSON report: its key path); nothing else may escape, nothing may crash or
// hang, and nothing accepted may hold a value that is not finite (CI also runs
// this under AddressSanitizer and UBSan: scripts/test.sh).
#define BOOST_TEST_MODULE rheodda scene fuzz
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <random>
#include <regex>
#include <sstream>

#include "test_support.hpp"
#include "rheodda/fit/creep_data.hpp"
#include "rheodda/forecast/forecast.hpp"
#include "rheodda/scene/describe.hpp"
#include "rheodda/scene/loader.hpp"
#include "rheodda/study/study.hpp"

using namespace rheodda;
using namespace rheodda::test;

namespace {

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream in(text);
  std::string l;
  while (std::getline(in, l)) out.push_back(l);
  return out;
}

std::string join(const std::vector<std::string>& lines) {
  std::string s;
  for (const auto& l : lines) s += l + '\n';
  return s;
}

const char* kNumbers[] = {"0", "-1", "1e308", "-1e308", "1e-308", "nan", ".nan", ".inf", "-.inf", "3.5", "90",
                          "0.5", "-0", "1e9", "2147483648", "99999999999", "1x", "[]", "{}", "~", "true", "\"7\"",
                          "5e-324", "1e-310", "2.2e-308", "1e200"};

/// A mutant of `text`; a number is replaced by one of kNumbers or, one time in three, by
/// a random whole number of magnitude below `whole` (a rock mass keeps it small: a
/// region of kilometres with metre spacings is a legitimate cut of minutes, docs/guide/rockmass.md).
std::string mutate(const std::string& text, std::mt19937_64& rng, long long whole = 1000000) {
  auto pick = [&rng](std::size_t n) { return static_cast<std::size_t>(rng() % std::max<std::size_t>(n, 1)); };
  std::vector<std::string> lines = lines_of(text);
  const int kinds = 1 + static_cast<int>(pick(3));
  for (int k = 0; k < kinds && !lines.empty(); ++k) {
    switch (pick(7)) {
      case 0:  // delete a line
        lines.erase(lines.begin() + static_cast<long>(pick(lines.size())));
        break;
      case 1: {  // duplicate a line
        const std::size_t i = pick(lines.size());
        lines.insert(lines.begin() + static_cast<long>(i), lines[i]);
        break;
      }
      case 2:  // swap two lines
        std::swap(lines[pick(lines.size())], lines[pick(lines.size())]);
        break;
      case 3: {  // swap two neighbouring characters
        std::string& l = lines[pick(lines.size())];
        if (l.size() > 1) {
          const std::size_t i = pick(l.size() - 1);
          std::swap(l[i], l[i + 1]);
        }
        break;
      }
      case 4: {  // replace a number by another value
        std::string& l = lines[pick(lines.size())];
        static const std::regex number("-?[0-9]+(\\.[0-9]*)?(e[-+]?[0-9]+)?");
        std::vector<std::pair<std::size_t, std::size_t>> spans;
        for (auto it = std::sregex_iterator(l.begin(), l.end(), number); it != std::sregex_iterator(); ++it)
          spans.emplace_back(static_cast<std::size_t>(it->position()), static_cast<std::size_t>(it->length()));
        if (!spans.empty()) {
          const auto [at, len] = spans[pick(spans.size())];
          const std::string v = pick(3) == 0 ? std::to_string(static_cast<long long>(rng() % (2 * whole)) - whole)
                                             : kNumbers[pick(std::size(kNumbers))];
          l.replace(at, len, v);
        }
        break;
      }
      case 5: {  // insert a stray character
        std::string& l = lines[pick(lines.size())];
        static const char stray[] = ":{}[],-#&*!|>'\"%@` \t";
        l.insert(l.begin() + static_cast<long>(pick(l.size() + 1)), stray[pick(sizeof stray - 1)]);
        break;
      }
      case 6: {  // truncate the file
        std::string all = join(lines);
        all.resize(pick(all.size() + 1));
        lines = lines_of(all);
        break;
      }
    }
  }
  return join(lines);
}

}  // namespace

BOOST_AUTO_TEST_CASE(mutated_examples_load_or_fail_with_a_located_scene_error) {
  constexpr int kMutantsPerExample = 1200;
  int loaded = 0, refused = 0;
  for (const char* name :
       {"shear-creep-test.yaml", "sliding-block.yaml", "goodman-toppling.yaml", "excavation-stages.yaml"}) {
    const std::string original = read_text(source_path(std::string("examples/") + name));
    std::mt19937_64 rng(0x5eedULL + std::hash<std::string>{}(name) % 1000);
    for (int i = 0; i < kMutantsPerExample; ++i) {
      const std::string text = mutate(original, rng);
      try {
        const auto s = scene::parse_scene(text, name);
        (void)scene::describe_scene(s);
        ++loaded;
      } catch (const scene::SceneError& e) {
        ++refused;
        BOOST_TEST(e.file() == name);
        BOOST_TEST(!e.message().empty());
        BOOST_TEST(e.line() >= 0);
      } catch (const std::exception& e) {
        BOOST_ERROR(name << " mutant " << i << ": escaped " << typeid(e).name() << ": " << e.what() << "\n" << text);
      }
    }
  }
  BOOST_TEST_MESSAGE("fuzz: " << loaded << " mutants loaded, " << refused << " refused cleanly");
  BOOST_TEST(refused > 0);
  BOOST_TEST(loaded > 0);
}

// The classes a file adds to a text: bytes of other encodings, NUL bytes, tabs in
// the indentation, byte-order marks; and paths that are not scene files. Loaded
// through load_scene (the command's path: read_scene_text, then the parser).
BOOST_AUTO_TEST_CASE(scene_files_in_other_encodings_with_tabs_or_from_devices_fail_with_a_scene_error) {
  const auto dir = fresh_dir("fuzz-files");
  int refused = 0, loaded = 0;
  auto load = [&](const std::string& path, const std::string& what) {
    try {
      (void)scene::describe_scene(scene::load_scene(path));
      ++loaded;
    } catch (const scene::SceneError& e) {
      ++refused;
      BOOST_TEST(!e.message().empty(), what);
      BOOST_TEST(std::string(e.what()).find(":0:0") == std::string::npos, what << ": " << e.what());
    } catch (const std::exception& e) {
      BOOST_ERROR(what << ": escaped " << typeid(e).name() << ": " << e.what());
    }
  };
  for (const char* device : {"/dev/zero", "/dev/null", "/dev/urandom", "/", "/proc/self/fd/0"}) load(device, device);
  const std::string original = read_text(source_path("examples/sliding-block.yaml"));
  std::mt19937_64 rng(0xE7C0DEULL);
  const char* inserts[] = {"\xE9", "\xFF\xFE", "\xC3", "\xED\xA0\x80", "\xF8\x88\x80\x80\x80"};
  for (int i = 0; i < 300; ++i) {
    std::string text = mutate(original, rng);
    const int kind = static_cast<int>(rng() % 4);
    if (kind == 0) {  // a foreign byte sequence somewhere
      const std::string ins = i % 7 == 5 ? std::string("\0", 1) : std::string(inserts[rng() % 5]);
      text.insert(rng() % (text.size() + 1), ins);
    } else if (kind == 1) {  // a line indented by a tab
      auto lines = lines_of(text);
      if (!lines.empty()) lines[rng() % lines.size()].insert(0, "\t");
      text = join(lines);
    } else if (kind == 2) {  // UTF-16 (little endian, with its mark)
      std::string w = "\xFF\xFE";
      for (char c : text) {
        w.push_back(c);
        w.push_back('\0');
      }
      text = w;
    } else {  // a UTF-8 byte-order mark
      text.insert(0, "\xEF\xBB\xBF");
    }
    std::string name = "m";  // (not "m" + ...: GCC 12 warns wrongly of -Wrestrict there)
    name += std::to_string(i);
    name += ".yaml";
    const auto path = dir / name;
    std::ofstream(path, std::ios::binary) << text;
    load(path.string(), "mutant " + std::to_string(i));
  }
  BOOST_TEST_MESSAGE("fuzz files: " << loaded << " loaded, " << refused << " refused cleanly");
  BOOST_TEST(refused > 0);
  BOOST_TEST(loaded > 0);
}

namespace {

/// Every coordinate and number a loaded scene holds is finite.
bool finite_scene(const scene::SceneDescription& s) {
  for (const auto& b : s.blocks)
    for (const auto& p : b.polygon)
      if (!std::isfinite(p[0]) || !std::isfinite(p[1])) return false;
  return std::isfinite(s.analysis.duration) && std::isfinite(s.analysis.dt);
}

/// A scene error that says where: the file, a line and a column (a whole-file fault
/// may have neither, and then says so without a bogus ":0:0").
void expect_located(const scene::SceneError& e, const std::string& file, const std::string& what) {
  BOOST_TEST(e.file() == file, what);
  BOOST_TEST(!e.message().empty(), what);
  if (e.line() > 0) BOOST_TEST(e.column() > 0, what << ": " << e.what());
  else BOOST_TEST(std::string(e.what()).find(":0:0") == std::string::npos, what << ": " << e.what());
}

// A rock mass whose lines are nearly all rock_mass keys: a region with a hole, two
// generated sets (one persistent, one with traces and gaps, normal spacing, dip
// spread) and explicit traces, sliver merging.
const char* kRockMass =
    "units: {length: m, force: N, time: d}\n"
    "analysis: {type: static, duration: 1, dt: 0.5, gravity: [0, -7.32313e10]}\n"
    "materials: {rock: {density: 3.41384e-7, young_modulus: 1.0e10, poisson_ratio: 0.25}}\n"
    "joint_sets: {bedding: {friction_angle: 30}, joints: {friction_angle: 35}, frame: {friction_angle: 40}}\n"
    "blocks:\n"
    "  - {name: base, rectangle: {x: -1, y: -1, width: 22, height: 1}, joint_set: frame, fixed: true}\n"
    "rock_mass:\n"
    "  name: rm\n"
    "  material: rock\n"
    "  region: [[0, 0], [20, 0], [20, 8], [12, 12], [0, 12]]\n"
    "  holes: [[[8, 4], [11, 4], [11, 6], [8, 6]]]\n"
    "  boundary_joint_set: frame\n"
    "  seed: 5\n"
    "  sliver_area: 0.05\n"
    "  joint_sets:\n"
    "    - {joint_set: bedding, dip: 12, dip_direction: left, spacing: 1.5, origin: [0, 0.5]}\n"
    "    - {joint_set: joints, dip: 80, spacing: 2, spacing_distribution: normal, spacing_deviation: 0.3,\n"
    "       trace_length: 5, gap: 1, dip_spread: 4}\n"
    "  traces:\n"
    "    - {joint_set: joints, from: [-1, 9], to: [21, 2]}\n"
    "    - {joint_set: bedding, from: [3, -1], to: [3, 13]}\n";

/// A study file's text as `rheodda study` reads it: parsed, and a study of at most 12
/// cases built into case scenes and checked (prepare_cases).
void st_load_and_prepare(const std::string& text, const std::string& path) {
  const study::StudyDescription st = study::parse_study(text, path);
  if (st.cases.size() <= 12) (void)study::prepare_cases(st);
}

}  // namespace

BOOST_AUTO_TEST_CASE(mutated_rock_masses_load_or_fail_with_a_located_scene_error) {
  // The rock_mass keys, generated and explicit traces and holes: each mutant is cut
  // (or refused) within the loader's limits on traces and on the cut's estimate.
  int loaded = 0, refused = 0;
  const std::vector<std::pair<std::string, std::string>> sources{
      {"rock.yaml", kRockMass}, {"tunnel.yaml", read_text(source_path("examples/rockmass/tunnel.yaml"))}};
  for (const auto& [name, original] : sources) {
    std::mt19937_64 rng(0x70cULL + std::hash<std::string>{}(name) % 1000);
    for (int i = 0; i < 150; ++i) {
      const std::string text = mutate(original, rng, 100);
      try {
        const auto s = scene::parse_scene(text, name);
        BOOST_TEST(finite_scene(s), name << " mutant " << i);
        (void)scene::describe_scene(s);
        ++loaded;
      } catch (const scene::SceneError& e) {
        ++refused;
        expect_located(e, name, name + " mutant " + std::to_string(i));
      } catch (const std::exception& e) {
        BOOST_ERROR(name << " mutant " << i << ": escaped " << typeid(e).name() << ": " << e.what() << "\n" << text);
      }
    }
  }
  BOOST_TEST_MESSAGE("rock mass fuzz: " << loaded << " loaded, " << refused << " refused cleanly");
  BOOST_TEST(refused > 0);
  BOOST_TEST(loaded > 0);
}

BOOST_AUTO_TEST_CASE(mutated_study_files_with_sweeps_load_or_fail_with_a_located_error) {
  // The shipped studies (sweeps: grid, log ranges, Latin hypercube; listed cases), each
  // mutant parsed; a study of at most 12 cases also has its case scenes built and checked.
  int loaded = 0, refused = 0;
  for (const char* name : {"sliding-grid.yaml", "toppling-laws.yaml", "forecast-slope.yaml", "toppling-phi.yaml"}) {
    const std::string path = source_path(std::string("examples/studies/") + name);
    const std::string original = read_text(path);
    std::mt19937_64 rng(0x57ULL + std::hash<std::string>{}(name) % 1000);
    for (int i = 0; i < 120; ++i) {
      const std::string text = mutate(original, rng);
      try {
        st_load_and_prepare(text, path);
        ++loaded;
      } catch (const scene::SceneError& e) {
        ++refused;
        // A fault in a case scene is reported in the study file (or the base scene's own).
        BOOST_TEST(!e.file().empty(), name << " mutant " << i);
        if (e.line() > 0) BOOST_TEST(e.column() > 0, e.what());
      } catch (const std::exception& e) {
        BOOST_ERROR(name << " mutant " << i << ": escaped " << typeid(e).name() << ": " << e.what() << "\n" << text);
      }
    }
  }
  BOOST_TEST_MESSAGE("study fuzz: " << loaded << " loaded, " << refused << " refused cleanly");
  BOOST_TEST(refused > 0);
  BOOST_TEST(loaded > 0);
}

BOOST_AUTO_TEST_CASE(fit_reports_with_broken_covariances_are_refused_with_the_key_or_sampled_finite) {
  // A Burgers report as `rheodda fit --json` writes it, then: correlations out of
  // [-1, 1], asymmetric, not positive semidefinite, null where both parameters are
  // identifiable, rows of the wrong size, standard errors null, negative or huge,
  // values that are text, keys deleted, the JSON cut short. Each is refused naming the
  // file and the key (JSON has no line for a value; a syntax error says its line and
  // column), or its draws are finite and within the law's ranges.
  const auto dir = fresh_dir("fuzz-fit");
  const std::string good =
      R"({"units": {"stress": "MPa", "length": "mm", "time": "h"}, "best": "burgers", "fits": [{"law": "burgers",)"
      R"( "parameters": [{"name": "E1", "value": 26.8, "std_error": 0.03, "identifiable": true},)"
      R"( {"name": "E2", "value": 192.0, "std_error": 1.3, "identifiable": true},)"
      R"( {"name": "eta1", "value": 34800.0, "std_error": 130.0, "identifiable": true},)"
      R"( {"name": "eta2", "value": 2130.0, "std_error": 36.0, "identifiable": true}],)"
      R"( "correlation": [[1.0, -0.92, -0.21, -0.88], [-0.92, 1.0, -0.16, 0.73], [-0.21, -0.16, 1.0, 0.37],)"
      R"( [-0.88, 0.73, 0.37, 1.0]]}]})";
  const char* values[] = {"2.0", "-1.5", "1.0000001", "null", "\"x\"", "[]", "{}", "1e308", "-1e308", "0", "-0.999999",
                          "0.999999", "1e-300", "true", "-1", "0.5"};
  std::mt19937_64 rng(0xf17ULL);
  static const std::regex number("-?[0-9]+(\\.[0-9]*)?(e[-+]?[0-9]+)?|null");
  int sampled = 0, refused = 0;
  for (int i = 0; i < 400; ++i) {
    std::string text = good;
    const int kinds = 1 + static_cast<int>(rng() % 3);
    for (int k = 0; k < kinds; ++k) {
      std::vector<std::pair<std::size_t, std::size_t>> spans;
      for (auto it = std::sregex_iterator(text.begin(), text.end(), number); it != std::sregex_iterator(); ++it)
        spans.emplace_back(static_cast<std::size_t>(it->position()), static_cast<std::size_t>(it->length()));
      switch (rng() % 5) {
        case 0:
        case 1:
        case 2: {  // a number (a correlation, a value, a standard error) replaced
          if (spans.empty()) break;
          const auto [at, len] = spans[rng() % spans.size()];
          text.replace(at, len, values[rng() % std::size(values)]);
          break;
        }
        case 3: {  // a row of the correlation shortened, or one more
          const std::size_t row = text.find("[-0.92, 1.0");
          if (row != std::string::npos) text.replace(row, 11, rng() % 2 ? "[1.0" : "[-0.92, 1.0, 0.1");
          break;
        }
        case 4:  // cut short
          text.resize(rng() % (text.size() + 1));
          break;
      }
    }
    const auto path = (dir / ("fit" + std::to_string(i) + ".json")).string();
    std::ofstream(path) << text;
    try {
      const auto fit = forecast::read_fit_report(path, "");
      const auto s = forecast::draw_samples(fit, 20, 7, {});
      for (const auto& v : s.accepted)
        for (const auto& [k, x] : v) BOOST_TEST(std::isfinite(x), "mutant " << i << ": " << k);
      ++sampled;
    } catch (const scene::SceneError& e) {
      ++refused;
      BOOST_TEST(e.file() == path);
      BOOST_TEST((!e.key().empty() || e.message().find("line") != std::string::npos), e.what() << "\n" << text);
    } catch (const std::runtime_error& e) {
      // The one run-time refusal: draws the law's ranges reject, 100 times over.
      ++refused;
      BOOST_TEST(std::string(e.what()).find("covariance is too wide") != std::string::npos, e.what());
    } catch (const std::exception& e) {
      BOOST_ERROR("mutant " << i << ": escaped " << typeid(e).name() << ": " << e.what() << "\n" << text);
    }
  }
  BOOST_TEST_MESSAGE("fit report fuzz: " << sampled << " sampled, " << refused << " refused cleanly");
  BOOST_TEST(refused > 0);
  BOOST_TEST(sampled > 0);
}

BOOST_AUTO_TEST_CASE(mutated_creep_data_csvs_load_finite_or_fail_naming_file_line_and_column) {
  int loaded = 0, refused = 0;
  for (const char* name : {"table1-row1.csv", "steps-unloading.csv"}) {
    const std::string original = read_text(source_path(std::string("examples/creep-data/") + name));
    const bool staged = std::string(name) == "steps-unloading.csv";
    std::mt19937_64 rng(0xc5fULL + std::hash<std::string>{}(name) % 1000);
    for (int i = 0; i < 300; ++i) {
      std::istringstream in(mutate(original, rng));
      fit::CsvOptions o;
      if (staged) o.stress_column = "tau";
      else o.stress = laws::StagedHistory({{0.0, 0.232}});
      try {
        const auto d = fit::parse_creep_csv(in, name, o);
        for (std::size_t k = 0; k < d.t.size(); ++k)
          BOOST_TEST((std::isfinite(d.t[k]) && std::isfinite(d.displacement[k])), name << " mutant " << i);
        ++loaded;
      } catch (const fit::DataError& e) {
        ++refused;
        BOOST_TEST(e.file() == name);
        // Every refusal but "no data rows" / a missing column of the header names its line.
        BOOST_TEST(std::string(e.what()).find(name) != std::string::npos, e.what());
      } catch (const std::exception& e) {
        BOOST_ERROR(name << " mutant " << i << ": escaped " << typeid(e).name() << ": " << e.what());
      }
    }
  }
  BOOST_TEST_MESSAGE("creep data fuzz: " << loaded << " loaded, " << refused << " refused cleanly");
  BOOST_TEST(refused > 0);
  BOOST_TEST(loaded > 0);
}
