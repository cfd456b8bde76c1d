// rheodda_units (units/): quantities split into number and unit, the declared
// dimensions spelled with a scene's labels, and conversions by UDUNITS-2 of each
// dimension a scene has, refused between different dimensions with both named.
#include <boost/test/unit_test.hpp>

#include <cmath>

#include "rheodda/units/units.hpp"

using namespace rheodda;

BOOST_AUTO_TEST_SUITE(units_module)

BOOST_AUTO_TEST_CASE(a_quantity_is_a_number_then_its_unit) {
  const auto q = units::split_quantity("  2600 kg/m^3 ");
  BOOST_TEST_REQUIRE(q.has_value());
  BOOST_TEST(q->value == 2600.0);
  BOOST_TEST(q->unit == "kg/m^3");
  BOOST_TEST(units::split_quantity("-9.81")->unit == "");
  BOOST_TEST(units::split_quantity("3.48e4 MPa*h/mm")->value == 3.48e4);
  BOOST_TEST(units::split_quantity("+1 d")->value == 1.0);
  BOOST_TEST(!units::split_quantity("1e5x").has_value());
  BOOST_TEST(!units::split_quantity("kg").has_value());
  BOOST_TEST(!units::split_quantity("").has_value());
}

BOOST_AUTO_TEST_CASE(a_dimension_is_spelled_with_the_scene_labels) {
  const units::Base mm{"mm", "N", "h"};
  BOOST_TEST(units::unit_of("stress*time/length", mm) == "N/mm^2*h/mm");
  BOOST_TEST(units::unit_of("mass/length³", mm) == "N*h^2/mm/mm^3");
  BOOST_TEST(units::unit_of("length/stress", mm) == "mm/(N/mm^2)");
  BOOST_TEST(units::unit_of("stress^2", mm) == "(N/mm^2)^2");
  BOOST_TEST(units::unit_of("stress/length", {"mm", "", "h", "MPa"}) == "MPa/mm");  // a fit's units
  BOOST_TEST(units::convert(1, "mm/(N/mm^2)", "m/Pa") == 1e-9, boost::test_tools::tolerance(1e-14));
  BOOST_TEST(units::unit_of("length/time²", {"m", "N", "d"}) == "m/d^2");
  BOOST_TEST(units::unit_of("–", mm) == "1");
  BOOST_TEST(units::unit_of("-", mm) == "1");
  BOOST_TEST(units::unit_of("force", {"m", "kN*m", "s"}) == "(kN*m)");
}

BOOST_AUTO_TEST_CASE(each_dimension_of_a_scene_converts) {
  const units::Base si{"m", "N", "s"}, mm{"mm", "N", "h"};
  auto to = [](double v, const std::string& from, const std::string& dim, const units::Base& b) {
    return units::convert(v, from, units::unit_of(dim, b));
  };
  BOOST_TEST(to(100, "mm", "length", si) == 0.1, boost::test_tools::tolerance(1e-15));
  BOOST_TEST(to(2, "kN", "force", si) == 2000.0);
  BOOST_TEST(to(100, "d", "time", si) == 8.64e6);
  BOOST_TEST(to(1, "ms", "time", si) == 1e-3, boost::test_tools::tolerance(1e-15));
  BOOST_TEST(to(20, "GPa", "stress", si) == 2e10);
  BOOST_TEST(to(20000, "MPa", "stress", mm) == 20000.0, boost::test_tools::tolerance(1e-15));
  // density 2700 kg/m^3 in N*h^2/mm^4 (the shear creep test's 2.08e-16)
  BOOST_TEST(to(2700, "kg/m^3", "mass/length³", mm) == 2.0833e-16, boost::test_tools::tolerance(1e-4));
  BOOST_TEST(to(2600, "kg/m^3", "mass/length³", si) == 2600.0, boost::test_tools::tolerance(1e-15));
  // viscosity per unit joint area: 3.48e4 MPa*h/mm in Pa*d/m
  BOOST_TEST(to(3.48e4, "MPa*h/mm", "stress*time/length", {"m", "N", "d"}) == 3.48e4 * 1e9 / 24.0,
             boost::test_tools::tolerance(1e-14));
  // joint stiffness per unit area, point spring stiffness
  BOOST_TEST(to(26.87, "MPa/mm", "stress/length", si) == 26.87e9, boost::test_tools::tolerance(1e-14));
  BOOST_TEST(to(5, "kN/mm", "force/length", si) == 5e6, boost::test_tools::tolerance(1e-14));
  // acceleration: the Earth's gravity in a scene whose time is days
  BOOST_TEST(to(9.81, "m/s^2", "length/time²", {"m", "N", "d"}) == 7.32312576e10, boost::test_tools::tolerance(1e-14));
  // angles: deg is the arc degree
  BOOST_TEST(units::convert(std::acos(-1.0), "rad", "deg") == 180.0, boost::test_tools::tolerance(1e-14));
  BOOST_TEST(units::convert(30, "deg", "deg") == 30.0);
  // dimensionless
  BOOST_TEST(units::convert(30, "%", "1") == 0.3, boost::test_tools::tolerance(1e-15));
}

BOOST_AUTO_TEST_CASE(a_bare_identity_keeps_the_number_exactly) {
  for (double v : {0.1, 7.32313e10, 2.08e-16, 34807.72}) BOOST_TEST(units::convert(v, "h", "h") == v);
}

BOOST_AUTO_TEST_CASE(a_wrong_dimension_is_refused_naming_both) {
  try {
    (void)units::convert(2600, "kg/m^3", "N/m^2");
    BOOST_ERROR("kg/m^3 converted to N/m^2");
  } catch (const units::UnitError& e) {
    const std::string m = e.what();
    BOOST_TEST_INFO(m);
    BOOST_TEST(m.find("kg/m^3 is force*time^2/length^4") != std::string::npos);
    BOOST_TEST(m.find("not force/length^2") != std::string::npos);
  }
  BOOST_CHECK_THROW((void)units::convert(1, "kgg", "kg"), units::UnitError);
  BOOST_TEST(!units::convertible("m", "s"));
  BOOST_TEST(units::convertible("kN/m", "N/mm"));
}

BOOST_AUTO_TEST_CASE(dimensions_are_named_in_force_length_and_time) {
  BOOST_TEST(units::dimension_words("MPa*h/mm") == "force*time/length^3");
  BOOST_TEST(units::dimension_words("m/s^2") == "length/time^2");
  BOOST_TEST(units::dimension_words("kN") == "force");
  BOOST_TEST(units::dimension_words("1") == "dimensionless");
  BOOST_TEST(units::dimension_words("deg") == "angle");
  BOOST_TEST(units::dimension_words("Hz") == "1/time");
}

BOOST_AUTO_TEST_SUITE_END()
