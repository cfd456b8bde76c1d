// Boost.Test entry point of the apps/ suite (the rheodda command).
#define BOOST_TEST_MODULE rheodda apps
#include <boost/test/unit_test.hpp>
