#define BOOST_TEST_MODULE rheodda_accuracy
#include <boost/test/unit_test.hpp>
