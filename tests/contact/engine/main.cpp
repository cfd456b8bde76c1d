#define BOOST_TEST_MODULE contact_engine
#include <boost/test/unit_test.hpp>
