// One headless OpenGL context shared by all GPU tests of the process.
#pragma once

#include <gtest/gtest.h>

#include <memory>

#include "cutaway/gl/context.hpp"

namespace cutaway::test {

inline gl::HeadlessContext& glContext() {
  static std::unique_ptr<gl::HeadlessContext> context = gl::HeadlessContext::create();
  return *context;
}

}  // namespace cutaway::test
