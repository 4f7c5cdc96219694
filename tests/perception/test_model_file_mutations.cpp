// The model-file loader against corrupted files (issue 14): a mutation fuzzer with a fixed seed.
// libFuzzer cannot drive torch (the clang fuzz build has no libtorch; fuzz_model_archive covers
// the container check in front of it), so every run of the tests (ASan included) loads a thousand
// damaged copies of a real model file: truncated, bits
// flipped, sizes and offsets overwritten with extremes, chunks deleted or repeated. Each one must
// load (and then detect without crashing) or be refused with an error naming the file.
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <iostream>
#include <iterator>
#include <random>

#include "../io/io_test_util.hpp"
#include "makeway/perception/detector.hpp"

namespace makeway::perception {
namespace {

std::string slurp(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

std::string mutate(std::string bytes, std::mt19937& rng) {
    const auto pick = [&](std::size_t n) {
        return std::uniform_int_distribution<std::size_t>(0, n - 1)(rng);
    };
    switch (pick(5)) {
        case 0:  // truncated
            bytes.resize(pick(bytes.size()));
            break;
        case 1:  // bits flipped
            for (std::size_t k = 0, n = 1 + pick(16); k < n; ++k)
                bytes[pick(bytes.size())] ^= static_cast<char>(1u << pick(8));
            break;
        case 2: {  // a 2/4/8-byte field (a zip size, an offset, a tensor length) set to an extreme
            const std::uint64_t extremes[] = {0, 0xFFFFFFFFFFFFFFFFull, 0x7FFFFFFFull,
                                              0x80000000ull, 0xFFFFull};
            const std::uint64_t v = extremes[pick(5)];
            const std::size_t width = std::size_t{2} << pick(3);
            const std::size_t at = pick(bytes.size() - width);
            std::memcpy(bytes.data() + at, &v, width);
            break;
        }
        case 3: {  // a chunk deleted
            const std::size_t at = pick(bytes.size());
            bytes.erase(at, std::min(bytes.size() - at, 1 + pick(512)));
            break;
        }
        default: {  // a chunk repeated
            const std::size_t at = pick(bytes.size());
            bytes.insert(at, bytes.substr(at, 1 + pick(512)));
            break;
        }
    }
    return bytes;
}

TEST(ModelFile, DamagedFilesLoadOrAreRefusedByName) {
    const auto dir = testing_util::fresh_dir("mutations");
    DetectorParams p;
    p.grid.range_m = 3.2;
    p.width = 4;
    Detector(p).save(dir / "good.pt");
    const std::string good = slurp(dir / "good.pt");
    ASSERT_GT(good.size(), 1000u);
    PointCloud cloud;
    for (int i = 0; i < 200; ++i) cloud.xyz.emplace_back(0.01f * i - 1.0f, 0.5f, 0.3f);
    cloud.intensity.assign(cloud.size(), 10.0f);

    constexpr int kMutations = 1000;
    const std::vector<float> reference = Detector::load(dir / "good.pt").heads(cloud);
    std::mt19937 rng(0);
    const auto path = dir / "damaged.pt";
    int refused = 0, loaded = 0;
    for (int k = 0; k < kMutations; ++k) {
        const std::string bytes = mutate(good, rng);
        std::ofstream(path, std::ios::binary | std::ios::trunc)
            .write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
        try {
            const Detector d = Detector::load(path);
            ++loaded;
            // Damage outside the records (padding, a comment) is harmless: the network is intact.
            EXPECT_EQ(d.heads(cloud), reference)
                << "mutation " << k << " loaded a different network";
        } catch (const std::runtime_error& e) {
            ++refused;
            EXPECT_EQ(std::string(e.what()).rfind(path.string() + ": ", 0), 0u)
                << "mutation " << k << ": " << e.what();
            EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos)
                << "mutation " << k << ": one line";
        }
    }
    // Every record carries a CRC-32: damage to a record is refused. Before the archive check, 22 %
    // of these loaded (altered weights included) and mutation 430 crashed torch after it asked
    // for 43 GB.
    EXPECT_GT(refused, kMutations * 9 / 10);
    std::cout << "[          ] " << kMutations << " damaged model files: " << refused
              << " refused, " << loaded << " loaded\n";
}

}  // namespace
}  // namespace makeway::perception
