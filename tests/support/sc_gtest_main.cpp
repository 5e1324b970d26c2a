// Test entry point. libsystemc provides main() and calls sc_main(), so every test binary starts
// here. Tests that elaborate SystemC modules run one per process (ctest runs each discovered test
// case on its own), because SystemC allows a single elaboration per process.
#include <gtest/gtest.h>

#include <systemc>

int sc_main(int argc, char* argv[]) {
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
