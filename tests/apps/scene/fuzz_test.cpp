// Fuzzing the scene loader: deterministic, seeded mutations of the shipped
// examples (deleted, duplicated and swapped lines, swapped characters, random
// numbers, truncations). Every mutant must either load or fail with a clean
// SceneError naming the file and a line; nothing else may escape, nothing may
// crash (CI also runs this under AddressSanitizer: scripts/test.sh).
#define BOOST_TEST_MODULE rheodda scene fuzz
#include <boost/test/unit_test.hpp>

#include <random>
#include <regex>

#include "../test_support.hpp"
#include "rheodda/scene/describe.hpp"
#include "rheodda/scene/loader.hpp"

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

std::string mutate(const std::string& text, std::mt19937_64& rng) {
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
          const std::string v = pick(3) == 0 ? std::to_string(static_cast<long long>(rng() % 2000000) - 1000000)
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
  for (const char* name : {"shear-creep-test.yaml", "sliding-block.yaml", "goodman-toppling.yaml"}) {
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
