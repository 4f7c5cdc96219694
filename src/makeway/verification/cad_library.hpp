#pragma once
// CAD models for verification: each mesh densely sampled into surface points with normals, thinned
// on voxel grids of several sizes (one per coarse-to-fine level), each with a k-d tree (nanoflann).
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "makeway/common/oriented_box.hpp"
#include "makeway/common/semantic_label.hpp"
#include "makeway/common/transforms.hpp"
#include "makeway/common/triangle_mesh.hpp"
#include "makeway/verification/closest_point_grid.hpp"

namespace makeway::verification {

struct ModelLevel {
    double voxel_m = 0.0;
    std::vector<Eigen::Vector3d> points_object;
    std::vector<Eigen::Vector3d> normals_object;
    struct Index;
    std::shared_ptr<const Index> index;  ///< k-d tree over points_object
    std::shared_ptr<const ClosestPointGrid>
        grid;  ///< optional lookup near the model (null: k-d tree only)
    static constexpr std::size_t kNone = static_cast<std::size_t>(-1);
    /// Index of the nearest model point within max_distance_m [m] of q (object frame) and its
    /// squared distance, or kNone (distance2 = inf) when there is none that close. Inside the
    /// lookup grid the answer is the nearest point of q's cell centre (see ClosestPointGrid).
    std::size_t nearest(const Eigen::Vector3d& q, double max_distance_m, double* distance2) const;
    /// The same from one grid read: the point q's lookup cell holds (at most two cell diagonals
    /// farther from q than the nearest point); the k-d tree off the grid.
    std::size_t nearest_cell(const Eigen::Vector3d& q, double max_distance_m,
                             double* distance2) const;
};

struct CadModel {
    std::string name;
    ObjectClass cls = ObjectClass::kChair;
    OrientedBox box_object;          ///< extent of the mesh in the object frame
    std::vector<ModelLevel> levels;  ///< coarse to fine
    /// Whether turning the model by k quarter turns about its box centre's vertical axis leaves its
    /// surface in place (k = 0 always; a rectangular table k = 2; a round one every k): yaw
    /// candidates that differ by such a turn are the same fit, not rivals.
    std::array<bool, 4> quarter_turn_symmetric{true, false, false, false};
};

struct CadLibraryParams {
    std::vector<double> voxel_sizes_m{0.08, 0.04, 0.02};  ///< one level each, coarse to fine
    double sample_spacing_m = 0.01;                       ///< surface sampling before thinning
    /// Closest-point lookup grids, one entry per level (coarse to fine), reaching this far around
    /// the model [m] (the ICP's correspondence distances); queries beyond, and levels without an
    /// entry, use the exact k-d tree. The finest level has one too: every accepted fit is refined
    /// and judged there, and its k-d tree took 12 % of a study-space run's CPU (issue 31).
    std::vector<double> lookup_margin_m{0.30, 0.15, 0.08};
    /// Grid cell size / level voxel size, one per lookup grid. The finest level's cells are as
    /// large as its voxels: half of that took 3-4x a model's memory (a conference table 19 MB
    /// against 6.5) and fitted no better (`bench verify`: yaw within 10 deg 90.1 % against 91.0 %).
    std::vector<double> lookup_cell_fraction{0.5, 0.5, 1.0};
    /// A quarter turn is a symmetry when the finest level's points, turned, lie within this RMS
    /// distance of the model [m].
    double symmetry_rms_m = 0.015;
    std::uint64_t seed = 0;
    std::vector<std::string> validate() const;
};

class CadLibrary {
  public:
    explicit CadLibrary(const CadLibraryParams& params = {}) : params_(params) {}
    /// Samples and indexes a mesh given in its object frame (origin on the floor, x forward).
    void add(const std::string& name, ObjectClass cls, const TriangleMesh& mesh_object);
    const std::vector<CadModel>& models() const { return models_; }
    std::vector<const CadModel*> models_of(ObjectClass cls) const;
    /// A library of the one model at `index` (shares its sampled points and indices: cheap), for
    /// callers that rank models by more than the residual.
    CadLibrary only(std::size_t index) const;
    const CadLibraryParams& params() const { return params_; }

  private:
    CadLibraryParams params_;
    std::vector<CadModel> models_;
};

}  // namespace makeway::verification
