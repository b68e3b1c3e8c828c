// SPDX-License-Identifier: MIT
#include "core/config.h"

#include <gtest/gtest.h>

#include "core/error.h"

namespace sabo {
namespace {

const char* const doc = R"(
[a]
x = 1.5
n = 3
flag = true
name = "slit"
[a.b]
y = 2
)";

std::string message_of(const std::function<void()>& f) {
    try {
        f();
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

TEST(Config, TypedReadsWithRanges) {
    const auto c = Config::from_string(doc, "case.toml");
    EXPECT_DOUBLE_EQ(c.real("a.x", Range::positive()), 1.5);
    EXPECT_DOUBLE_EQ(c.real("a.b.y", Range::positive()), 2.0);  // integers accepted as reals
    EXPECT_EQ(c.integer("a.n", 0, 10), 3);
    EXPECT_TRUE(c.boolean("a.flag"));
    EXPECT_EQ(c.choice("a.name", {"slit", "closed"}), "slit");
    EXPECT_DOUBLE_EQ(c.real_or("a.missing", 7.0, Range::positive()), 7.0);
    EXPECT_NO_THROW(c.finish());
}

TEST(Config, ErrorsNameFileKeyAndRange) {
    const auto c = Config::from_string(doc, "case.toml");
    const auto range = message_of([&] { (void)c.real("a.x", Range::closed(0.0, 1.0)); });
    EXPECT_NE(range.find("case.toml"), std::string::npos) << range;
    EXPECT_NE(range.find("'a.x'"), std::string::npos) << range;
    EXPECT_NE(range.find("[0, 1]"), std::string::npos) << range;
    const auto missing = message_of([&] { (void)c.real("a.z", Range::positive()); });
    EXPECT_NE(missing.find("missing"), std::string::npos) << missing;
    EXPECT_NE(missing.find("(0, inf)"), std::string::npos) << missing;
    const auto type = message_of([&] { (void)c.real("a.name", Range::positive()); });
    EXPECT_NE(type.find("must be a number"), std::string::npos) << type;
    const auto choice = message_of([&] { (void)c.choice("a.name", {"closed", "none"}); });
    EXPECT_NE(choice.find("closed, none"), std::string::npos) << choice;
    EXPECT_THROW((void)c.integer("a.x", 0, 10), InputError);  // 1.5 is not an integer
}

TEST(Config, UnknownKeysAreRejected) {
    const auto c = Config::from_string(doc, "case.toml");
    (void)c.real("a.x", Range::positive());
    const auto msg = message_of([&] { c.finish(); });
    EXPECT_NE(msg.find("unknown keys"), std::string::npos) << msg;
    EXPECT_NE(msg.find("a.b.y"), std::string::npos) << msg;
}

TEST(Config, OverridesReplaceAndAddKeys) {
    const auto c = Config::from_string(doc, "case.toml", {"a.x=0.25", "a.b.z=4", "c.word=closed"});
    EXPECT_DOUBLE_EQ(c.real("a.x", Range::positive()), 0.25);
    EXPECT_EQ(c.integer("a.b.z", 0, 9), 4);
    EXPECT_EQ(c.text("c.word"), "closed");  // bare words become strings
    EXPECT_THROW(Config::from_string(doc, "case.toml", {"novalue"}), InputError);
    EXPECT_THROW(Config::from_string(doc, "case.toml", {"a.x.deeper=1"}), InputError);
}

TEST(Config, SyntaxErrorsGiveLineNumbers) {
    const auto msg = message_of([] { (void)Config::from_string("[a]\nx = = 1\n", "bad.toml"); });
    EXPECT_NE(msg.find("bad.toml:2"), std::string::npos) << msg;
}

TEST(Config, ResolvedCaseHoldsDefaultsAndDerivedValues) {
    const auto c = Config::from_string(doc, "case.toml");
    (void)c.real_or("a.missing", 7.0, Range::positive());
    c.record("derived.dt_s", 1e-4);
    const auto text = c.resolved_toml();
    EXPECT_NE(text.find("missing = 7.0"), std::string::npos) << text;
    EXPECT_NE(text.find("dt_s = 0.0001"), std::string::npos) << text;
}

}  // namespace
}  // namespace sabo
