// The readers' key handles (scene/src/key_names.hpp): a handle is made only for a word
// its map's registry entry lists (else it does not compile), so each registry entry
// naming a key its map declares (keys*.cpp, declared_key_names) is what makes every
// handle name a declared key. A registry typo, or a key renamed in its declaration and
// not in the registry, fails here.
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <set>
#include <string>
#include <vector>

#include "key_names.hpp"
#include "rheodda/scene/keys.hpp"

using namespace rheodda::scene;

namespace {

/// The words of a registry entry, as written (split at each space).
std::vector<std::string> words(std::string_view text) {
  std::vector<std::string> out;
  for (std::size_t at = 0; at <= text.size();) {
    const std::size_t end = std::min(text.find(' ', at), text.size());
    out.emplace_back(text.substr(at, end - at));
    at = end + 1;
  }
  return out;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(key_names)

BOOST_AUTO_TEST_CASE(every_registered_key_is_declared_in_its_map) {
  std::set<std::string> maps;
  for (const detail::LookedUpKeys& e : detail::key_registry) {
    const std::string map(e.map);
    BOOST_TEST(maps.insert(map).second, map << " has two registry entries");
    const std::vector<std::string> declared = declared_key_names(map);
    BOOST_TEST(!declared.empty(), map << " is not a declared map");
    std::set<std::string> seen;
    for (const std::string& w : words(e.words)) {
      BOOST_TEST((std::find(declared.begin(), declared.end(), w) != declared.end()),
                 map << ": '" << w << "' is not a declared key of the map");
      BOOST_TEST(seen.insert(w).second, map << ": '" << w << "' is listed twice");
    }
  }
}

BOOST_AUTO_TEST_CASE(a_handle_names_its_map_and_word) {
  // The views point into the registry entry of its map.
  BOOST_TEST(detail::key::settle::until.map() == "analysis.settle");
  BOOST_TEST(detail::key::settle::until.word() == "until");
  BOOST_TEST(detail::key::analysis::settle.map() == "analysis");
  BOOST_TEST(detail::key::analysis::settle.word() == "settle");
  BOOST_TEST(detail::point_on_block<detail::key::bolt_to>.block.map() == "bolts.to");
  BOOST_TEST(detail::force_or_history<detail::key::stage_load>.history.map() == "stages.add_loads");
}

BOOST_AUTO_TEST_SUITE_END()
