// Fuzzing the checkpoint's state file (scene/src/checkpoint_state.hpp):
// seeded mutations of a real state's payload (bytes overwritten, cut, added),
// each given a fresh header with a matching checksum so that the decoder and
// Engine/ContactSystem::restore see the damage rather than the checksum.
// Every mutant must be refused with std::invalid_argument naming the file, or
// decode into a state that the engine and the contacts take or refuse
// (std::invalid_argument); nothing else may escape, nothing may crash (CI
// runs this under AddressSanitizer: scripts/test.sh).
#include <boost/test/unit_test.hpp>

#include <nlohmann/json.hpp>
#include <fmt/format.h>

#include <random>

#include "test_support.hpp"
#include "checkpoint_state.hpp"
#include "rheodda/core/contact_adapter.hpp"
#include "rheodda/scene/build.hpp"
#include "rheodda/scene/loader.hpp"
#include "rheodda/scene/output.hpp"
#include "rheodda/scene/run.hpp"

using namespace rheodda;
using namespace rheodda::test;
namespace fs = std::filesystem;

BOOST_AUTO_TEST_CASE(mutated_state_files_are_refused_or_taken_never_crash) {
  // A creeping slope stopped within its settling stage (0.01 d in steps of
  // 5e-5 d): blocks, contacts with Burgers histories, the stage in progress.
  auto s = scene::load_scene(source_path("examples/goodman-toppling-creep.yaml"));
  s.analysis.duration = 0.05;
  s.analysis.output_interval = 0.01;
  const fs::path out = fresh_dir("state-fuzz");
  scene::RunOptions o;
  o.out_dir = out.string();
  o.stop_after_step = 100;
  BOOST_TEST_REQUIRE((scene::run_scene(s, read_text(s.file), o).status == scene::RunStatus::interrupted));
  const auto ck = nlohmann::json::parse(read_text((out / "checkpoint.json").string()));
  const std::string scene_hash = ck.at("scene_hash").get<std::string>();
  const std::string bytes = read_text((out / ck.at("state").at("file").get<std::string>()).string());
  const std::size_t eol = bytes.find('\n');
  const std::string payload = bytes.substr(eol + 1);
  auto header = nlohmann::ordered_json::parse(bytes.substr(0, eol));
  BOOST_TEST_REQUIRE(!scene::decode_state(bytes, "state", scene_hash).contacts.contacts.empty());

  const scene::BuiltScene built = scene::build_scene(s);
  std::mt19937_64 rng(20240940);
  auto pick = [&rng](std::size_t n) { return static_cast<std::size_t>(rng() % std::max<std::size_t>(n, 1)); };
  int refused = 0, taken = 0;
  for (int k = 0; k < 400; ++k) {
    std::string p = payload;
    switch (pick(4)) {
      case 0:  // a few bytes overwritten
      case 1:
        for (std::size_t n = 1 + pick(4); n > 0; --n) p[pick(p.size())] = static_cast<char>(rng());
        break;
      case 2:  // cut
        p.resize(pick(p.size()));
        break;
      case 3:  // bytes put in
        p.insert(pick(p.size()), std::string(1 + pick(16), static_cast<char>(rng())));
        break;
    }
    header["payload_bytes"] = p.size();
    header["payload_fnv1a"] = fmt::format("{:016x}", scene::fnv1a(p.data(), p.size()));
    const std::string mutant = header.dump() + "\n" + p;
    try {
      const scene::SavedRun run = scene::decode_state(mutant, "mutant.state", scene_hash);
      contact::ContactSystem contacts(built.joint_sets, built.contact_settings);
      core::ContactAdapter adapter(contacts);
      core::Engine engine(built.model, adapter);
      engine.restore(run.engine);
      contacts.restore(run.contacts);
      ++taken;
    } catch (const std::invalid_argument& e) {
      const std::string m = e.what();
      BOOST_TEST((m.find("mutant.state") != std::string::npos || m.find("restore") != std::string::npos ||
                  m.find("state") != std::string::npos),
                 m);
      ++refused;
    }
  }
  BOOST_TEST_MESSAGE(refused << " refused, " << taken << " taken");
  BOOST_TEST(refused > 100);
  fs::remove_all(out);
}
