// SPDX-License-Identifier: MIT
#include "parallel/slab_exchange.h"

namespace sabo::parallel {

SlabExchange::SlabExchange(const MpiWorld& world, const SlabLayout& layout, int fields)
    : world_(world),
      layout_(layout),
      left_(world.rank() > 0 ? world.rank() - 1 : -1),
      right_(world.rank() + 1 < world.size() ? world.rank() + 1 : -1),
      cells_(static_cast<std::size_t>(layout.ghosts) * static_cast<std::size_t>(layout.ny) *
             static_cast<std::size_t>(layout.nz)),
      send_(cells_ * sizeof(double) * static_cast<std::size_t>(fields)),
      receive_(send_.size()) {}

}  // namespace sabo::parallel
