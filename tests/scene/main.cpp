// Boost.Test entry point of the scene suite (scene files, the model they build, the run).
#define BOOST_TEST_MODULE rheodda scene
#include <boost/test/unit_test.hpp>
