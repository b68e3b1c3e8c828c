// SPDX-License-Identifier: MIT
#include "core/config.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>

#include "core/error.h"

namespace sabo {

bool Range::contains(double v) const {
    if (!std::isfinite(v)) return false;
    if (min_open ? v <= min : v < min) return false;
    if (max_open ? v >= max : v > max) return false;
    return true;
}

std::string Range::describe() const {
    auto bound = [](double b) {
        return std::isinf(b) ? std::string(b < 0 ? "-inf" : "inf") : fmt::format("{:g}", b);
    };
    return fmt::format("{}{}, {}{}", min_open || std::isinf(min) ? "(" : "[", bound(min), bound(max),
                       max_open || std::isinf(max) ? ")" : "]");
}

namespace {

std::vector<std::string> split_key(std::string_view key) {
    std::vector<std::string> parts;
    std::size_t start = 0;
    while (true) {
        const auto dot = key.find('.', start);
        parts.emplace_back(
            key.substr(start, dot == std::string_view::npos ? std::string_view::npos : dot - start));
        if (dot == std::string_view::npos) break;
        start = dot + 1;
    }
    return parts;
}

// Returns the table that holds the last component of `key`, creating intermediate tables.
toml::table& parent_table(toml::table& root, const std::vector<std::string>& parts, std::string_view key,
                          std::string_view source) {
    toml::table* t = &root;
    for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
        auto* node = t->get(parts[i]);
        if (node == nullptr) {
            t->insert_or_assign(parts[i], toml::table{});
            node = t->get(parts[i]);
        }
        if (!node->is_table()) {
            throw InputError(
                fmt::format("{}: key '{}': '{}' is a value, not a table", source, key, parts[i]));
        }
        t = node->as_table();
    }
    return *t;
}

std::string node_text(const toml::node& node) {
    std::ostringstream os;
    node.visit([&os](auto&& v) { os << v; });
    return os.str();
}

// Every key's path; an empty table counts as a key of its own (`[bogus]` alone is an unknown key too).
void collect_leaves(const toml::table& table, const std::string& prefix, std::vector<std::string>& out) {
    for (auto&& [k, v] : table) {
        const std::string path = prefix.empty() ? std::string(k.str()) : prefix + "." + std::string(k.str());
        const auto* sub = v.as_table();
        if (sub == nullptr || sub->empty()) {
            out.push_back(path);
        } else {
            collect_leaves(*sub, path, out);
        }
    }
}

// toml++ parses dotted keys, table headers and nested arrays and inline tables by recursion, at a cost that
// grows with the square of a key's parts: a 50 000-part key overflowed the stack (a crash, not a message),
// 20 000 took a second and half a gigabyte. No case needs more than a few: such text is refused before it is
// parsed, naming its line.
constexpr int deepest_key = 64;  // parts of a dotted key or header, and nested [ and {

void refuse_deep_text(std::string_view text, const std::string& source) {
    enum class In { text, basic, literal, ml_basic, ml_literal, comment } in = In::text;
    int line = 1, depth = 0, dots = 0;
    const auto refuse = [&](std::string_view what) {
        throw InputError(
            fmt::format("{}:{}: {} more than {} deep: no case needs that many (refused before the "
                        "file is read)",
                        source, line, what, deepest_key));
    };
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        const auto starts = [&](std::string_view s) { return text.substr(i, s.size()) == s; };
        if (c == '\n') {
            ++line;
            dots = 0;
            if (in == In::comment || in == In::basic || in == In::literal) in = In::text;
            continue;
        }
        switch (in) {
            case In::text:
                if (c == '#') {
                    in = In::comment;
                } else if (starts("\"\"\"")) {
                    in = In::ml_basic;
                    i += 2;
                } else if (starts("'''")) {
                    in = In::ml_literal;
                    i += 2;
                } else if (c == '"') {
                    in = In::basic;
                } else if (c == '\'') {
                    in = In::literal;
                } else if (c == '[' || c == '{') {
                    if (++depth > deepest_key) refuse("arrays or inline tables nested");
                } else if (c == ']' || c == '}') {
                    depth = std::max(0, depth - 1);
                } else if (c == '.') {  // a key's separator, not a number's point
                    const auto digit = [&](std::size_t k) {
                        return std::isdigit(static_cast<unsigned char>(text[k])) != 0;
                    };
                    const bool digits = i > 0 && i + 1 < text.size() && digit(i - 1) && digit(i + 1);
                    if (!digits && ++dots >= deepest_key) refuse("a dotted key or table name");
                }
                break;
            case In::basic:
                if (c == '\\')
                    ++i;
                else if (c == '"')
                    in = In::text;
                break;
            case In::literal:
                if (c == '\'') in = In::text;
                break;
            case In::ml_basic:
                if (c == '\\')
                    ++i;
                else if (starts("\"\"\"")) {
                    in = In::text;
                    i += 2;
                }
                break;
            case In::ml_literal:
                if (starts("'''")) {
                    in = In::text;
                    i += 2;
                }
                break;
            case In::comment:
                break;
        }
    }
}

}  // namespace

