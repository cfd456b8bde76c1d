#define BOOST_TEST_MODULE rheodda_core
#include <boost/test/unit_test.hpp>
