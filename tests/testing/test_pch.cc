// The source of the target that builds the test programs' precompiled header
// (tests/CMakeLists.txt, motif_test_pch); the header itself is all it holds.
