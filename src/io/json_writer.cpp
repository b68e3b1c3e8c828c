// SPDX-License-Identifier: MIT
#include "io/json_writer.h"

#include <fmt/format.h>

#include <cmath>

namespace sabo::io {

std::string json_number(double value) {
    return std::isfinite(value) ? fmt::format("{:.9g}", value) : "null";
}

std::string json_string(std::string_view value) {
    std::string out = "\"";
    for (const char c : value) {
        switch (c) {
            case '"':
                out += "\\\"";
                break;
            case '\\':
                out += "\\\\";
                break;
            case '\n':
                out += "\\n";
                break;
            case '\t':
                out += "\\t";
                break;
            default:
                if (static_cast<unsigned char>(c) < 0x20) {
                    out += fmt::format("\\u{:04x}", static_cast<int>(c));
                } else {
                    out += c;
                }
        }
    }
    return out + "\"";
}

JsonObject& JsonObject::number(std::string_view key, double value) {
    entries_.emplace_back(key, json_number(value));
    return *this;
}
JsonObject& JsonObject::integer(std::string_view key, std::int64_t value) {
    entries_.emplace_back(key, fmt::format("{}", value));
    return *this;
}
JsonObject& JsonObject::text(std::string_view key, std::string_view value) {
    entries_.emplace_back(key, json_string(value));
    return *this;
}
JsonObject& JsonObject::boolean(std::string_view key, bool value) {
    entries_.emplace_back(key, value ? "true" : "false");
    return *this;
}
JsonObject& JsonObject::numbers(std::string_view key, std::span<const double> values) {
    std::string s = "[";
    for (std::size_t k = 0; k < values.size(); ++k) s += (k ? ", " : "") + json_number(values[k]);
    entries_.emplace_back(key, s + "]");
    return *this;
}
JsonObject& JsonObject::object(std::string_view key, const JsonObject& value) {
    entries_.emplace_back(key, value.dump(false));
    return *this;
}
JsonObject& JsonObject::objects(std::string_view key, const std::vector<JsonObject>& values) {
    std::string s = "[";
    for (std::size_t k = 0; k < values.size(); ++k) s += (k ? ", " : "") + values[k].dump(false);
    entries_.emplace_back(key, s + "]");
    return *this;
}

std::string JsonObject::dump(bool pretty) const {
    std::string s = "{";
    for (std::size_t k = 0; k < entries_.size(); ++k) {
        s += k ? "," : "";
        s += pretty ? "\n  " : (k ? " " : "");
        s += json_string(entries_[k].first) + ": " + entries_[k].second;
    }
    return s + (pretty ? "\n}\n" : "}");
}

}  // namespace sabo::io
