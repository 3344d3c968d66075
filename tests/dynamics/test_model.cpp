#include <gtest/gtest.h>
#include "dynamics/model.hpp"
TEST(Dummy, X) {}
