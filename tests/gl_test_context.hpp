// One headless OpenGL context shared by all GPU tests of the process.
#pragma once

#include <gtest/gtest.h>

#include <memory>

#include "cutaway/gl/context.hpp"
#include "test_label.hpp"

namespace cutaway::test {

inline gl::HeadlessContext& glContext() {
  usesGl();
  static std::unique_ptr<gl::HeadlessContext> context = gl::HeadlessContext::create();
  return *context;
}

}  // namespace cutaway::test
