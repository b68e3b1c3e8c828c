// SPDX-License-Identifier: MIT
// A small JSON object writer for summary files: keys in insertion order, numbers with 9 significant
// digits, NaN and infinities as null, strings escaped. Nested objects and arrays render on one line.
#pragma once
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace sabo::io {

// Written as null: a value that does not apply or was not reached.
inline constexpr double not_a_number = std::numeric_limits<double>::quiet_NaN();

class JsonObject {
  public:
    JsonObject& number(std::string_view key, double value);
    JsonObject& integer(std::string_view key, std::int64_t value);
    JsonObject& text(std::string_view key, std::string_view value);
    JsonObject& boolean(std::string_view key, bool value);
    JsonObject& numbers(std::string_view key, std::span<const double> values);
    JsonObject& object(std::string_view key, const JsonObject& value);
    JsonObject& objects(std::string_view key, const std::vector<JsonObject>& values);
    // Pretty at the top level (one key per line), compact below.
    [[nodiscard]] std::string dump(bool pretty = true) const;

  private:
    std::vector<std::pair<std::string, std::string>> entries_;
};

[[nodiscard]] std::string json_number(double value);
[[nodiscard]] std::string json_string(std::string_view value);

}  // namespace sabo::io
