// SPDX-License-Identifier: MIT
// Binary checkpoints of a run's state (docs/restart.md): the writer fills `path.tmp` and renames it over
// `path` on commit() (a crash mid-write leaves the previous checkpoint whole); the file ends with a
// checksum of everything before it. The reader checks the checksum before it reads anything and refuses a
// file of another kind, version or build, a truncated or damaged one, naming the file.
//
// The objects that are checkpointed expose one `template <class A> void transfer(A& a)` listing their
// state as a(x, y, ...): the same list writes (CheckpointOut) and reads (CheckpointIn), so the two cannot
// disagree. Scalars and vectors of trivially copyable types go as raw bytes (native layout: a checkpoint
// is read back by the same build on the same kind of machine), strings and vectors of anything else with
// a transfer() element by element.
#pragma once
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <type_traits>
#include <vector>

#include "core/config.h"

namespace sabo::io {

// The file's first bytes: kind and layout version (bump when a transfer() list or an array's layout changes;
// 2: the lattice's rows padded to cache lines; 4: every run type, the simulation's and observers' state;
// 5: the checksum; 7: the lattice's obstacle elements, a divided run's slab faces; 8: the grains' ghost
// count; 9: whether the grains' external forces are set; A: a debris run's fluid height; B: the lattice's
// outlets; C: the grains that left a channel or passed its barrier's crest; D: the fluid that crossed a
// debris run's barrier; E: the triangles of mesh walls in the grains' neighbour lists; F: the force maps on a
// mesh barrier's triangles; G: the fluid's part of them).
inline constexpr char checkpoint_magic[8] = {'S', 'A', 'B', 'O', 'C', 'K', 'P', 'G'};

// A 64-bit checksum of a byte stream, fed piece by piece (FNV-1a on 8-byte words; the tail's bytes padded
// with zeros): catches the damage of a disk, a copy or an editor, not a forgery.
class Checksum {
  public:
    void add(const void* data, std::size_t size);
    [[nodiscard]] std::uint64_t value() const;

  private:
    void mix(std::uint64_t word) { hash_ = (hash_ ^ word) * 0x100000001b3ULL; }
    std::uint64_t hash_ = 0xcbf29ce484222325ULL;
    unsigned char tail_[8] = {};
    std::size_t tail_size_ = 0;
};

// Checks the checksum that ends the file against its content; throws InputError naming the file if it is
// too short or damaged.
void verify_checksum(const std::filesystem::path& path);

class CheckpointOut {
  public:
    static constexpr bool reading = false;  // transfer() lists may act after a read (if constexpr)
    explicit CheckpointOut(std::filesystem::path path);
    ~CheckpointOut();
    CheckpointOut(const CheckpointOut&) = delete;
    CheckpointOut& operator=(const CheckpointOut&) = delete;
    template <class... T>
    void operator()(const T&... values) {
        (put(values), ...);
    }
    // Flushes and renames the temporary file over the checkpoint.
    void commit();

  private:
    void bytes(const void* data, std::size_t size);
    template <class T>
    void put(const T& value) {
        if constexpr (std::is_trivially_copyable_v<T>) {
            bytes(&value, sizeof(T));
        } else {
            const_cast<T&>(value).transfer(*this);  // transfer() only reads when writing
        }
    }
    template <class T, class A>
    void put(const std::vector<T, A>& v) {
        put(static_cast<std::uint64_t>(v.size()));
        if constexpr (std::is_trivially_copyable_v<T>) {
            bytes(v.data(), v.size() * sizeof(T));
        } else {
            for (const T& e : v) put(e);
        }
    }
    void put(const std::string& s);

    std::filesystem::path path_, tmp_;
    std::FILE* file_ = nullptr;
    Checksum sum_;
};

class CheckpointIn {
  public:
    static constexpr bool reading = true;
    explicit CheckpointIn(std::filesystem::path path);
    ~CheckpointIn();
    CheckpointIn(const CheckpointIn&) = delete;
    CheckpointIn& operator=(const CheckpointIn&) = delete;
    template <class... T>
    void operator()(T&... values) {
        (get(values), ...);
    }
    [[nodiscard]] const std::filesystem::path& path() const { return path_; }
    // Throws InputError naming the file unless every byte was read.
    void expect_end();

  private:
    void bytes(void* data, std::size_t size);
    // a list's length, checked against what is left of the file (each element takes at least `bytes`)
    std::uint64_t count(std::size_t bytes = 1);
    template <class T>
    void get(T& value) {
        if constexpr (std::is_trivially_copyable_v<T>) {
            bytes(&value, sizeof(T));
        } else {
            value.transfer(*this);
        }
    }
    template <class T, class A>
    void get(std::vector<T, A>& v) {
        v.resize(count(std::is_trivially_copyable_v<T> ? sizeof(T) : 1));
        if constexpr (std::is_trivially_copyable_v<T>) {
            bytes(v.data(), v.size() * sizeof(T));
        } else {
            for (T& e : v) get(e);
        }
    }
    void get(std::string& s);

    std::filesystem::path path_;
    std::FILE* file_ = nullptr;
    std::uint64_t left_ = 0;
};

// The resolved case without its end time, its checkpoint and progress intervals, the lattice's device and
// comments: what a checkpoint is checked against when a run resumes (these may change: a run is continued
// further, on either backend: both hold the same state).
[[nodiscard]] std::string case_identity(const Config& cfg);
// Throws InputError naming the first line in which the checkpoint's case and this one differ (a key the
// user wrote before the [derived] values that follow from it).
void check_same_case(const std::filesystem::path& checkpoint, const std::string& stored,
                     const std::string& current);

}  // namespace sabo::io
