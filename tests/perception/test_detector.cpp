#include <dlfcn.h>
#include <gtest/gtest.h>

#include <fstream>
#include <thread>

#include "../io/io_test_util.hpp"
#include "makeway/common/random.hpp"
#include "makeway/perception/detector.hpp"
#include "makeway/perception/neural_module.hpp"

namespace makeway::perception {
namespace {

// A small grid keeps the tests fast.
DetectorParams small_params() {
    DetectorParams p;
    p.grid.range_m = 3.2;
    p.width = 8;
    return p;
}

// Synthetic keyframes: chair-like point blocks (legs and a back) and table-like slabs.
std::vector<PointCloud> clouds;
std::vector<TrainingSample> synthetic_set(int n, std::uint64_t seed) {
    Rng rng = make_rng(seed);
    clouds.assign(static_cast<std::size_t>(n), {});
    std::vector<TrainingSample> out;
    for (int k = 0; k < n; ++k) {
        PointCloud& c = clouds[static_cast<std::size_t>(k)];
        TrainingSample s;
        for (int o = 0; o < 3; ++o) {
            const bool chair = o < 2;
            const Eigen::Vector3d size =
                chair ? Eigen::Vector3d(0.5, 0.5, 0.9) : Eigen::Vector3d(1.2, 0.7, 0.75);
            const OrientedBox b{
                {uniform(rng, -2.2, 2.2), uniform(rng, -2.2, 2.2), -0.45 + size.z() / 2},
                size,
                uniform(rng, -3.1, 3.1)};
            for (int i = 0; i < 150; ++i) {
                const Eigen::Vector3d local(
                    uniform(rng, -0.5, 0.5) * size.x(), uniform(rng, -0.5, 0.5) * size.y(),
                    chair ? uniform(rng, -0.5, 0.5) * size.z() : 0.45 * size.z());
                const Eigen::Vector3d p = b.T_frame_box() * local;
                c.xyz.push_back(p.cast<float>());
                c.intensity.push_back(0.5f);
            }
            s.boxes.emplace_back(chair ? ObjectClass::kChair : ObjectClass::kTable, b);
        }
        s.cloud_sensor = &c;
        out.push_back(s);
    }
    return out;
}

TEST(Detector, TrainingOnATinySetLowersTheLoss) {
    Detector det(small_params());
    const auto samples = synthetic_set(8, 3);
    TrainParams tp;
    tp.epochs = 12;
    tp.batch_size = 4;
    tp.learning_rate = 5e-3;
    const auto reports = train_detector(det, samples, tp);
    ASSERT_EQ(reports.size(), 12u);
    EXPECT_LT(reports.back().mean_loss, 0.6 * reports.front().mean_loss)
        << reports.front().mean_loss << " -> " << reports.back().mean_loss;
    EXPECT_TRUE(std::isfinite(reports.back().mean_loss));
}

TEST(Detector, SaveAndLoadReproduceIdenticalOutputs) {
    Detector det(small_params());
    const auto samples = synthetic_set(2, 4);
    train_detector(det, samples, {.epochs = 1, .batch_size = 2});
    const auto dir = testing_util::fresh_dir("detector");
    det.save(dir / "model.pt");
    const Detector back = Detector::load(dir / "model.pt");
    EXPECT_EQ(back.params().grid.cells(), det.params().grid.cells());
    EXPECT_EQ(back.heads(clouds[0]), det.heads(clouds[0]));
    EXPECT_GT(det.parameter_count(), 1000u);
    // Bad files: one error naming the file.
    std::ofstream(dir / "junk.pt") << "not a model";
    for (const auto& bad : {dir / "junk.pt", dir / "missing.pt"}) {
        try {
            Detector::load(bad);
            ADD_FAILURE() << bad;
        } catch (const std::runtime_error& e) {
            EXPECT_EQ(std::string(e.what()).rfind(bad.string(), 0), 0u) << e.what();
        }
    }
}

TEST(Detector, SharedByThreadsGivesTheSerialAnswers) {
    // `bench nav` runs navigation in parallel with one detector: detect() is documented safe from
    // several threads (the network is in eval mode, nothing writes to it). `make tsan` runs this.
    set_inference_threads(1);
    const Detector detector(small_params());
    synthetic_set(4, 9);
    std::vector<std::vector<float>> serial;
    for (const PointCloud& c : clouds) serial.push_back(detector.heads(c));
    std::vector<int> mismatches(3, 0);
    std::vector<std::thread> threads;
    for (int t = 0; t < 3; ++t) {
        threads.emplace_back([&, t] {
            for (int round = 0; round < 2; ++round) {
                for (std::size_t k = 0; k < clouds.size(); ++k)
                    mismatches[static_cast<std::size_t>(t)] +=
                        detector.heads(clouds[k]) != serial[k];
            }
        });
    }
    for (auto& th : threads) th.join();
    EXPECT_EQ(mismatches, std::vector<int>(3, 0));
}

// The network is the module's (neural_module.hpp), opened with its libraries kept local: the thread
// count must still reach the OpenBLAS under torch, whose spinning pool took a core from
// verification when it was left at a thread per core (set before the module opens and after).
TEST(Detector, InferenceThreadsReachTheModulesOpenBlas) {
    set_inference_threads(1);
    const Detector detector(small_params());
    EXPECT_NE(neural_module_path().find(kNeuralModuleFile), std::string::npos);
    void* blas = dlopen("libopenblas.so.0", RTLD_NOW | RTLD_NOLOAD);
    if (blas == nullptr) GTEST_SKIP() << "torch is not on OpenBLAS here";
    using GetThreads = int (*)();
    const auto get = reinterpret_cast<GetThreads>(dlsym(blas, "openblas_get_num_threads"));
    ASSERT_NE(get, nullptr);
    EXPECT_EQ(get(), 1);
    set_inference_threads(2);
    EXPECT_GE(get(), std::min(2, static_cast<int>(std::thread::hardware_concurrency())));
    set_inference_threads(1);
    EXPECT_EQ(get(), 1);
    dlclose(blas);
}

// bench nav leaves the simulated intensity out when the detector says it reads none: the flag must
// tell the truth. Without the channel the heads ignore intensity; with it they change with it.
TEST(Detector, SaysWhetherItReadsIntensity) {
    synthetic_set(1, 5);
    PointCloud with = clouds[0];
    with.intensity.assign(with.size(), 0.0f);
    for (std::size_t i = 0; i < with.size(); ++i) with.intensity[i] = static_cast<float>(i % 200);
    PointCloud without = clouds[0];
    without.intensity.clear();
    ASSERT_GT(with.size(), 50u);
    const Detector plain(small_params());
    EXPECT_FALSE(plain.uses_intensity());
    EXPECT_EQ(plain.heads(with), plain.heads(without));
    DetectorParams p = small_params();
    p.grid.intensity = true;
    const Detector reading(p);
    EXPECT_TRUE(reading.uses_intensity());
    EXPECT_NE(reading.heads(with), reading.heads(without));
}

TEST(Detector, EmptyCloudGivesNoDetections) {
    const Detector det(small_params());
    EXPECT_TRUE(
        det.detect(PointCloud{}).empty());  // fresh heatmaps start at 0.1, below the threshold
}

}  // namespace
}  // namespace makeway::perception
