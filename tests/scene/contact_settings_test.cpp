// The contact layer's settings (contact/contact_settings_specs.hpp) and the scene's
// `analysis:` keys of the same names: each declared setting is the key of its name with
// the declaration's type, unit, range, default and meaning; the scene's Analysis starts
// from the declared default; a value given in a scene file reaches the contact layer's
// ContactSettings; a value outside the range is refused by the loader (file, line, key)
// and by the contact layer (ContactSystem's constructor, the setting named).
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <limits>

#include "declared_key_checks.hpp"
#include "test_support.hpp"
#include "rheodda/contact/contact_settings_specs.hpp"
#include "rheodda/contact/contact_system.hpp"
#include "rheodda/scene/build.hpp"
#include "rheodda/scene/keys.hpp"
#include "rheodda/scene/loader.hpp"

using namespace rheodda;
using namespace rheodda::test;

BOOST_AUTO_TEST_SUITE(contact_settings)

BOOST_AUTO_TEST_CASE(every_contact_setting_is_the_analysis_key_of_its_name_with_its_declaration) {
  BOOST_TEST_REQUIRE(contact::contact_setting_specs().size() == 12u);
  const scene::Analysis fresh{};
  for (const contact::ContactSettingSpec& s : contact::contact_setting_specs()) {
    BOOST_TEST_CONTEXT("setting " << s.name()) {
      const scene::KeySpec& k = scene::analysis_key(s.name());
      const bool flag = s.type == laws::SettingType::flag;
      BOOST_TEST((k.type == (flag                                   ? scene::KeyType::flag
                             : s.type == laws::SettingType::integer ? scene::KeyType::integer
                                                                    : scene::KeyType::number)));
      check_key_is_declaration(k, s.parameter, !flag);
      if (!flag) BOOST_TEST(scene::key_range_text(k) == s.range_text());
      // The default is ContactSettings{}'s, and the scene starts from it; the penalty's is a
      // mark the loader replaces (its key says by what).
      BOOST_TEST(*s.parameter.default_value == s.value(contact::ContactSettings{}));
      BOOST_TEST(scene::key_number(k.get(fresh)) == *s.parameter.default_value);
      if (s.default_meaning.empty()) BOOST_TEST(k.default_text == s.default_text());
      else BOOST_TEST(!s.parameter.admits(*s.parameter.default_value));
    }
  }
}

BOOST_AUTO_TEST_CASE(a_contact_setting_given_reaches_the_contact_layer_and_out_of_range_is_refused_by_both) {
  for (const contact::ContactSettingSpec& s : contact::contact_setting_specs()) {
    if (s.type == laws::SettingType::flag) continue;  // stick_keeps_force: its own test below
    BOOST_TEST_CONTEXT("setting " << s.name()) {
      const bool integer = s.type == laws::SettingType::integer;
      // Inside, away from the default: the value the scene gives is the contact layer's.
      const double lo = s.parameter.min, hi = s.parameter.max;
      double good = std::numeric_limits<double>::quiet_NaN();
      for (double c : {hi < 1e300 ? (lo + hi) / 2.0 : lo + 2.0, lo + 2.0, lo + 0.25})
        if (const double v = integer ? std::floor(c) : c; s.admits(v) && v != *s.parameter.default_value) {
          good = v;
          break;
        }
      BOOST_TEST_REQUIRE(std::isfinite(good));
      const std::string given = with("  dt: 0.01", "  dt: 0.01\n  " + s.name() + ": " + laws::setting_number_text(good));
      const scene::BuiltScene built = scene::build_scene(scene::parse_scene(given, "given.yaml"));
      BOOST_TEST(s.value(built.contact_settings) == good);
      // Below the lower bound, or on it where it is excluded: refused by the scene at its key.
      const double bad = s.parameter.min_exclusive ? lo : lo - 1.0;
      BOOST_TEST(!s.parameter.admits(bad));
      const std::string line = "  " + s.name() + ": " + laws::setting_number_text(bad);
      try {
        (void)scene::parse_scene(with("  dt: 0.01", "  dt: 0.01\n" + line), "range.yaml");
        BOOST_ERROR("the scene took " << line);
      } catch (const scene::SceneError& err) {
        BOOST_TEST(err.key() == "analysis." + s.name(), err.what());
        BOOST_TEST(err.line() == 5, err.what());
      }
      // And by the contact layer, the setting named (a penalty left at 0 by its own check).
      if (!s.default_meaning.empty()) continue;
      contact::ContactSettings cs = built.contact_settings;
      s.set(cs, bad);
      try {
        contact::ContactSystem system({}, cs);
        BOOST_ERROR("the contact layer took " << s.name() << " = " << bad);
      } catch (const std::invalid_argument& err) {
        BOOST_TEST(std::string(err.what()).find("contact setting " + s.name() + ": ") == 0u, err.what());
        BOOST_TEST(std::string(err.what()).find(s.range_text()) != std::string::npos, err.what());
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(stick_keeps_force_is_declared_with_the_scenes_rule_for_its_default) {
  // The declaration states the rule the loader applies (its host_default), the key's
  // default text is it, and each case of the rule reaches the contact layer.
  const contact::ContactSettingSpec& s = contact::contact_setting_spec("stick_keeps_force");
  BOOST_TEST((s.type == laws::SettingType::flag));
  BOOST_TEST(!s.host_default.empty());
  BOOST_TEST(scene::analysis_key("stick_keeps_force").default_text == s.host_default);
  BOOST_TEST(!s.admits(0.5));
  const auto built_with = [](const std::string& text) {
    return scene::build_scene(scene::parse_scene(text, "stick.yaml")).contact_settings.stick_keeps_force;
  };
  BOOST_TEST(!built_with(kBaseScene));                                                  // static
  BOOST_TEST(built_with(with("  dt: 0.01", "  dt: 0.01\n  type: dynamic")));            // dynamic
  BOOST_TEST(built_with(with("  dt: 0.01", "  dt: 0.01\n  stick_keeps_force: true")));  // given
  BOOST_TEST(!built_with(with("  dt: 0.01", "  dt: 0.01\n  type: dynamic\n  stick_keeps_force: false")));
  try {
    (void)scene::parse_scene(with("  dt: 0.01", "  dt: 0.01\n  stick_keeps_force: 2"), "flag.yaml");
    BOOST_ERROR("the scene took stick_keeps_force: 2");
  } catch (const scene::SceneError& err) {
    BOOST_TEST(err.key() == "analysis.stick_keeps_force", err.what());
    BOOST_TEST(err.line() == 5, err.what());
  }
}

BOOST_AUTO_TEST_SUITE_END()
