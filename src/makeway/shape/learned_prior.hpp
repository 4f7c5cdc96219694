#pragma once
// The shape networks as verification's prior (verification/shape_prior.hpp): F_n poses the
// segment (upright 7-DoF solve), F_0's code is fitted to it and F_1 completes it; the completed
// mesh, scaled back to metres and stood on the floor, is the model ICP then aligns and scores.
#include <memory>

#include "makeway/shape/shape_completion.hpp"
#include "makeway/verification/shape_prior.hpp"

namespace makeway::shape {

struct LearnedPriorParams {
    double ground_band_m =
        0.05;  ///< segment points this close to the floor are left out (as in training)
    std::size_t min_points = 30;
    /// Online: F_0's mean code (no fit), F_1 queried on 24^3 cells, no prior field.
    CompletionParams completion{.fit_iterations = 0,
                                .fit_points = 192,
                                .free_offset = 0.15,
                                .prior_field = false,
                                .mesh_resolution = 24};
    RobustSolveParams solve;
};

class LearnedShapePrior : public verification::ShapePrior {
  public:
    LearnedShapePrior(std::shared_ptr<const ShapeModel> model,
                      const LearnedPriorParams& params = {});
    std::optional<Estimate> estimate(const std::vector<Eigen::Vector3d>& segment_sensor,
                                     ObjectClass cls, double floor_z_m) const override;
    /// The views back in the canonical frame, fused into one TSDF, and F_1's shape of all of them.
    std::optional<TriangleMesh> complete(const std::vector<View>& views, ObjectClass cls,
                                         double scale,
                                         const Eigen::Vector3d& offset_m) const override;

  private:
    std::shared_ptr<const ShapeModel> model_;
    LearnedPriorParams params_;
};

}  // namespace makeway::shape
