// Weighted Umeyama (full and upright) and its sample-and-refine wrapper.
#include "makeway/shape/similarity.hpp"

#include <Eigen/SVD>
#include <cmath>

#include "makeway/common/random.hpp"
#include "makeway/common/transforms.hpp"

namespace makeway::shape {

double Similarity3::yaw_rad() const { return yaw_of(rotation); }

std::optional<Similarity3> solve_similarity(const std::vector<Eigen::Vector3d>& v,
                                            const std::vector<Eigen::Vector3d>& p,
                                            const std::vector<double>& w, bool upright) {
    if (v.size() != p.size() || v.size() != w.size()) return std::nullopt;
    double wsum = 0.0;
    std::size_t carrying = 0;
    Eigen::Vector3d vbar = Eigen::Vector3d::Zero(), pbar = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < v.size(); ++i) {
        if (!(w[i] >= 0.0) || !std::isfinite(w[i]) || !v[i].allFinite() || !p[i].allFinite())
            return std::nullopt;
        if (w[i] == 0.0) continue;
        ++carrying;
        wsum += w[i];
        vbar += w[i] * v[i];
        pbar += w[i] * p[i];
    }
    if (carrying < (upright ? 2u : 3u) || !(wsum > 0.0)) return std::nullopt;
    vbar /= wsum;
    pbar /= wsum;
    Eigen::Matrix3d S = Eigen::Matrix3d::Zero();  // sum w (p - pbar)(v - vbar)^T
    double var_v = 0.0;
    for (std::size_t i = 0; i < v.size(); ++i) {
        if (w[i] == 0.0) continue;
        const Eigen::Vector3d dv = v[i] - vbar;
        S += w[i] * (p[i] - pbar) * dv.transpose();
        var_v += w[i] * dv.squaredNorm();
    }
    if (!(var_v > 1e-12 * wsum)) return std::nullopt;
    Similarity3 out;
    double trace = 0.0;  // tr(R^T S) = sum w (p - pbar) . R (v - vbar)
    if (upright) {
        // Only the xy block depends on the yaw: maximise cos(y)(Sxx + Syy) + sin(y)(Syx - Sxy).
        const double c = S(0, 0) + S(1, 1), s = S(1, 0) - S(0, 1);
        if (std::hypot(c, s) < 1e-12 * wsum) return std::nullopt;  // no horizontal extent
        const double yaw = std::atan2(s, c);
        out.rotation = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
        trace = (out.rotation.transpose() * S).trace();
    } else {
        const Eigen::JacobiSVD<Eigen::Matrix3d> svd(S, Eigen::ComputeFullU | Eigen::ComputeFullV);
        const Eigen::Vector3d sv = svd.singularValues();
        if (sv(1) < 1e-9 * sv(0) || !(sv(0) > 0.0)) return std::nullopt;  // collinear
        Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
        if ((svd.matrixU() * svd.matrixV().transpose()).determinant() < 0.0) D(2, 2) = -1.0;
        out.rotation = svd.matrixU() * D * svd.matrixV().transpose();
        trace = (sv.asDiagonal() * D).trace();
    }
    out.scale = trace / var_v;
    if (!(out.scale > 0.0)) return std::nullopt;
    out.translation = pbar - out.scale * (out.rotation * vbar);
    return out;
}

std::optional<RobustSolveResult> solve_similarity_robust(const std::vector<Eigen::Vector3d>& v,
                                                         const std::vector<Eigen::Vector3d>& p,
                                                         const std::vector<double>& w,
                                                         const RobustSolveParams& params) {
    if (v.size() != p.size() || v.size() != w.size()) return std::nullopt;
    std::vector<std::size_t> usable;
    for (std::size_t i = 0; i < v.size(); ++i) {
        if (w[i] > 0.0 && std::isfinite(w[i]) && v[i].allFinite() && p[i].allFinite())
            usable.push_back(i);
    }
    const std::size_t minimal = params.upright ? 2 : 3;
    if (usable.size() < 3) return std::nullopt;
    if (params.hypotheses <= 0) {  // the weighted least squares alone
        const auto all = solve_similarity(v, p, w, params.upright);
        if (!all) return std::nullopt;
        RobustSolveResult out;
        out.similarity = *all;
        out.inlier.assign(v.size(), false);
        for (const std::size_t i : usable) out.inlier[i] = true;
        out.inliers = usable.size();
        return out;
    }
    const double d2 = params.inlier_distance * params.inlier_distance;
    auto support = [&](const Similarity3& T, std::vector<bool>* inlier) {
        double score = 0.0;
        std::size_t count = 0;
        if (inlier) inlier->assign(v.size(), false);
        for (const std::size_t i : usable) {
            if ((T.apply(v[i]) - p[i]).squaredNorm() <= d2) {
                score += w[i];
                ++count;
                if (inlier) (*inlier)[i] = true;
            }
        }
        return std::make_pair(score, count);
    };
    Rng rng = make_rng(params.seed, 19);
    std::optional<Similarity3> best;
    double best_score = -1.0;
    std::vector<Eigen::Vector3d> sv(minimal), sp(minimal);
    const std::vector<double> sw(minimal, 1.0);
    const auto last = static_cast<std::int64_t>(usable.size()) - 1;
    for (int h = 0; h < params.hypotheses; ++h) {
        for (std::size_t k = 0; k < minimal; ++k) {
            const std::size_t i = usable[static_cast<std::size_t>(uniform_int(rng, 0, last))];
            sv[k] = v[i];
            sp[k] = p[i];
        }
        const auto T = solve_similarity(sv, sp, sw, params.upright);
        if (!T || T->scale < params.min_scale || T->scale > params.max_scale) continue;
        const double score = support(*T, nullptr).first;
        if (score > best_score) best_score = score, best = T;
    }
    // The whole weighted set as one more hypothesis: with no outliers it is the answer.
    if (const auto all = solve_similarity(v, p, w, params.upright);
        all && all->scale >= params.min_scale && all->scale <= params.max_scale) {
        if (support(*all, nullptr).first > best_score) best = all;
    }
    if (!best) return std::nullopt;
    RobustSolveResult out;
    out.similarity = *best;
    for (int round = 0; round < 3; ++round) {
        std::vector<bool> inlier;
        const std::size_t count = support(out.similarity, &inlier).second;
        if (count < 3) return std::nullopt;
        std::vector<double> wi(w.size(), 0.0);
        for (std::size_t i = 0; i < w.size(); ++i) wi[i] = inlier[i] ? w[i] : 0.0;
        const auto refined = solve_similarity(v, p, wi, params.upright);
        out.inlier = std::move(inlier);
        out.inliers = count;
        if (!refined) break;
        out.similarity = *refined;
    }
    return out;
}

}  // namespace makeway::shape