Config::Config(toml::table root, std::string source, std::string text,
               const std::vector<std::string>& overrides)
    : root_(std::move(root)), source_(std::move(source)), text_(std::move(text)), overrides_(overrides) {
    for (const auto& o : overrides_) apply_override(o);
}

Config Config::from_file(const std::filesystem::path& path, const std::vector<std::string>& overrides) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(fmt::format("{}: cannot be read", path.string()));
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    return from_string(text, path.string(), overrides);
}

Config Config::from_string(std::string_view text, std::string source_name,
                           const std::vector<std::string>& overrides) {
    refuse_deep_text(text, source_name);
    toml::table root;
    try {
        root = toml::parse(text, source_name);
    } catch (const toml::parse_error& e) {
        const auto& b = e.source().begin;
        throw InputError(
            fmt::format("{}:{}:{}: TOML syntax error: {}", source_name, b.line, b.column, e.description()));
    }
    return Config(std::move(root), std::move(source_name), std::string(text), overrides);
}

void Config::apply_override(const std::string& assignment) {
    const auto eq = assignment.find('=');
    if (eq == std::string::npos || eq == 0) {
        throw InputError(fmt::format("--set '{}': expected key.path=value", assignment));
    }
    // the key without the spaces around it (`--set 'a.b = 5'`); an empty part is the command line's error,
    // not the case file's
    const std::string written = assignment.substr(0, eq);
    const auto first = written.find_first_not_of(" \t"), last = written.find_last_not_of(" \t");
    const std::string key =
        first == std::string::npos ? std::string() : written.substr(first, last - first + 1);
    const std::string value = assignment.substr(eq + 1);
    refuse_deep_text(assignment, "--set");
    const auto parts = split_key(key);
    if (std::any_of(parts.begin(), parts.end(), [](const std::string& p) { return p.empty(); }))
        throw InputError(
            fmt::format("--set '{}': expected key.path=value (the key has an empty part)", assignment));
    auto& parent = parent_table(root_, parts, key, "--set");
    try {
        auto parsed = toml::parse("v = " + value);
        parent.insert_or_assign(parts.back(), std::move(*parsed.get("v")));
    } catch (const toml::parse_error&) {
        parent.insert_or_assign(parts.back(), value);  // bare word: take it as a string
    }
}

const toml::node* Config::find(std::string_view key) const {
    const toml::node* node = &root_;
    std::string path;
    for (const auto& part : split_key(key)) {
        const auto* table = node->as_table();
        if (table == nullptr) {  // `channel = 35` where [channel] is meant: say so, not "missing"
            throw InputError(fmt::format("{}: key '{}': must be a table ([{}] section), got {}", source_,
                                         path, path, node_text(*node)));
        }
        node = table->get(part);
        if (node == nullptr) return nullptr;
        path += path.empty() ? part : "." + part;
    }
    return node;
}

bool Config::has(std::string_view key) const {
    return find(key) != nullptr;
}

void Config::accept_unused(std::initializer_list<std::string_view> keys) const {
    for (const auto key : keys) read_.emplace(key);
}

void Config::fail(std::string_view key, std::string_view message) const {
    throw InputError(fmt::format("{}: key '{}': {}", source_, key, message));
}

template <class T>
void Config::remember(std::string_view key, T value) const {
    read_.emplace(key);
    const auto parts = split_key(key);
    parent_table(resolved_, parts, key, source_).insert_or_assign(parts.back(), std::move(value));
}

void Config::record(std::string_view key, double value) const {
    remember(key, value);
}
void Config::record(std::string_view key, std::int64_t value) const {
    remember(key, value);
}
void Config::record(std::string_view key, std::string value) const {
    remember(key, std::move(value));
}

double Config::recorded_number(std::string_view key) const {
    const auto node = resolved_.at_path(key);
    return node.value<double>().value_or(0.0);
}

std::string Config::recorded_text(std::string_view key) const {
    return resolved_.at_path(key).value<std::string>().value_or(std::string());
}

double Config::real(std::string_view key, Range range) const {
    const auto* node = find(key);
    if (node == nullptr) fail(key, fmt::format("missing (a number in {} is required)", range.describe()));
    double v = 0.0;
    if (const auto* d = node->as_floating_point()) {
        v = d->get();
    } else if (const auto* i = node->as_integer()) {
        v = static_cast<double>(i->get());
    } else {
        fail(key, fmt::format("must be a number, got {}", node_text(*node)));
    }
    if (!range.contains(v))
        fail(key, fmt::format("value {:g} is outside the allowed range {}", v, range.describe()));
    remember(key, v);
    return v;
}

