#include "makeway/eval/tracking_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "makeway/common/box_overlap.hpp"
#include "makeway/tracking/hungarian.hpp"

namespace makeway::eval {
namespace {

constexpr double kEps = 1e-10;

Eigen::MatrixXd similarities(const TrackingFrame& gt, const TrackingFrame& tr) {
    Eigen::MatrixXd s(static_cast<Eigen::Index>(gt.size()), static_cast<Eigen::Index>(tr.size()));
    for (std::size_t i = 0; i < gt.size(); ++i) {
        for (std::size_t j = 0; j < tr.size(); ++j)
            s(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) =
                iou_3d(gt[i].box, tr[j].box);
    }
    return s;
}

ClearMot clear_mot(const std::vector<TrackingFrame>& gt, const std::vector<TrackingFrame>& tracks,
                   double thr) {
    ClearMot m;
    std::unordered_map<std::uint32_t, std::uint32_t>
        last_match;  // gt id -> track id it was last matched to
    std::unordered_map<std::uint32_t, bool>
        tracked_before;  // gt id -> matched at its previous frame
    double iou_sum = 0.0;
    const TrackingFrame none;
    for (std::size_t k = 0; k < std::max(gt.size(), tracks.size()); ++k) {
        const TrackingFrame& g = k < gt.size() ? gt[k] : none;
        const TrackingFrame& t = k < tracks.size() ? tracks[k] : none;
        const Eigen::MatrixXd s = similarities(g, t);
        std::vector<int> match(g.size(), -1);
        std::vector<bool> used(t.size(), false);
        // Matches from the previous frame stay while they still overlap enough.
        for (std::size_t i = 0; i < g.size(); ++i) {
            const auto it = last_match.find(g[i].id);
            if (it == last_match.end() || !tracked_before[g[i].id]) continue;
            for (std::size_t j = 0; j < t.size(); ++j) {
                if (!used[j] && t[j].id == it->second &&
                    s(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) >= thr - kEps) {
                    match[i] = static_cast<int>(j), used[j] = true;
                }
            }
        }
        // The rest by the Hungarian algorithm on IoU (pairs below the threshold forbidden).
        std::vector<std::size_t> rows, cols;
        for (std::size_t i = 0; i < g.size(); ++i) {
            if (match[i] < 0) rows.push_back(i);
        }
        for (std::size_t j = 0; j < t.size(); ++j) {
            if (!used[j]) cols.push_back(j);
        }
        if (!rows.empty() && !cols.empty()) {
            Eigen::MatrixXd cost(static_cast<Eigen::Index>(rows.size()),
                                 static_cast<Eigen::Index>(cols.size()));
            for (std::size_t a = 0; a < rows.size(); ++a) {
                for (std::size_t b = 0; b < cols.size(); ++b) {
                    const double v =
                        s(static_cast<Eigen::Index>(rows[a]), static_cast<Eigen::Index>(cols[b]));
                    cost(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b)) =
                        v >= thr - kEps ? -v : 1.0;
                }
            }
            const std::vector<int> c = tracking::min_cost_assignment(cost);
            for (std::size_t a = 0; a < rows.size(); ++a) {
                if (c[a] >= 0 && cost(static_cast<Eigen::Index>(a), c[a]) <= 0.0) {
                    match[rows[a]] = static_cast<int>(cols[static_cast<std::size_t>(c[a])]);
                    used[cols[static_cast<std::size_t>(c[a])]] = true;
                }
            }
        }
        for (std::size_t i = 0; i < g.size(); ++i) {
            const std::uint32_t gid = g[i].id;
            const bool tracked = match[i] >= 0;
            if (tracked) {
                const std::uint32_t tid = t[static_cast<std::size_t>(match[i])].id;
                ++m.tp;
                iou_sum += s(static_cast<Eigen::Index>(i), match[i]);
                const auto it = last_match.find(gid);
                if (it != last_match.end() && it->second != tid) ++m.id_switches;
                if (it != last_match.end() && !tracked_before[gid])
                    ++m.fragmentations;  // tracked again after a gap
                last_match[gid] = tid;
            } else {
                ++m.fn;
            }
            tracked_before[gid] = tracked;
        }
        m.gt += g.size();
        m.fp += t.size() - static_cast<std::size_t>(std::count(used.begin(), used.end(), true));
    }
    m.mota =
        m.gt ? 1.0 - static_cast<double>(m.fn + m.fp + m.id_switches) / static_cast<double>(m.gt)
             : 0.0;
    m.motp = m.tp ? iou_sum / static_cast<double>(m.tp) : 0.0;
    return m;
}

Hota hota(const std::vector<TrackingFrame>& gt, const std::vector<TrackingFrame>& tracks) {
    // Dense indices for the ids.
    std::unordered_map<std::uint32_t, Eigen::Index> gi, ti;
    for (const auto& f : gt)
        for (const auto& b : f) gi.emplace(b.id, static_cast<Eigen::Index>(gi.size()));
    for (const auto& f : tracks)
        for (const auto& b : f) ti.emplace(b.id, static_cast<Eigen::Index>(ti.size()));
    const auto ng = static_cast<Eigen::Index>(gi.size()), nt = static_cast<Eigen::Index>(ti.size());
    Eigen::VectorXd gt_count = Eigen::VectorXd::Zero(ng), tr_count = Eigen::VectorXd::Zero(nt);
    Eigen::MatrixXd potential = Eigen::MatrixXd::Zero(ng, nt);
    std::size_t gt_dets = 0, tr_dets = 0;
    const std::size_t frames = std::max(gt.size(), tracks.size());
    auto frame_of = [](const std::vector<TrackingFrame>& v, std::size_t k) {
        return k < v.size() ? v[k] : TrackingFrame{};
    };
    std::vector<Eigen::MatrixXd> sims(frames);
    for (std::size_t k = 0; k < frames; ++k) {
        const TrackingFrame g = frame_of(gt, k), t = frame_of(tracks, k);
        sims[k] = similarities(g, t);
        gt_dets += g.size(), tr_dets += t.size();
        for (const auto& b : g) gt_count[gi[b.id]] += 1;
        for (const auto& b : t) tr_count[ti[b.id]] += 1;
        if (g.empty() || t.empty()) continue;
        const Eigen::VectorXd row = sims[k].rowwise().sum();
        const Eigen::RowVectorXd col = sims[k].colwise().sum();
        for (Eigen::Index i = 0; i < sims[k].rows(); ++i) {
            for (Eigen::Index j = 0; j < sims[k].cols(); ++j) {
                const double sv = sims[k](i, j);
                potential(gi[g[static_cast<std::size_t>(i)].id],
                          ti[t[static_cast<std::size_t>(j)].id]) +=
                    sv > 0 ? sv / (row[i] + col[j] - sv) : 0.0;
            }
        }
    }
    Eigen::MatrixXd global(ng, nt);
    for (Eigen::Index a = 0; a < ng; ++a) {
        for (Eigen::Index b = 0; b < nt; ++b)
            global(a, b) = potential(a, b) / (gt_count[a] + tr_count[b] - potential(a, b));
    }
    constexpr int kAlphas = 19;
    std::vector<Eigen::MatrixXd> matches(kAlphas, Eigen::MatrixXd::Zero(ng, nt));
    std::vector<double> tp(kAlphas, 0.0);
    for (std::size_t k = 0; k < frames; ++k) {
        const TrackingFrame g = frame_of(gt, k), t = frame_of(tracks, k);
        if (g.empty() || t.empty()) continue;
        Eigen::MatrixXd score(sims[k].rows(), sims[k].cols());
        for (Eigen::Index i = 0; i < score.rows(); ++i) {
            for (Eigen::Index j = 0; j < score.cols(); ++j) {
                score(i, j) = global(gi[g[static_cast<std::size_t>(i)].id],
                                     ti[t[static_cast<std::size_t>(j)].id]) *
                              sims[k](i, j);
            }
        }
        const std::vector<int> col = tracking::min_cost_assignment(-score);
        for (Eigen::Index i = 0; i < score.rows(); ++i) {
            const int j = col[static_cast<std::size_t>(i)];
            if (j < 0) continue;
            for (int a = 0; a < kAlphas; ++a) {
                const double alpha = 0.05 * (a + 1);
                if (sims[k](i, j) >= alpha - kEps) {
                    tp[static_cast<std::size_t>(a)] += 1;
                    matches[static_cast<std::size_t>(a)](gi[g[static_cast<std::size_t>(i)].id],
                                                         ti[t[static_cast<std::size_t>(j)].id]) +=
                        1;
                }
            }
        }
    }
    Hota h;
    for (int a = 0; a < kAlphas; ++a) {
        const Eigen::MatrixXd& mc = matches[static_cast<std::size_t>(a)];
        double ass = 0.0;
        for (Eigen::Index i = 0; i < ng; ++i) {
            for (Eigen::Index j = 0; j < nt; ++j) {
                if (mc(i, j) > 0)
                    ass += mc(i, j) * mc(i, j) / (gt_count[i] + tr_count[j] - mc(i, j));
            }
        }
        const double t_a = tp[static_cast<std::size_t>(a)];
        const double assa = ass / std::max(1.0, t_a);
        const double deta = t_a / std::max(1.0, static_cast<double>(gt_dets + tr_dets) - t_a);
        h.assa += assa / kAlphas;
        h.deta += deta / kAlphas;
        h.hota += std::sqrt(deta * assa) / kAlphas;
    }
    return h;
}

}  // namespace

TrackingMetrics evaluate_tracking(const std::vector<TrackingFrame>& gt,
                                  const std::vector<TrackingFrame>& tracks,
                                  const TrackingMetricsParams& params) {
    return {clear_mot(gt, tracks, params.clear_iou_threshold), hota(gt, tracks)};
}

std::map<ObjectClass, TrackingMetrics> evaluate_tracking_per_class(
    const std::vector<TrackingFrame>& gt, const std::vector<TrackingFrame>& tracks,
    const TrackingMetricsParams& params) {
    std::map<ObjectClass, TrackingMetrics> out;
    for (ObjectClass cls : kAllObjectClasses) {
        auto only = [cls](const std::vector<TrackingFrame>& v) {
            std::vector<TrackingFrame> f(v.size());
            for (std::size_t k = 0; k < v.size(); ++k) {
                for (const auto& b : v[k]) {
                    if (b.cls == cls) f[k].push_back(b);
                }
            }
            return f;
        };
        out[cls] = evaluate_tracking(only(gt), only(tracks), params);
    }
    return out;
}

}  // namespace makeway::eval
