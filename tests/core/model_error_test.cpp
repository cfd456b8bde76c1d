// Bad model input is refused with a ModelError whose key names the entry.
#include <boost/test/unit_test.hpp>

#include "rheodda/core/engine.hpp"
#include "test_support.hpp"

using namespace rheodda::core;
using rheodda::core::test::block;

namespace {

Model good() {
  Model m;
  m.blocks.push_back(block({{0, 0}, {1, 0}, {1, 1}, {0, 1}}));
  return m;
}

std::string key_of(const Model& m) {
  try {
    Engine e(m);
  } catch (const ModelError& err) {
    return err.key();
  }
  return "";
}

}  // namespace

BOOST_AUTO_TEST_SUITE(model_error)

BOOST_AUTO_TEST_CASE(bad_input_names_its_key) {
  BOOST_TEST(key_of(good()).empty());
  {
    Model m = good();
    m.blocks.push_back(block({{0, 0}, {1, 1}, {1, 0}, {0, 1}}));
    BOOST_TEST(key_of(m) == "blocks[1].vertices");
  }
  {
    Model m = good();
    m.blocks[0].edge_joint_set = {0, 1};
    BOOST_TEST(key_of(m) == "blocks[0].edge_joint_set");
  }
  {
    Model m = good();
    m.blocks[0].material = 3;
    BOOST_TEST(key_of(m) == "blocks[0].material");
  }
  {
    Model m = good();
    m.materials[0].poisson_ratio = 0.5;
    BOOST_TEST(key_of(m) == "materials[0].poisson_ratio");
  }
  {
    Model m = good();
    m.point_loads.push_back({.block = 0, .point = {0.5, 0.5}, .history = {{1.0, {0, 0}}, {1.0, {1, 0}}}});
    BOOST_TEST(key_of(m) == "point_loads[0].history");
  }
  {
    Model m = good();
    m.fixed_points.push_back({.block = 0, .point = {5.0, 0.5}});
    BOOST_TEST(key_of(m) == "fixed_points[0].point");
  }
  {
    Model m = good();
    m.measurement_points.push_back({.block = 2, .point = {0.5, 0.5}});
    BOOST_TEST(key_of(m) == "measurement_points[0].block");
  }
  {
    Model m = good();
    m.settings.dynamic_ratio = 0.0;
    m.blocks[0].initial_velocity = {1.0, 0.0};
    BOOST_TEST(key_of(m) == "blocks[0].initial_velocity");
  }
  {
    Model m = good();
    m.settings.max_displacement_ratio = 0.0;
    BOOST_TEST(key_of(m) == "settings.max_displacement_ratio");
  }
}

BOOST_AUTO_TEST_CASE(the_entry_and_the_message_are_data_apart_from_the_key) {
  // A reader maps an error to its own entry (a scene file's line) by entry(), not by
  // parsing key(); message() is the text after the key.
  Model m = good();
  m.blocks.push_back(block({{0, 0}, {1, 1}, {1, 0}, {0, 1}}));
  try {
    Engine e(m);
    BOOST_ERROR("a self-crossing block was accepted");
  } catch (const ModelError& err) {
    BOOST_TEST_REQUIRE(err.entry().has_value());
    BOOST_TEST(err.entry()->list == "blocks");
    BOOST_TEST(err.entry()->index == 1u);
    BOOST_TEST(err.entry()->part == "vertices");
    BOOST_TEST(err.message() == "not a simple polygon (edges cross, touch or have zero length)");
    BOOST_TEST(std::string(err.what()) == err.key() + ": " + err.message());
  }
  Model b = good();
  b.blocks.push_back(block({{2, 0}, {3, 0}, {3, 1}, {2, 1}}));
  Bolt bolt;
  bolt.block_a = 0;
  bolt.point_a = {0.5, 0.5};
  bolt.block_b = 1;
  bolt.point_b = {9.0, 0.5};  // off block 1
  bolt.axial_stiffness = 1e6;
  b.bolts.push_back(bolt);
  try {
    Engine e(b);
    BOOST_ERROR("a bolt end off its block was accepted");
  } catch (const ModelError& err) {
    BOOST_TEST_REQUIRE(err.entry().has_value());
    BOOST_TEST(err.key() == "bolts[0].b.point");
    BOOST_TEST(err.entry()->list == "bolts");
    BOOST_TEST(err.entry()->index == 0u);
    BOOST_TEST(err.entry()->part == "b.point");
  }
  try {
    Model s = good();
    s.settings.dt = -1.0;
    Engine e(s);
    BOOST_ERROR("a negative dt was accepted");
  } catch (const ModelError& err) {
    BOOST_TEST(!err.entry().has_value());  // a setting: no list entry
    BOOST_TEST(err.key() == "settings.dt");
  }
}

BOOST_AUTO_TEST_SUITE_END()
