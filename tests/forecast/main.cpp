// Boost.Test entry point of the forecast suite (`rheodda forecast`).
#define BOOST_TEST_MODULE rheodda forecast
#include <boost/test/unit_test.hpp>
