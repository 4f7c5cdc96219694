#pragma once
// The learned shape networks of the supplementary material, one set per class (chair, table), in
// libtorch on the CPU (torch stays inside the networks' module, src/makeway/neural/, opened on
// first use: perception/neural_module.hpp):
//
//  F_n  canonical correspondences: a PointNet over the object's points (per-point features and
//       their max-pooled global feature, concatenated, then an MLP) regresses each point's
//       coordinate v in the class's canonical frame and a confidence w; the 7-DoF similarity
//       follows from them by the weighted least squares of the init loss (similarity.hpp).
//  F_0  the category-level shape prior: a DeepSDF auto-decoder (eight fully connected layers,
//       softplus, the input concatenated again at the fifth) mapping a latent code z and a
//       canonical point to its signed distance; codes are fitted to a partial observation.
//  F_1  shape completion: a CONet-style 3D convolutional encoder over the TSDF volume (32
//       features per cell) and the weight volume (1), sampled trilinearly at a query point,
//       concatenated with F_0's code for the object and the point, through three fully connected
//       ResNet blocks to an occupancy logit.
//
// Frames. The input ("gravity") frame of an object: world axes, the origin on the floor under the
// centroid of the object's points. The canonical frame: the object's box centre at the origin,
// its axes (x forward, z up), lengths divided by the box's half diagonal, so the shape lies in
// the unit ball; T_gravity_canonical is a similarity (scale = the half diagonal).
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

#include "makeway/common/semantic_label.hpp"
#include "makeway/shape/similarity.hpp"
#include "makeway/shape/volume.hpp"

namespace makeway::shape {

constexpr int kLatentDim = 32;
using Latent = std::array<float, kLatentDim>;

/// The classes with shape networks (chair, table); index into per-class arrays.
/// -1 for a class without networks.
inline int shape_class_index(ObjectClass cls) {
    switch (cls) {
        case ObjectClass::kChair:
            return 0;
        case ObjectClass::kTable:
            return 1;
        default:
            return -1;
    }
}

struct ShapeModelParams {
    int points = 128;  ///< F_n's input size (clouds are resampled to it, seeded)
    int correspondence_width = 64;
    int sdf_width = 128;
    int occupancy_width = 64;
    CubeGrid grid{32, 1.1};  ///< F_1's TSDF volume over the canonical cube
    double truncation_cells = 2.5;
    double sdf_clamp = 0.1;  ///< DeepSDF's clamp (canonical units)
    std::uint64_t seed = 0;  ///< weight initialisation
};

/// F_n's answer for the points it saw (at most ShapeModelParams::points of the cloud).
struct Correspondences {
    std::vector<std::size_t> point;  ///< index into the input cloud
    std::vector<Eigen::Vector3d> canonical;
    std::vector<double> confidence;  ///< in (0, 1)
};

class ShapeModel {
  public:
    explicit ShapeModel(const ShapeModelParams& params = {});
    ~ShapeModel();
    ShapeModel(ShapeModel&&) noexcept;
    ShapeModel& operator=(ShapeModel&&) noexcept;

    /// Throws std::runtime_error naming the file on a missing, corrupt or foreign file.
    static ShapeModel load(const std::filesystem::path& path);
    /// Atomic (written beside, then renamed).
    void save(const std::filesystem::path& path) const;

    /// F_n on points of the gravity frame (any count >= 1; resampled to params().points, seeded).
    Correspondences correspond(ObjectClass cls,
                               const std::vector<Eigen::Vector3d>& points_gravity) const;
    /// F_n and the robust upright solve: T_gravity_canonical, or nullopt when the solve finds no
    /// support (or the class has no networks).
    std::optional<Similarity3> estimate_pose(ObjectClass cls,
                                             const std::vector<Eigen::Vector3d>& points_gravity,
                                             const RobustSolveParams& solve = {}) const;

    /// F_0: signed distances (canonical units) at canonical points for a code.
    std::vector<float> sdf(ObjectClass cls, const Latent& z,
                           const std::vector<Eigen::Vector3d>& points) const;
    /// F_0's code fitted to an observation: surface points (SDF 0) and free points (SDF >= the
    /// clamp) in the canonical frame, Adam on the code only, from the mean training code.
    Latent fit_latent(ObjectClass cls, const std::vector<Eigen::Vector3d>& surface,
                      const std::vector<Eigen::Vector3d>& free, int iterations = 60) const;
    /// F_1: occupancy probabilities at canonical points given the TSDF and weight volumes (on
    /// params().grid) and F_0's code.
    std::vector<float> occupancy(ObjectClass cls, const TsdfVolume& tsdf, const Latent& z,
                                 const std::vector<Eigen::Vector3d>& points) const;

    const ShapeModelParams& params() const { return params_; }
    std::size_t parameter_count() const;

    struct Impl;  ///< the networks (shape_backend.hpp), in the networks' module
    Impl& impl() const { return *impl_; }

  private:
    ShapeModel(const ShapeModelParams& params, std::unique_ptr<Impl> impl);
    ShapeModelParams params_;
    std::unique_ptr<Impl> impl_;
};

/// Threads torch, and the OpenBLAS under it, use for the shape networks in this process (0: leave
/// the default); perception::set_inference_threads.
void set_threads(int threads);

}  // namespace makeway::shape
