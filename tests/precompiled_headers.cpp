// Compiled only so that the target nbar_test_headers makes the precompiled headers the test
// programs share (tests/CMakeLists.txt).
