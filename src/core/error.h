// SPDX-License-Identifier: MIT
// Error types that the command line maps to exit codes (see src/app/main.cpp).
#pragma once
#include <stdexcept>
#include <string>

namespace sabo {

// Bad case file or command-line input: unknown/missing key, wrong type, value out of range,
// or a derived number (time step, overlap, memory) that makes the run unsafe. Exit code 2.
class InputError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// Numerical failure detected during a run (NaN, runaway overlap). Exit code 3.
class RunError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

}  // namespace sabo
