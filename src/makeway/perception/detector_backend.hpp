#pragma once
// What Detector asks of its network: the contract between the program's facade (detector.cpp)
// and the module that holds the network in libtorch (neural/detector_net.cpp,
// neural_module.hpp). Only plain C++ types cross it; the module is built from the same sources,
// and the table says which interface it was built against.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "makeway/perception/detector.hpp"

namespace makeway::perception {

/// The network behind a Detector. Const methods are safe from several threads at once.
struct Detector::Impl {
    virtual ~Impl() = default;
    /// The activated head maps (channel-major, bev_grid.hpp) for a BEV grid encoded by
    /// encode_bev with params.grid.
    virtual std::vector<float> heads(const std::vector<float>& bev,
                                     const DetectorParams& params) const = 0;
    virtual std::size_t parameter_count() const = 0;
    /// The parameters and the weights, atomically (written beside, then renamed).
    virtual void save(const std::filesystem::path& path, const DetectorParams& params) const = 0;
};

/// Bumped whenever Detector::Impl or this table changes.
inline constexpr std::uint32_t kDetectorBackendAbi = 1;

struct DetectorBackend {
    std::uint32_t abi = kDetectorBackendAbi;
    std::uint32_t size = sizeof(DetectorBackend);
    /// A freshly initialised network (seeded with params.seed).
    std::unique_ptr<Detector::Impl> (*create)(const DetectorParams& params) = nullptr;
    /// A model file's bytes (passed model_archive_problem) -> its parameters and network; throws
    /// std::runtime_error naming `path`.
    std::unique_ptr<Detector::Impl> (*load)(const std::string& bytes,
                                            const std::filesystem::path& path,
                                            DetectorParams& params) = nullptr;
    /// train_detector's training of a Detector's network, made with `detector` (the facade has set
    /// the threads). The module never sees the facade itself.
    std::vector<EpochReport> (*train)(
        Detector::Impl& network, const DetectorParams& detector,
        const std::vector<TrainingSample>& samples, const TrainParams& params,
        const std::function<void(int, int, double)>& progress,
        const std::function<void(const EpochReport&)>& on_epoch) = nullptr;
};

/// The module's table, the module opened on first use (neural_module_symbol); throws
/// std::runtime_error when it cannot be opened or was built against another interface.
const DetectorBackend& detector_backend();

}  // namespace makeway::perception
