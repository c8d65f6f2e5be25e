#pragma once
// The message of the mimic::Error a call throws ("" when it throws none), for tests that check
// what an error says, not only that one is thrown.
#include <functional>
#include <string>

#include "core/error.hpp"

namespace mimic::test {

inline std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace mimic::test
