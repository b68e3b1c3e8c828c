// SPDX-License-Identifier: MIT
// The case types by their case.type name: the one place that knows them all (`sabo run`, `resume`, `check`,
// the fuzzers). A new case type is its folder under src/cases/ and one line in registry.cpp.
#pragma once
#include <memory>
#include <string_view>
#include <vector>

#include "core/config.h"
#include "sim/case_type.h"

namespace sabo::cases {

// Every case.type value, the default ("channel") first.
[[nodiscard]] std::vector<std::string_view> case_type_names();
// The case type `cfg` names (case.type, default "channel"; another value is an InputError listing them).
[[nodiscard]] std::unique_ptr<sim::CaseType> make_case_type(const Config& cfg);

}  // namespace sabo::cases
