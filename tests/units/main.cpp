// Boost.Test entry point of the units suite (quantities with units, in scenes and on the command line).
#define BOOST_TEST_MODULE rheodda units
#include <boost/test/unit_test.hpp>
