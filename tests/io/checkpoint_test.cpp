// SPDX-License-Identifier: MIT
#include "io/checkpoint.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/vec3.h"

using sabo::InputError;
using sabo::Vec3;
using sabo::io::CheckpointIn;
using sabo::io::CheckpointOut;
using sabo::io::Checksum;

namespace {

// A nested object with its own transfer() list, as the run's objects have.
struct Record {
    double time = 0.0;
    std::string name;
    std::vector<Vec3> forces;
    template <class Archive>
    void transfer(Archive& a) {
        a(time, name, forces);
    }
};

std::filesystem::path temp_file(const std::string& name) {
    return std::filesystem::temp_directory_path() / ("sabo_checkpoint_test_" + name);
}

void write_sample(const std::filesystem::path& path) {
    CheckpointOut out(path);
    std::uint64_t steps = 1234;
    std::vector<float> f{1.5f, -2.25f, 3.0f};
    std::vector<Record> records{{0.5, "first", {{1, 2, 3}}}, {1.5, "second", {}}};
    out(steps, f, records);
    out.commit();
}

}  // namespace

// What goes in comes out, nested objects and strings included; every byte is read.
TEST(Checkpoint, RoundTripsScalarsVectorsStringsAndNestedObjects) {
    const auto path = temp_file("roundtrip");
    write_sample(path);
    EXPECT_FALSE(std::filesystem::exists(path.string() + ".tmp"));
    CheckpointIn in(path);
    std::uint64_t steps = 0;
    std::vector<float> f;
    std::vector<Record> records;
    in(steps, f, records);
    in.expect_end();
    EXPECT_EQ(steps, 1234u);
    EXPECT_EQ(f, (std::vector<float>{1.5f, -2.25f, 3.0f}));
    ASSERT_EQ(records.size(), 2u);
    EXPECT_EQ(records[0].name, "first");
    EXPECT_EQ(records[0].forces.size(), 1u);
    EXPECT_EQ(records[0].forces[0].z, 3.0);
    EXPECT_EQ(records[1].time, 1.5);
    std::filesystem::remove(path);
}

// A truncated file, a file of another kind, and leftover bytes (another layout) are refused by name.
TEST(Checkpoint, RefusesTruncatedForeignAndLongerFiles) {
    const auto path = temp_file("bad");
    write_sample(path);
    const auto size = std::filesystem::file_size(path);
    std::filesystem::resize_file(path, size - 5);  // cut short: the checksum no longer matches
    EXPECT_THROW(CheckpointIn{path}, InputError);
    write_sample(path);
    {  // one bit changed in the middle
        std::FILE* file = std::fopen(path.c_str(), "r+b");
        std::fseek(file, static_cast<long>(size / 2), SEEK_SET);
        const int c = std::fgetc(file);
        std::fseek(file, static_cast<long>(size / 2), SEEK_SET);
        std::fputc(c ^ 1, file);
        std::fclose(file);
        EXPECT_THROW(CheckpointIn{path}, InputError);
    }
    write_sample(path);
    {  // the reader expects less than the file holds
        CheckpointIn in(path);
        std::uint64_t steps = 0;
        in(steps);
        EXPECT_THROW(in.expect_end(), InputError);
    }
    {
        std::FILE* file = std::fopen(path.c_str(), "wb");
        std::fputs("not a checkpoint at all", file);
        std::fclose(file);
        EXPECT_THROW(CheckpointIn{path}, InputError);
    }
    std::filesystem::remove(path);
}

// The checksum does not depend on how the stream was cut into pieces.
TEST(Checkpoint, ChecksumOfPiecesIsTheChecksumOfTheWhole) {
    std::vector<unsigned char> bytes(1000);
    for (std::size_t k = 0; k < bytes.size(); ++k) bytes[k] = static_cast<unsigned char>(k * 37 + 11);
    Checksum whole;
    whole.add(bytes.data(), bytes.size());
    for (const std::size_t piece : {1u, 3u, 7u, 8u, 13u, 999u}) {
        Checksum pieces;
        for (std::size_t at = 0; at < bytes.size(); at += piece)
            pieces.add(bytes.data() + at, std::min(piece, bytes.size() - at));
        EXPECT_EQ(pieces.value(), whole.value()) << piece;
    }
    Checksum shorter;
    shorter.add(bytes.data(), bytes.size() - 1);
    EXPECT_NE(shorter.value(), whole.value());
}

// An uncommitted writer (a run that failed while writing) leaves the previous checkpoint whole.
TEST(Checkpoint, UncommittedWriteKeepsThePreviousFile) {
    const auto path = temp_file("keep");
    write_sample(path);
    const auto size = std::filesystem::file_size(path);
    {
        CheckpointOut out(path);
        std::uint64_t junk = 7;
        out(junk);
    }  // destroyed without commit()
    EXPECT_EQ(std::filesystem::file_size(path), size);
    EXPECT_FALSE(std::filesystem::exists(path.string() + ".tmp"));
    std::filesystem::remove(path);
}
