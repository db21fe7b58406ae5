// Expecting a cutaway::Error that names the right things.
#pragma once

#include <gtest/gtest.h>

#include <initializer_list>
#include <string>

#include "cutaway/core/error.hpp"

namespace cutaway::test {

// Runs `f`, expects a cutaway::Error whose message contains every one of `parts`.
template <typename F>
void expectError(F&& f, std::initializer_list<std::string> parts) {
  try {
    f();
    ADD_FAILURE() << "no error; expected one mentioning " << *parts.begin();
  } catch (const Error& e) {
    for (const std::string& p : parts)
      EXPECT_NE(std::string(e.what()).find(p), std::string::npos)
          << "\"" << e.what() << "\" does not mention \"" << p << "\"";
  }
}

}  // namespace cutaway::test
