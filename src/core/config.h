// SPDX-License-Identifier: MIT
// Case-file access: typed, validated reads of a TOML document with dotted key paths.
//
// Every read records the key (so keys nobody read are reported as unknown by finish()) and the
// value actually used, defaults included, in resolved() — the "fully resolved case" written next
// to the outputs. Errors name the file, the key and the allowed range (InputError).
#pragma once
#include <toml++/toml.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <limits>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace sabo {

// Closed or open interval for numeric keys; printed in error messages as e.g. "(0, 1]".
struct Range {
    double min = -std::numeric_limits<double>::infinity();
    double max = std::numeric_limits<double>::infinity();
    bool min_open = false;
    bool max_open = false;

    static Range positive() { return {0.0, std::numeric_limits<double>::infinity(), true, false}; }
    static Range non_negative() { return {0.0, std::numeric_limits<double>::infinity(), false, false}; }
    static Range closed(double a, double b) { return {a, b, false, false}; }
    static Range open_closed(double a, double b) { return {a, b, true, false}; }
    [[nodiscard]] bool contains(double v) const;
    [[nodiscard]] std::string describe() const;
};

class Config {
  public:
    // Parses `path` and applies "--set key.path=value" overrides (value parsed as TOML, else string).
    static Config from_file(const std::filesystem::path& path,
                            const std::vector<std::string>& overrides = {});
    static Config from_string(std::string_view text, std::string source_name,
                              const std::vector<std::string>& overrides = {});

    [[nodiscard]] bool has(std::string_view key) const;
    // What the case was made from: the text, and the overrides applied to it (a run folder keeps them so
    // that the run can be resumed from the folder alone).
    [[nodiscard]] const std::string& text() const { return text_; }
    [[nodiscard]] const std::vector<std::string>& overrides() const { return overrides_; }

    [[nodiscard]] double real(std::string_view key, Range range) const;
    [[nodiscard]] double real_or(std::string_view key, double fallback, Range range) const;
    [[nodiscard]] std::int64_t integer(std::string_view key, std::int64_t min, std::int64_t max) const;
    [[nodiscard]] std::int64_t integer_or(std::string_view key, std::int64_t fallback, std::int64_t min,
                                          std::int64_t max) const;
    [[nodiscard]] bool boolean(std::string_view key) const;
    [[nodiscard]] bool boolean_or(std::string_view key, bool fallback) const;
    [[nodiscard]] std::string text(std::string_view key) const;
    [[nodiscard]] std::string text_or(std::string_view key, std::string fallback) const;
    [[nodiscard]] std::string choice(std::string_view key,
                                     std::initializer_list<std::string_view> allowed) const;
    [[nodiscard]] std::string choice_or(std::string_view key, std::string fallback,
                                        std::initializer_list<std::string_view> allowed) const;
    [[nodiscard]] std::string choice(std::string_view key, std::span<const std::string_view> allowed) const;
    [[nodiscard]] std::string choice_or(std::string_view key, std::string fallback,
                                        std::span<const std::string_view> allowed) const;
    // A choice read as the enum E whose value i is named names[i].
    template <class E, std::size_t N>
    [[nodiscard]] E enum_or(std::string_view key, E fallback,
                            const std::array<std::string_view, N>& names) const {
        const std::string v = choice_or(key, std::string(names[static_cast<std::size_t>(fallback)]),
                                        std::span<const std::string_view>(names));
        return static_cast<E>(std::find(names.begin(), names.end(), v) - names.begin());
    }

    // Records a derived value (not read from the file) in the resolved case, e.g. "derived.dt_s".
    void record(std::string_view key, double value) const;
    void record(std::string_view key, std::int64_t value) const;
    void record(std::string_view key, std::string value) const;
    // A number recorded so (0 when none was).
    [[nodiscard]] double recorded_number(std::string_view key) const;
    // A text value of the resolved case, recorded or read (empty when none was).
    [[nodiscard]] std::string recorded_text(std::string_view key) const;

    // Keys that are valid but do not apply to this case (e.g. a slit's S/r when a sweep sets
    // barrier.type = "closed"): not reported as unknown, not written to the resolved case.
    void accept_unused(std::initializer_list<std::string_view> keys) const;

    // Throws InputError listing every key present in the file that no reader asked for.
    void finish() const;

    [[nodiscard]] const std::string& source() const { return source_; }
    [[nodiscard]] std::string resolved_toml() const;

    [[noreturn]] void fail(std::string_view key, std::string_view message) const;

  private:
    Config(toml::table root, std::string source, std::string text, const std::vector<std::string>& overrides);
    [[nodiscard]] const toml::node* find(std::string_view key) const;
    void apply_override(const std::string& assignment);
    template <class T>
    void remember(std::string_view key, T value) const;

    toml::table root_;
    std::string source_;
    std::string text_;
    std::vector<std::string> overrides_;
    mutable toml::table resolved_;
    mutable std::set<std::string, std::less<>> read_;
};

}  // namespace sabo
