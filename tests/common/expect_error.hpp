#pragma once
// The message of the cnclab::IoError (ConfigError) that f() throws, or "" and
// a test failure when it throws none; EXPECT_IO_ERROR checks the message.
#include <gtest/gtest.h>

#include <string>

#include "cnclab/core/error.hpp"

namespace cnclab::testing {

template <class E, class F>
std::string error_message(F&& f, const char* expected) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected " << expected;
  return "";
}

template <class F>
std::string io_error(F&& f) {
  return error_message<IoError>(f, "IoError");
}

template <class F>
std::string config_error(F&& f) {
  return error_message<ConfigError>(f, "ConfigError");
}

}  // namespace cnclab::testing

#define EXPECT_IO_ERROR(statement, text)                                          \
  do {                                                                            \
    const std::string message_ = ::cnclab::testing::io_error([&] { statement; }); \
    EXPECT_NE(message_.find(text), std::string::npos) << message_;                \
  } while (0)
