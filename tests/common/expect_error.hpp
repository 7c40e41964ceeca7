#pragma once
// The message of the cnclab::IoError that f() throws, or "" and a test
// failure when it throws none; EXPECT_IO_ERROR checks the message.
#include <gtest/gtest.h>

#include <string>
#include <utility>

#include "cnclab/core/error.hpp"

namespace cnclab::testing {

// The message of the E that f() throws, or "" and a test failure when it
// throws none.
template <class E, class F>
std::string thrown_message(F&& f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected an exception of the named cnclab::Error type";
  return "";
}

template <class F>
std::string io_error(F&& f) {
  return thrown_message<IoError>(std::forward<F>(f));
}

}  // namespace cnclab::testing

#define EXPECT_IO_ERROR(statement, text)                                          \
  do {                                                                            \
    const std::string message_ = ::cnclab::testing::io_error([&] { statement; }); \
    EXPECT_NE(message_.find(text), std::string::npos) << message_;                \
  } while (0)
