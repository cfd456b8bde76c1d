#define BOOST_TEST_MODULE rheodda_laws
#include <boost/test/unit_test.hpp>
