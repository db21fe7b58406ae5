// CTest labels the tests by what they need (tests/CMakeLists.txt): cpu, gl, xvfb, python. A
// test that reaches OpenGL (a headless context, or the CLI, which renders) while labelled cpu
// fails at once, so the labels cannot drift from what the tests do.
#pragma once

#include <cstdlib>
#include <stdexcept>
#include <string_view>

namespace cutaway::test {

inline void usesGl() {
  const char* label = std::getenv("CUTAWAY_TEST_LABEL");
  if (label && std::string_view(label) == "cpu")
    throw std::logic_error(
        "this test uses OpenGL but its suite is labelled cpu: add the suite to "
        "CUTAWAY_GL_SUITES in tests/CMakeLists.txt");
}

}  // namespace cutaway::test
