#pragma once
// The message of the lb::InputError a call throws, for tests of bad input.
#include <string>

#include "error.h"

namespace lbtest {

// The message of the InputError thrown by f, or "" if f returns (other exceptions fail the test).
template <class F>
std::string inputErrorOf(F f) {
  try {
    f();
  } catch (const lb::InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace lbtest