double Config::real_or(std::string_view key, double fallback, Range range) const {
    if (has(key)) return real(key, range);
    remember(key, fallback);
    return fallback;
}

std::int64_t Config::integer(std::string_view key, std::int64_t min, std::int64_t max) const {
    const auto* node = find(key);
    if (node == nullptr) fail(key, fmt::format("missing (an integer in [{}, {}] is required)", min, max));
    const auto* i = node->as_integer();
    if (i == nullptr) fail(key, fmt::format("must be an integer, got {}", node_text(*node)));
    const auto v = i->get();
    if (v < min || v > max)
        fail(key, fmt::format("value {} is outside the allowed range [{}, {}]", v, min, max));
    remember(key, v);
    return v;
}

std::int64_t Config::integer_or(std::string_view key, std::int64_t fallback, std::int64_t min,
                                std::int64_t max) const {
    if (has(key)) return integer(key, min, max);
    remember(key, fallback);
    return fallback;
}

bool Config::boolean(std::string_view key) const {
    const auto* node = find(key);
    if (node == nullptr) fail(key, "missing (true or false is required)");
    const auto* b = node->as_boolean();
    if (b == nullptr) fail(key, fmt::format("must be true or false, got {}", node_text(*node)));
    remember(key, b->get());
    return b->get();
}

bool Config::boolean_or(std::string_view key, bool fallback) const {
    if (has(key)) return boolean(key);
    remember(key, fallback);
    return fallback;
}

std::string Config::text(std::string_view key) const {
    const auto* node = find(key);
    if (node == nullptr) fail(key, "missing (a string is required)");
    const auto* s = node->as_string();
    if (s == nullptr) fail(key, fmt::format("must be a string, got {}", node_text(*node)));
    remember(key, s->get());
    return s->get();
}

std::string Config::text_or(std::string_view key, std::string fallback) const {
    if (has(key)) return text(key);
    remember(key, fallback);
    return fallback;
}

std::string Config::choice(std::string_view key, std::initializer_list<std::string_view> allowed) const {
    return choice(key, std::span<const std::string_view>(allowed.begin(), allowed.size()));
}

std::string Config::choice(std::string_view key, std::span<const std::string_view> allowed) const {
    const auto* node = find(key);
    if (node == nullptr) fail(key, fmt::format("missing (one of: {})", fmt::join(allowed, ", ")));
    const auto* s = node->as_string();
    std::string v = s != nullptr ? s->get() : node_text(*node);
    for (auto a : allowed) {
        if (s != nullptr && v == a) {
            remember(key, v);
            return v;
        }
    }
    fail(key, fmt::format("'{}' is not one of: {}", v, fmt::join(allowed, ", ")));
}

std::string Config::choice_or(std::string_view key, std::string fallback,
                              std::initializer_list<std::string_view> allowed) const {
    return choice_or(key, std::move(fallback),
                     std::span<const std::string_view>(allowed.begin(), allowed.size()));
}

std::string Config::choice_or(std::string_view key, std::string fallback,
                              std::span<const std::string_view> allowed) const {
    if (has(key)) return choice(key, allowed);
    remember(key, fallback);
    return fallback;
}

void Config::finish() const {
    std::vector<std::string> leaves;
    collect_leaves(root_, "", leaves);
    std::vector<std::string> unknown;
    for (const auto& leaf : leaves) {
        if (read_.find(leaf) == read_.end()) unknown.push_back(leaf);
    }
    if (!unknown.empty()) {
        // the first few by name (a file of a million unknown keys made one line of 58 MB)
        constexpr std::size_t named = 10;
        const std::size_t shown = std::min(unknown.size(), named);
        const std::vector<std::string> first(unknown.begin(),
                                             unknown.begin() + static_cast<std::ptrdiff_t>(shown));
        throw InputError(fmt::format(
            "{}: unknown key{} '{}'{} (misspelt, or not used by this case; see docs/case_files.md for the "
            "keys "
            "each section accepts)",
            source_, unknown.size() > 1 ? "s" : "", fmt::join(first, "', '"),
            unknown.size() > shown ? fmt::format(" and {} more", unknown.size() - shown) : std::string()));
    }
}

std::string Config::resolved_toml() const {
    std::ostringstream os;
    os << "# Fully resolved case: every value the run used, defaults and derived numbers included.\n";
    os << "# Source: " << source_ << "\n\n";
    os << resolved_;
    os << "\n";
    return os.str();
}

}  // namespace sabo
