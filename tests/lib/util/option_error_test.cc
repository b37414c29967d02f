#include "lib/util/option_error.h"

#include <gtest/gtest.h>

namespace lutex {
namespace {

TEST(OptionError, WhatNamesTheFieldsAndRenderUsesTheCallersNames) {
  const OptionError error("{targets_workspace} needs {targets}; see {calibration.grid.nx}");
  EXPECT_STREQ(error.what(), "targets_workspace needs targets; see calibration.grid.nx");
  const std::string rendered = error.Render([](const std::string& field) { return "<" + field + ">"; });
  EXPECT_EQ(rendered, "<targets_workspace> needs <targets>; see <calibration.grid.nx>");
}

TEST(OptionError, TextWithoutFieldsOrWithAnUnclosedBraceIsKept) {
  EXPECT_STREQ(OptionError("plain text").what(), "plain text");
  EXPECT_STREQ(OptionError("{a} then {unclosed").what(), "a then {unclosed");
}

}  // namespace
}  // namespace lutex
