// SPDX-License-Identifier: MIT
#include "cases/registry.h"

#include <functional>
#include <utility>

#include "cases/channel/channel_type.h"
#include "cases/dam_break/dam_break_type.h"
#include "cases/debris/debris_type.h"
#include "cases/fluid_box/fluid_box_type.h"
#include "cases/sandpile/sandpile_type.h"

namespace sabo::cases {

namespace {

template <class Type>
std::unique_ptr<sim::CaseType> make() {
    return std::make_unique<Type>();
}

using Entry = std::pair<std::string_view, std::unique_ptr<sim::CaseType> (*)()>;

// One line per case type; the first is the default.
constexpr Entry registry[] = {
    {"channel", make<ChannelType>}, {"sandpile", make<SandpileType>},  {"dam_break", make<DamBreakType>},
    {"debris", make<DebrisType>},   {"fluid_box", make<FluidBoxType>},
};

}  // namespace

std::vector<std::string_view> case_type_names() {
    std::vector<std::string_view> names;
    for (const auto& [name, factory] : registry) names.emplace_back(name);
    return names;
}

std::unique_ptr<sim::CaseType> make_case_type(const Config& cfg) {
    const std::vector<std::string_view> names = case_type_names();
    const std::string type = cfg.choice_or("case.type", std::string(names.front()), names);
    for (const auto& [name, factory] : registry)
        if (type == name) return factory();
    return nullptr;  // (choice_or refused any other name)
}

}  // namespace sabo::cases
