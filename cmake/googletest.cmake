# GoogleTest 1.12 (Debian: libgtest-dev). Provides GTest::gtest and GTest::gtest_main.
find_package(GTest REQUIRED)
include(GoogleTest)
