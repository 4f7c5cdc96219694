// The shape networks' facade: sampling and the robust solve here, the networks in the module
// (shape_backend.hpp).
#include "makeway/shape/shape_model.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "makeway/common/random.hpp"
#include "makeway/perception/detector.hpp"
#include "makeway/perception/model_archive.hpp"
#include "makeway/perception/neural_module.hpp"
#include "makeway/shape/shape_backend.hpp"

namespace makeway::shape {

const ShapeBackend& shape_backend() {
    static const ShapeBackend& backend = perception::neural_module_table<ShapeBackend>(
        "makeway_shape_backend", kShapeBackendAbi, "shape network");
    return backend;
}

void set_threads(int threads) {
    perception::set_inference_threads(threads);  // torch's and OpenBLAS's (its spinning pool)
}

ShapeModel::ShapeModel(const ShapeModelParams& params)
    : params_(params), impl_(shape_backend().create(params)) {}

ShapeModel::ShapeModel(const ShapeModelParams& params, std::unique_ptr<Impl> impl)
    : params_(params), impl_(std::move(impl)) {}

ShapeModel::~ShapeModel() = default;
ShapeModel::ShapeModel(ShapeModel&&) noexcept = default;
ShapeModel& ShapeModel::operator=(ShapeModel&&) noexcept = default;

std::size_t ShapeModel::parameter_count() const { return impl_->parameter_count(); }

void ShapeModel::save(const std::filesystem::path& path) const { impl_->save(path, params_); }

ShapeModel ShapeModel::load(const std::filesystem::path& path) {
    const std::string bytes = perception::read_checked_model_archive(path, "shape model");
    ShapeModelParams params;
    std::unique_ptr<Impl> impl = shape_backend().load(bytes, path, params);
    return ShapeModel(params, std::move(impl));
}

Correspondences ShapeModel::correspond(ObjectClass cls,
                                       const std::vector<Eigen::Vector3d>& points) const {
    Correspondences out;
    if (points.empty()) return out;
    if (shape_class_index(cls) < 0) throw std::invalid_argument("no shape networks for this class");
    // The network sees params().points points, as in training: a larger cloud is subsampled
    // (seeded by its size, so the same cloud gives the same answer), a smaller one repeated.
    const auto np = static_cast<std::size_t>(params_.points);
    std::vector<std::size_t> rows(np);
    if (points.size() > np) {
        std::vector<std::size_t> all(points.size());
        for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
        Rng rng = make_rng(points.size(), 29);
        for (std::size_t i = 0; i < np; ++i)
            std::swap(all[i], all[i + static_cast<std::size_t>(uniform_int(
                                          rng, 0, static_cast<std::int64_t>(all.size() - i - 1)))]);
        rows.assign(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(np));
    } else {
        for (std::size_t i = 0; i < np; ++i) rows[i] = i % points.size();
    }
    std::vector<Eigen::Vector3d> sample;
    sample.reserve(np);
    for (const std::size_t i : rows) sample.push_back(points[i]);
    const std::vector<float> t = impl_->correspond(cls, sample);  // 4 per point
    const float* d = t.data();
    const std::size_t count = std::min(np, points.size());
    for (std::size_t i = 0; i < count; ++i) {
        out.point.push_back(rows[i]);
        out.canonical.emplace_back(d[4 * i], d[4 * i + 1], d[4 * i + 2]);
        out.confidence.push_back(1.0 / (1.0 + std::exp(-static_cast<double>(d[4 * i + 3]))));
    }
    return out;
}

std::optional<Similarity3> ShapeModel::estimate_pose(ObjectClass cls,
                                                     const std::vector<Eigen::Vector3d>& points,
                                                     const RobustSolveParams& solve) const {
    if (shape_class_index(cls) < 0 || points.size() < 3) return std::nullopt;
    const Correspondences c = correspond(cls, points);
    std::vector<Eigen::Vector3d> observed;
    for (const std::size_t i : c.point) observed.push_back(points[i]);
    const auto r = solve_similarity_robust(c.canonical, observed, c.confidence, solve);
    if (!r) return std::nullopt;
    return r->similarity;
}

std::vector<float> ShapeModel::sdf(ObjectClass cls, const Latent& z,
                                   const std::vector<Eigen::Vector3d>& points) const {
    return impl_->sdf(cls, z, points);
}

Latent ShapeModel::fit_latent(ObjectClass cls, const std::vector<Eigen::Vector3d>& surface,
                              const std::vector<Eigen::Vector3d>& free, int iterations) const {
    return impl_->fit_latent(cls, surface, free, iterations, params_);
}

std::vector<float> ShapeModel::occupancy(ObjectClass cls, const TsdfVolume& tsdf, const Latent& z,
                                         const std::vector<Eigen::Vector3d>& points) const {
    return impl_->occupancy(cls, tsdf, z, points, params_);
}

}  // namespace makeway::shape
