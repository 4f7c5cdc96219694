#include "makeway/verification/cad_library.hpp"

#include <cmath>
#include <limits>
#include <map>
#include <nanoflann.hpp>
#include <tuple>

#include "makeway/common/angles.hpp"
#include "makeway/common/random.hpp"

namespace makeway::verification {

struct ModelLevel::Index {
    struct Adaptor {
        const std::vector<Eigen::Vector3d>* pts;
        std::size_t kdtree_get_point_count() const { return pts->size(); }
        double kdtree_get_pt(std::size_t i, std::size_t d) const {
            return (*pts)[i][static_cast<int>(d)];
        }
        template <class Bbox>
        bool kdtree_get_bbox(Bbox&) const {
            return false;
        }
    };
    using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Adaptor>,
                                                     Adaptor, 3, std::size_t>;
    explicit Index(const std::vector<Eigen::Vector3d>& points)
        : owned(points),
          adaptor{&owned},
          tree(3, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(10)) {}
    std::vector<Eigen::Vector3d> owned;
    Adaptor adaptor;
    Tree tree;
};

namespace {

// A grid's answer j at squared distance d2, or kNone (distance2 = inf) past max_distance_m.
std::size_t within_reach(std::size_t j, double d2, double max_distance_m, double* distance2) {
    const bool near = d2 <= max_distance_m * max_distance_m;
    if (distance2) *distance2 = near ? d2 : std::numeric_limits<double>::infinity();
    return near ? j : ModelLevel::kNone;
}

}  // namespace

std::size_t ModelLevel::nearest_cell(const Eigen::Vector3d& q, double max_distance_m,
                                     double* distance2) const {
    if (grid) {
        const std::uint32_t j = grid->lookup(q);
        if (j != ClosestPointGrid::kOutside)
            return within_reach(j, (points_object[j] - q).squaredNorm(), max_distance_m, distance2);
    }
    return nearest(q, max_distance_m, distance2);
}

std::size_t ModelLevel::nearest(const Eigen::Vector3d& q, double max_distance_m,
                                double* distance2) const {
    // A 1-NN search whose ball starts at max_distance: branches farther away are never visited.
    if (grid) {
        double d2 = 0.0;
        const std::uint32_t j = grid->nearest(q, points_object, &d2);
        if (j != ClosestPointGrid::kOutside) return within_reach(j, d2, max_distance_m, distance2);
    }
    std::size_t idx = kNone;
    double d2 = 0.0;
    nanoflann::KNNResultSet<double, std::size_t> found(1);
    found.init(&idx, &d2);
    d2 = max_distance_m * max_distance_m;
    index->tree.findNeighbors(found, q.data(), nanoflann::SearchParams());
    if (found.size() == 0) idx = kNone;
    if (distance2) *distance2 = idx == kNone ? std::numeric_limits<double>::infinity() : d2;
    return idx;
}

std::vector<std::string> CadLibraryParams::validate() const {
    std::vector<std::string> p;
    if (voxel_sizes_m.empty() || voxel_sizes_m.size() > 6)
        p.push_back("voxel_sizes_m must hold 1..6 sizes");
    for (double v : voxel_sizes_m) {
        if (!(v > 0.0 && v < 1.0)) p.push_back("voxel sizes must be in (0, 1)");
    }
    if (!(sample_spacing_m > 0.0 && sample_spacing_m < 0.5))
        p.push_back("sample_spacing_m must be in (0, 0.5)");
    if (lookup_margin_m.size() > voxel_sizes_m.size())
        p.push_back("lookup_margin_m has more entries than voxel_sizes_m");
    for (double m : lookup_margin_m) {
        if (!(m >= 0.0 && m <= 1.0)) p.push_back("lookup margins must be in [0, 1] m");
    }
    if (lookup_cell_fraction.size() < lookup_margin_m.size())
        p.push_back("lookup_cell_fraction needs an entry per lookup margin");
    for (double f : lookup_cell_fraction) {
        if (!(f >= 0.1 && f <= 2.0))
            p.push_back("lookup_cell_fraction entries must be in [0.1, 2]");
    }
    return p;
}

void CadLibrary::add(const std::string& name, ObjectClass cls, const TriangleMesh& mesh) {
    CadModel model;
    model.name = name;
    model.cls = cls;
    // Dense area-weighted surface samples with their triangle normals.
    Rng rng = make_rng(params_.seed, 41 + models_.size());
    std::vector<Eigen::Vector3d> pts, nrm;
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e9), hi = -lo;
    for (const auto& t : mesh.triangles) {
        const Eigen::Vector3d a = mesh.vertices_m[t[0]].cast<double>(),
                              b = mesh.vertices_m[t[1]].cast<double>(),
                              c = mesh.vertices_m[t[2]].cast<double>();
        lo = lo.cwiseMin(a).cwiseMin(b).cwiseMin(c);
        hi = hi.cwiseMax(a).cwiseMax(b).cwiseMax(c);
        const Eigen::Vector3d cr = (b - a).cross(c - a);
        const double area = 0.5 * cr.norm();
        if (area < 1e-12) continue;
        const Eigen::Vector3d n = cr.normalized();
        const double expected = area / (params_.sample_spacing_m * params_.sample_spacing_m);
        auto count = static_cast<int>(expected);
        if (uniform(rng, 0, 1) < expected - count) ++count;
        for (int i = 0; i < count; ++i) {
            double u = uniform(rng, 0, 1), v = uniform(rng, 0, 1);
            if (u + v > 1) u = 1 - u, v = 1 - v;
            pts.push_back(a + u * (b - a) + v * (c - a));
            nrm.push_back(n);
        }
    }
    model.box_object.centre_m = 0.5 * (lo + hi);
    model.box_object.size_m = hi - lo;
    // One voxel-thinned level per size: the sample nearest each voxel's centre survives.
    for (std::size_t l = 0; l < params_.voxel_sizes_m.size(); ++l) {
        const double voxel = params_.voxel_sizes_m[l];
        std::map<std::tuple<long, long, long>, std::size_t> cells;
        for (std::size_t i = 0; i < pts.size(); ++i) {
            const auto key = std::make_tuple(std::lround(std::floor(pts[i].x() / voxel)),
                                             std::lround(std::floor(pts[i].y() / voxel)),
                                             std::lround(std::floor(pts[i].z() / voxel)));
            const Eigen::Vector3d centre =
                (Eigen::Vector3d(std::get<0>(key), std::get<1>(key), std::get<2>(key)) +
                 Eigen::Vector3d::Constant(0.5)) *
                voxel;
            auto [it, inserted] = cells.emplace(key, i);
            if (!inserted &&
                (pts[i] - centre).squaredNorm() < (pts[it->second] - centre).squaredNorm())
                it->second = i;
        }
        ModelLevel level;
        level.voxel_m = voxel;
        for (const auto& [key, i] : cells) {
            level.points_object.push_back(pts[i]);
            level.normals_object.push_back(nrm[i]);
        }
        level.index = std::make_shared<ModelLevel::Index>(level.points_object);
        if (l < params_.lookup_margin_m.size() &&
            l < params_.lookup_cell_fraction.size()) {  // validate() says when not
            level.grid = std::make_shared<ClosestPointGrid>(level.points_object,
                                                            params_.lookup_cell_fraction[l] * voxel,
                                                            params_.lookup_margin_m[l]);
        }
        model.levels.push_back(std::move(level));
    }
    if (!model.levels.empty()) {
        const ModelLevel& fine = model.levels.back();
        const Eigen::Vector3d c(model.box_object.centre_m.x(), model.box_object.centre_m.y(), 0.0);
        for (int k = 1; k < 4; ++k) {
            const Eigen::Matrix3d R =
                Eigen::AngleAxisd(k * kPi / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
            const double cap_m = 0.2;
            double sum2 = 0.0;
            for (const auto& p : fine.points_object) {
                double d2 = 0.0;
                (void)fine.nearest(c + R * (p - c), cap_m, &d2);
                sum2 += std::min(d2, cap_m * cap_m);
            }
            model.quarter_turn_symmetric[static_cast<std::size_t>(k)] =
                !fine.points_object.empty() &&
                std::sqrt(sum2 / static_cast<double>(fine.points_object.size())) <=
                    params_.symmetry_rms_m;
        }
    }
    models_.push_back(std::move(model));
}

CadLibrary CadLibrary::only(std::size_t index) const {
    CadLibrary one(params_);
    one.models_.push_back(models_.at(index));
    return one;
}

std::vector<const CadModel*> CadLibrary::models_of(ObjectClass cls) const {
    std::vector<const CadModel*> out;
    for (const auto& m : models_) {
        if (m.cls == cls) out.push_back(&m);
    }
    return out;
}

}  // namespace makeway::verification
