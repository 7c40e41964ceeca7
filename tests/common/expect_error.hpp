#pragma once
// The message of the cnclab::IoError that f() throws, or "" and a test
// failure when it throws none; EXPECT_IO_ERROR checks the message.
#include <gtest/gtest.h>

#include <string>

#include "cnclab/core/error.hpp"

namespace cnclab::testing {

template <class F>
std::string io_error(F&& f) {
  try {
    f();
  } catch (const IoError& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected IoError";
  return "";
}

// The message of the exception of type E that f() throws, or "no error"
// when it throws none (for tests comparing messages of rejected options).
template <class E, class F>
std::string error_message(F&& f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace cnclab::testing

#define EXPECT_IO_ERROR(statement, text)                                          \
  do {                                                                            \
    const std::string message_ = ::cnclab::testing::io_error([&] { statement; }); \
    EXPECT_NE(message_.find(text), std::string::npos) << message_;                \
  } while (0)
