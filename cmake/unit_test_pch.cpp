// The one source of robodds_unit_test_pch (cmake/RoboddsHelpers.cmake): the target that compiles
// the unit tests' precompiled header, built with the unit tests' own flags. Its main is gtest_main's.
