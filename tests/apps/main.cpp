// Boost.Test entry point of the apps/ suite (scene files and the rheodda command).
#define BOOST_TEST_MODULE rheodda apps
#include <boost/test/unit_test.hpp>
