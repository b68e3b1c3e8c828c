// SPDX-License-Identifier: MIT
#include "parallel/grain_visitors.h"

#include <algorithm>
#include <chrono>
#include <cstring>

#include "core/stopwatch.h"

namespace sabo::parallel {

void GrainVisitors::send(const dem::DemSolver& grains, double lo, double hi) {
    const auto start = std::chrono::steady_clock::now();
    const dem::Particles& p = grains.particles();
    sent_left_.clear();
    sent_right_.clear();
    for (std::size_t i = 0; i < grains.own_count(); ++i) {
        if (left() >= 0 && p.x[i].x - p.r[i] < lo) sent_left_.push_back(static_cast<std::uint32_t>(i));
        if (right() >= 0 && p.x[i].x + p.r[i] > hi) sent_right_.push_back(static_cast<std::uint32_t>(i));
    }
    arrived_.clear();
    const auto pass = [&](const std::vector<std::uint32_t>& sent, int to, int from) {
        out_.clear();
        for (const std::uint32_t i : sent) out_.push_back({p.x[i], p.v[i], p.w[i], p.r[i]});
        world_.send_receive_block(std::as_bytes(std::span(out_)), to, received_, from);
        const std::size_t first = arrived_.size(), n = received_.size() / sizeof(coupling::VisitingGrain);
        arrived_.resize(first + n);
        std::memcpy(static_cast<void*>(arrived_.data() + first), received_.data(), received_.size());
    };
    pass(sent_right_, right(), left());  // the left neighbour's grains arrive first
    from_left_ = arrived_.size();
    pass(sent_left_, left(), right());
    exchanging_ += seconds_since(start);
}

void GrainVisitors::gather_forces(std::span<const Vec3> force, std::span<const Vec3> torque,
                                  const dem::DemSolver& grains) {
    const auto start = std::chrono::steady_clock::now();
    const std::size_t own = grains.own_count();
    force_.assign(grains.mobile_count(), Vec3{});
    torque_.assign(grains.mobile_count(), Vec3{});
    std::copy_n(force.begin(), own, force_.begin());
    std::copy_n(torque.begin(), own, torque_.begin());
    // the arrived grains' loads to their owners; the own grains' from where they went
    const auto pass = [&](std::size_t first, std::size_t count, int to,
                          const std::vector<std::uint32_t>& sent, int from) {
        loads_out_.resize(count);
        for (std::size_t k = 0; k < count; ++k)
            loads_out_[k] = {force[own + first + k], torque[own + first + k]};
        loads_in_.resize(sent.size());
        world_.send_receive(std::as_bytes(std::span(loads_out_)), to,
                            std::as_writable_bytes(std::span(loads_in_)), from);
        for (std::size_t k = 0; k < sent.size(); ++k) {
            force_[sent[k]] += loads_in_[k].force;
            torque_[sent[k]] += loads_in_[k].torque;
        }
    };
    pass(0, from_left_, left(), sent_right_, right());
    pass(from_left_, arrived_.size() - from_left_, right(), sent_left_, left());
    exchanging_ += seconds_since(start);
}

}  // namespace sabo::parallel
