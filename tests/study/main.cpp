// Boost.Test entry point of the study suite (`rheodda study`).
#define BOOST_TEST_MODULE rheodda study
#include <boost/test/unit_test.hpp>
