// SPDX-License-Identifier: MIT
// A stable counting sort in parallel whose result does not depend on the thread count: the grains into
// cells and the transposed pair index (dem/neighbor_list.cpp), the grains into spatial order
// (dem/spatial_order.cpp).
#pragma once
#include <omp.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace sabo::dem {

// Stable counting sort of the items 0..count-1 by key(item) < keys, in parallel: start (keys + 1 entries)
// gets each key's first position, and place(item, position) is called once per item, positions of one key
// in ascending item order. Each thread counts and places a contiguous range of items, earlier ranges first,
// so every position is the same whatever the thread count. histogram: scratch, threads x keys counts.
template <class Key, class Place>
void counting_sort(std::size_t count, std::size_t keys, Key&& key, std::vector<std::uint32_t>& start,
                   std::vector<std::uint32_t>& histogram, Place&& place) {
    const int threads = omp_get_max_threads();
    histogram.resize(static_cast<std::size_t>(threads) * keys + static_cast<std::size_t>(threads));
    start.resize(keys + 1);
    start[0] = 0;
    std::uint32_t* const chunk_total = histogram.data() + static_cast<std::size_t>(threads) * keys;
#pragma omp parallel num_threads(threads)
    {
        const auto t = static_cast<std::size_t>(omp_get_thread_num());
        const auto nt = static_cast<std::size_t>(omp_get_num_threads());
        const std::size_t i0 = count * t / nt, i1 = count * (t + 1) / nt;
        const std::size_t c0 = keys * t / nt, c1 = keys * (t + 1) / nt;
        std::uint32_t* const mine = histogram.data() + t * keys;
        std::fill(mine, mine + keys, 0U);
        for (std::size_t i = i0; i < i1; ++i) ++mine[key(i)];
#pragma omp barrier
        // per key: each thread's offset within the key (earlier threads first) and the key's count; the
        // running sum over this thread's chunk of keys
        std::uint32_t run = 0;
        for (std::size_t c = c0; c < c1; ++c) {
            std::uint32_t sum = 0;
            for (std::size_t u = 0; u < nt; ++u) {
                std::uint32_t& h = histogram[u * keys + c];
                const std::uint32_t v = h;
                h = sum;
                sum += v;
            }
            run += sum;
            start[c + 1] = run;
        }
        chunk_total[t] = run;
#pragma omp barrier
        std::uint32_t base = 0;
        for (std::size_t u = 0; u < t; ++u) base += chunk_total[u];
        for (std::size_t c = c0; c < c1; ++c) start[c + 1] += base;
#pragma omp barrier
        for (std::size_t i = i0; i < i1; ++i) {
            const std::size_t c = key(i);
            place(i, start[c] + mine[c]++);
        }
    }
}

}  // namespace sabo::dem
