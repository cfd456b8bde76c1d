#define BOOST_TEST_MODULE rheodda fit tests
#include <boost/test/unit_test.hpp>
