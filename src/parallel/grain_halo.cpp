// SPDX-License-Identifier: MIT
#include "parallel/grain_halo.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <limits>
#include <span>
#include <stdexcept>
#include <utility>

#include "core/error.h"
#include "core/stopwatch.h"
#include "dem/spatial_order.h"
#include "parallel/slab_partition.h"

namespace sabo::parallel {

namespace {

// Records travel as a count followed by their bytes.
template <class T>
void append(std::vector<std::byte>& out, const std::vector<T>& items) {
    const std::uint64_t count = items.size();
    const auto* head = reinterpret_cast<const std::byte*>(&count);
    out.insert(out.end(), head, head + sizeof count);
    const auto bytes = std::as_bytes(std::span(items));
    out.insert(out.end(), bytes.begin(), bytes.end());
}

template <class T>
void take(std::span<const std::byte>& in, std::vector<T>& items) {
    std::uint64_t count = 0;
    std::memcpy(&count, in.data(), sizeof count);
    in = in.subspan(sizeof count);
    const std::size_t first = items.size();
    items.resize(first + count);
    std::memcpy(static_cast<void*>(items.data() + first), in.data(), count * sizeof(T));
    in = in.subspan(count * sizeof(T));
}

template <class T>
std::span<const std::byte> bytes_of(const std::vector<T>& v) {
    return std::as_bytes(std::span(v));
}
template <class T>
std::span<std::byte> bytes_of(std::vector<T>& v) {
    return std::as_writable_bytes(std::span(v));
}

}  // namespace

GrainHalo::GrainHalo(const MpiWorld& world, dem::DemSolver& grains, std::vector<double> faces,
                     bool follow_grains, double largest_radius)
    : world_(world),
      grains_(grains),
      faces_(std::move(faces)),
      follow_grains_(follow_grains),
      largest_radius_(largest_radius) {
    if (!faces_.empty() && faces_.size() + 1 != static_cast<std::size_t>(world_.size()))
        throw InputError(fmt::format("{} slab faces for {} ranks (expected {})", faces_.size(), world_.size(),
                                     world_.size() - 1));
    if (!std::is_sorted(faces_.begin(), faces_.end()))
        throw InputError("the slab faces must be in ascending order of x");
}

void GrainHalo::sort_spatially(std::vector<dem::GrainRecord>& grains) {
    positions_.resize(grains.size());
    for (std::size_t k = 0; k < grains.size(); ++k) positions_[k] = grains[k].x;
    dem::spatial_order(positions_, grains.size(), reach_, order_, order_start_, order_histogram_);
    sorted_.resize(grains.size());
    for (std::size_t k = 0; k < grains.size(); ++k) sorted_[k] = grains[order_[k]];
    grains.swap(sorted_);
}

void GrainHalo::restored() const {
    const bool fits =
        faces_.size() + 1 == static_cast<std::size_t>(world_.size()) &&
        ghost_state_.size() == grains_.ghost_count() && removed_ <= total_ &&
        (leaving_.empty() || leaving_.size() == grains_.own_count()) &&
        std::all_of(lent_.begin(), lent_.end(), [&](std::uint32_t i) { return i < grains_.own_count(); });
    if (!fits) throw InputError("the checkpoint's slab state does not fit its grains (corrupt checkpoint)");
}

void GrainHalo::move_faces(std::vector<double> faces) {
    if (faces.size() != faces_.size()) throw std::logic_error("move_faces: another number of faces");
    const auto start = std::chrono::steady_clock::now();
    faces_ = std::move(faces);
    ++face_moves_;
    repartition();
    grains_.rebuild_lists_now();  // the next step's rolling sweep reads the lists of these grains
    repartitioning_ += seconds_since(start);
}

void GrainHalo::set_external_forces(std::span<const Vec3> force, std::span<const Vec3> torque) {
    grains_.set_external_forces(force, torque);
    const auto start = std::chrono::steady_clock::now();
    refresh_ghosts();
    exchanging_ += seconds_since(start);
}

void GrainHalo::remove(std::span<const std::uint8_t> gone) {
    if (gone.size() != grains_.own_count())
        throw std::logic_error(
            fmt::format("GrainHalo::remove: {} flags for {} own grains", gone.size(), grains_.own_count()));
    if (std::none_of(gone.begin(), gone.end(), [](std::uint8_t g) { return g != 0; })) return;
    if (leaving_.empty()) leaving_.assign(gone.size(), 0);
    for (std::size_t i = 0; i < gone.size(); ++i) leaving_[i] |= gone[i];
    grains_.invalidate_lists();  // this rank's stale lists make every rank re-partition at the next step
}

void GrainHalo::add(std::vector<dem::GrainRecord> batch) {
    // every rank places the same batch (from the same gathered grains): a rank that did not would give other
    // ids than its neighbours
    const auto n = static_cast<std::int64_t>(batch.size());
    if (world_.max(n) != -world_.max(-n)) throw std::logic_error("GrainHalo::add: the ranks' batches differ");
    if (batch.empty()) return;
    const auto start = std::chrono::steady_clock::now();
    std::vector<dem::GrainRecord> mine;
    for (dem::GrainRecord& g : batch) {
        if (total_ >= dem::first_wall_key) throw RunError("an inflow: the run has used every grain id");
        if (2.0 * g.r + grains_.skin_max() > reach_ * (1.0 + 1e-12))
            throw std::logic_error("GrainHalo::add: a grain larger than the ghost reach counts");
        g.id = static_cast<std::uint32_t>(total_++);
        if (owner_of(g.x.x) == world_.rank()) mine.push_back(g);
    }
    repartition(std::move(mine));
    grains_.rebuild_lists_now();  // the next step's rolling sweep reads the lists of these grains
    repartitioning_ += seconds_since(start);
}

int GrainHalo::owner_of(double x) const {
    return static_cast<int>(std::upper_bound(faces_.begin(), faces_.end(), x) - faces_.begin());
}

void GrainHalo::divide(double reach) {
    if (grains_.ghost_count() != 0) throw InputError("the grains are divided already");
    const dem::Particles& p = grains_.particles();
    total_ = p.n_mobile;
    double r_max = largest_radius_;
    for (std::size_t i = 0; i < total_; ++i) r_max = std::max(r_max, p.r[i]);
    reach_ = reach > 0.0 ? reach : 2.0 * r_max + grains_.skin_max();
    if (faces_.empty() && world_.size() > 1) faces_ = equal_count_faces(p);
    for (std::size_t k = 1; k < faces_.size(); ++k) {
        if (faces_[k] - faces_[k - 1] < reach_)
            throw InputError(fmt::format(
                "the slab of rank {} is {:.4g} m wide, less than the {:.4g} m the grains' contacts can reach "
                "across a face (twice the largest radius plus the largest skin): use fewer ranks",
                k, faces_[k] - faces_[k - 1], reach_));
    }
    const int me = world_.rank();
    const auto& ids = grains_.ids();
    // grains are named by their ids below the count (a solver that removed grains has gaps: not divided)
    if (std::any_of(ids.begin(), ids.begin() + static_cast<std::ptrdiff_t>(total_),
                    [&](std::uint32_t id) { return id >= total_; }))
        throw InputError(
            "grains were removed from this run before it was divided among ranks: run it as one process");
    owner_by_id_.resize(total_);
    for (std::size_t i = 0; i < total_; ++i) owner_by_id_[ids[i]] = owner_of(p.x[i].x);
    // this rank's grains, and the right neighbour's in the order that rank will give them
    std::vector<std::uint32_t> own, right_own;
    for (std::size_t i = 0; i < total_; ++i) {
        const int owner = owner_by_id_[ids[i]];
        if (owner == me) own.push_back(static_cast<std::uint32_t>(i));
        if (owner == me + 1) right_own.push_back(static_cast<std::uint32_t>(i));
    }
    std::vector<dem::ContactRecord> all, mine;
    grains_.contact_records(all);
    for (const dem::ContactRecord& c : all) {
        const int at = is_grain(c.b) ? std::min(owner_by_id_[c.a], owner_by_id_[c.b]) : owner_by_id_[c.a];
        if (at == me) mine.push_back(c);
    }
    std::vector<dem::GrainRecord> own_grains, right_grains, ghost_grains;
    grains_.pack_grains(own, own_grains);
    sort_spatially(own_grains);
    grains_.pack_grains(right_own, right_grains);
    sort_spatially(right_grains);
    if (right() >= 0) {
        const double reach = faces_[static_cast<std::size_t>(me)] + reach_;
        for (const dem::GrainRecord& g : right_grains)
            if (g.x.x < reach) ghost_grains.push_back(g);
    }
    install(std::move(own_grains), std::move(ghost_grains), std::move(mine));
    if (me != 0) grains_.drop_last_reactions();  // every rank holds the undivided run's: count them once
    grains_.rebuild_lists_now();  // the first step's rolling sweep reads the lists of these grains
}

void GrainHalo::install(std::vector<dem::GrainRecord> own, std::vector<dem::GrainRecord> ghosts,
                        std::vector<dem::ContactRecord> contacts) {
    lent_.clear();
    if (left() >= 0) {
        const double reach = faces_[static_cast<std::size_t>(left())] + reach_;
        for (std::size_t i = 0; i < own.size(); ++i)
            if (own[i].x.x < reach) lent_.push_back(static_cast<std::uint32_t>(i));
    }
    ghost_state_.clear();
    for (const dem::GrainRecord& g : ghosts) ghost_state_.push_back({g.x, g.vh, g.wh, g.contacts});
    const std::size_t n_ghosts = ghosts.size();
    own.insert(own.end(), ghosts.begin(), ghosts.end());
    grains_.replace_mobile(own, n_ghosts, std::move(contacts));
}

void GrainHalo::step() {
    using clock = std::chrono::steady_clock;
    const double excess = grains_.drift();
    auto start = clock::now();
    return_spins();
    refresh_ghosts();
    const bool rebuild =
        world_.max_real(grains_.lists_stale() ? std::numeric_limits<double>::infinity() : excess) > 0.0;
    exchanging_ += seconds_since(start);
    if (rebuild) {
        start = clock::now();
        repartition();
        repartitioning_ += seconds_since(start);
    }
    grains_.finish_step(rebuild);
    start = clock::now();
    return_reactions();
    refresh_ghosts();
    exchanging_ += seconds_since(start);
}

void GrainHalo::return_spins() {
    const std::size_t first = grains_.own_count(), n_ghosts = grains_.ghost_count();
    const auto spins = grains_.half_step_spins();
    spins_out_.resize(n_ghosts);
    spins_in_.resize(lent_.size());
    for (std::size_t g = 0; g < n_ghosts; ++g) spins_out_[g] = spins[first + g] - ghost_state_[g].wh;
    world_.send_receive(bytes_of(spins_out_), right(), bytes_of(spins_in_), left());
    for (std::size_t k = 0; k < lent_.size(); ++k) grains_.add_spin(lent_[k], spins_in_[k]);
}

void GrainHalo::return_reactions() {
    const std::size_t first = grains_.own_count(), n_ghosts = grains_.ghost_count();
    reactions_out_.resize(n_ghosts);
    reactions_in_.resize(lent_.size());
    const auto& f = grains_.forces();
    const auto& t = grains_.torques();
    const auto& counts = grains_.contact_counts();
    for (std::size_t g = 0; g < n_ghosts; ++g)
        reactions_out_[g] = {f[first + g], t[first + g], counts[first + g]};
    world_.send_receive(bytes_of(reactions_out_), right(), bytes_of(reactions_in_), left());
    for (std::size_t k = 0; k < lent_.size(); ++k)
        grains_.add_reaction(lent_[k], reactions_in_[k].force, reactions_in_[k].torque,
                             static_cast<std::uint32_t>(reactions_in_[k].count));
}

void GrainHalo::refresh_ghosts() {
    grains_.ghost_states(lent_, lent_state_);
    ghost_state_.resize(grains_.ghost_count());
    world_.send_receive(bytes_of(lent_state_), left(), bytes_of(ghost_state_), right());
    grains_.set_ghost_states(ghost_state_);
}

std::vector<double> GrainHalo::count_in_bins(const dem::Particles& p, std::size_t n, double lo,
                                             double hi) const {
    const double bin = 0.5 * reach_;
    std::vector<double> count(static_cast<std::size_t>(std::floor((hi - lo) / bin)) + 1, 0.0);
    for (std::size_t i = 0; i < n; ++i)
        count[std::min(count.size() - 1, static_cast<std::size_t>(std::floor((p.x[i].x - lo) / bin)))] += 1.0;
    return count;
}

std::vector<double> GrainHalo::equal_count_cuts(std::span<const double> count, double lo) const {
    const std::vector<int> cuts = SlabPartition::balanced(count, world_.size(), 2).cuts();
    std::vector<double> faces;
    for (std::size_t r = 1; r + 1 < cuts.size(); ++r) faces.push_back(lo + 0.5 * reach_ * cuts[r]);
    return faces;
}

std::vector<double> GrainHalo::equal_count_faces(const dem::Particles& p) const {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (std::size_t i = 0; i < p.n_mobile; ++i) lo = std::min(lo, p.x[i].x), hi = std::max(hi, p.x[i].x);
    const std::vector<double> count = count_in_bins(p, p.n_mobile, lo, hi);
    const std::size_t bins = count.size();
    const auto ranks = static_cast<std::size_t>(world_.size());
    if (bins < 2 * ranks)
        throw InputError(
            fmt::format("{} MPI ranks cannot each hold a slab of grains {:.4g} m wide (twice the "
                        "largest radius plus the largest skin): the grains span {:.4g} m along x; "
                        "use at most {} ranks",
                        ranks, reach_, hi - lo, std::max<std::size_t>(1, bins / 2)));
    return equal_count_cuts(count, lo);
}

void GrainHalo::follow_grains() {
    const int ranks = world_.size();
    if (ranks < 2 || !follow_grains_) return;
    const dem::Particles& p = grains_.particles();
    const std::size_t n_own = grains_.own_count();
    // the slowest slab: the most grains over the mean (each rank's count, exact)
    std::vector<double> count(static_cast<std::size_t>(ranks), 0.0);
    count[static_cast<std::size_t>(world_.rank())] = static_cast<double>(n_own);
    world_.sum_reals(count);
    const double mean = static_cast<double>(total_grains()) / ranks;
    if (*std::max_element(count.begin(), count.end()) < (1.0 + min_imbalance) * mean) return;
    // the grains' count in bins of half a ghost reach along x, over the ranks
    std::vector<double> extent(2, -std::numeric_limits<double>::infinity());  // −min x, max x
    for (std::size_t i = 0; i < n_own; ++i) {
        extent[0] = std::max(extent[0], -p.x[i].x);
        extent[1] = std::max(extent[1], p.x[i].x);
    }
    world_.max_reals(extent);
    const double lo = -extent[0];
    std::vector<double> histogram = count_in_bins(p, n_own, lo, extent[1]);
    if (histogram.size() < 2 * static_cast<std::size_t>(ranks))
        return;  // a cloud narrower than the slabs may be
    world_.sum_reals(histogram);
    const std::vector<double> target = equal_count_cuts(histogram, lo);
    // Each face moves toward its target but stays a ghost reach inside its neighbours' old faces: a grain
    // then changes rank by one slab at most (it moved less than a half-skin), and no slab is thinner than
    // a reach.
    std::vector<double> moved(faces_);
    for (std::size_t k = 0; k < faces_.size(); ++k) {
        const double floor = k > 0 ? std::max(faces_[k - 1], moved[k - 1]) + reach_ : -1e300;
        const double ceiling = k + 1 < faces_.size() ? faces_[k + 1] - reach_ : 1e300;
        if (floor > ceiling) return;  // no room: the faces stay
        moved[k] = std::clamp(target[k], floor, ceiling);
    }
    faces_ = std::move(moved);
    ++face_moves_;
}

void GrainHalo::repartition(std::vector<dem::GrainRecord> joining) {
    follow_grains();
    const int me = world_.rank();
    const dem::Particles& p = grains_.particles();
    const auto& ids = grains_.ids();
    const std::size_t n_own = grains_.own_count(), n_local = p.n_mobile;
    // where each grain held here (own or ghost) belongs now, by id (only those entries are read)
    owner_by_id_.resize(total_);
    for (std::size_t i = 0; i < n_local; ++i) owner_by_id_[ids[i]] = owner_of(p.x[i].x);
    constexpr int nobody = -1;  // a grain removed now, and its contacts
    std::size_t removed_here = 0;
    for (std::size_t i = 0; i < leaving_.size(); ++i)
        if (leaving_[i] != 0) owner_by_id_[ids[i]] = nobody, ++removed_here;
    leaving_.clear();
    removed_ += static_cast<std::size_t>(world_.sum(static_cast<std::int64_t>(removed_here)));
    const auto owner = [&](std::uint32_t id) { return owner_by_id_[id]; };
    const auto jumped = [&](std::uint32_t id, int to) {
        return RunError(
            fmt::format("step {}: grain {} went from rank {} to rank {} between two list builds (a "
                        "slab narrower than one list interval's travel)",
                        grains_.steps(), id, me, to));
    };
    std::vector<std::uint32_t> stay, to_left, to_right;
    for (std::size_t i = 0; i < n_own; ++i) {
        const int to = owner(ids[i]);
        if (to == nobody) continue;
        if (to == me)
            stay.push_back(static_cast<std::uint32_t>(i));
        else if (to == me - 1)
            to_left.push_back(static_cast<std::uint32_t>(i));
        else if (to == me + 1)
            to_right.push_back(static_cast<std::uint32_t>(i));
        else
            throw jumped(ids[i], to);
    }
    // every contact to the rank that evaluates it now: the left one of its two grains' owners
    std::vector<dem::ContactRecord> all, kept, left_contacts, right_contacts;
    grains_.contact_records(all);
    for (const dem::ContactRecord& c : all) {
        if (owner(c.a) == nobody || (is_grain(c.b) && owner(c.b) == nobody)) continue;
        const int at = is_grain(c.b) ? std::min(owner(c.a), owner(c.b)) : owner(c.a);
        if (at == me)
            kept.push_back(c);
        else if (at == me - 1)
            left_contacts.push_back(c);
        else if (at == me + 1)
            right_contacts.push_back(c);
        else
            throw jumped(c.a, at);
    }
    std::vector<dem::GrainRecord> own, moving;
    grains_.pack_grains(stay, own);
    const auto swap_with = [&](const std::vector<std::uint32_t>& leaving,
                               const std::vector<dem::ContactRecord>& contacts, int to, int from) {
        moving.clear();
        grains_.pack_grains(leaving, moving);
        send_.clear();
        append(send_, moving);
        append(send_, contacts);
        world_.send_receive_block(send_, to, receive_, from);
        if (receive_.empty()) return;
        std::span<const std::byte> in(receive_);
        const std::size_t before = own.size();
        take(in, own);
        arrivals_ += own.size() - before;
        take(in, kept);
    };
    swap_with(to_left, left_contacts, left(), right());
    swap_with(to_right, right_contacts, right(), left());
    own.insert(own.end(), joining.begin(), joining.end());
    sort_spatially(own);
    // the left neighbour's ghosts: own grains within reach of its face
    moving.clear();
    if (left() >= 0) {
        const double reach = faces_[static_cast<std::size_t>(left())] + reach_;
        for (const dem::GrainRecord& g : own)
            if (g.x.x < reach) moving.push_back(g);
    }
    send_.clear();
    append(send_, moving);
    world_.send_receive_block(send_, left(), receive_, right());
    std::vector<dem::GrainRecord> ghosts;
    if (!receive_.empty()) {
        std::span<const std::byte> in(receive_);
        take(in, ghosts);
    }
    install(std::move(own), std::move(ghosts), std::move(kept));
    ++repartitions_;
}

}  // namespace sabo::parallel
