#include "makeway/eval/kitti_tracking_eval.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <unordered_map>

#include "makeway/common/angles.hpp"
#include "makeway/common/box_overlap.hpp"
#include "makeway/tracking/hungarian.hpp"

namespace makeway::eval {
namespace {

std::string neighbour_of(const std::string& cls) {
    if (cls == "car") return "van";
    if (cls == "pedestrian") return "person_sitting";
    return {};
}

// Intersection over a's area of two 2D boxes (the devkit's DontCare criterion).
double overlap_of_a(const std::array<double, 4>& a, const std::array<double, 4>& b) {
    const double w = std::min(a[2], b[2]) - std::max(a[0], b[0]),
                 h = std::min(a[3], b[3]) - std::max(a[1], b[1]);
    if (w <= 0.0 || h <= 0.0) return 0.0;
    return w * h / ((a[2] - a[0]) * (a[3] - a[1]));
}

// The class evaluated or its neighbour (Van for Car, Person_sitting for Pedestrian).
bool of_class(const std::string& type, const std::string& cls, const std::string& neighbour) {
    return type == cls || (!neighbour.empty() && type == neighbour);
}

struct Loaded {
    std::vector<KittiSequence> boxes;  // the class and its neighbour
    std::vector<KittiSequence> dont_care;
};

// The class, its neighbour and (ground truth) the DontCare regions; the field of view applied;
// tracker boxes below the threshold (on their track's mean score) dropped, scores set to the mean.
// With `track_scores`, a tracker box's score is its track's entry there instead of the mean.
Loaded load(const std::vector<KittiSequence>& seqs, const KittiEvalParams& p, bool tracker,
            double threshold,
            const std::vector<std::unordered_map<int, double>>* track_scores = nullptr) {
    const std::string neighbour = p.ignore_neighbours ? neighbour_of(p.cls) : std::string();
    const double half_fov = deg_to_rad(p.fov_deg) / 2;
    Loaded out;
    for (std::size_t si = 0; si < seqs.size(); ++si) {
        const KittiSequence& seq = seqs[si];
        std::unordered_map<int, std::pair<double, int>> score_sum;  // track id -> (sum, count)
        for (const KittiFrame& f : seq) {
            for (const KittiBox& b : f) {
                auto& s = score_sum[b.track_id];
                s.first += b.score, ++s.second;
            }
        }
        KittiSequence boxes(seq.size()), dc(seq.size());
        for (std::size_t k = 0; k < seq.size(); ++k) {
            for (KittiBox b : seq[k]) {
                if (b.type == "dontcare") {
                    if (!tracker) dc[k].push_back(b);
                    continue;
                }
                if (!of_class(b.type, p.cls, neighbour)) continue;
                if (b.track_id < 0) continue;  // the devkit skips boxes without an id
                if (p.fov_deg > 0.0) {
                    const Eigen::Vector3d& c = b.box.centre_m;
                    if (c.x() <= 0.0 || std::abs(std::atan2(c.y(), c.x())) > half_fov) continue;
                }
                if (tracker) {
                    const auto& s = score_sum[b.track_id];
                    b.score =
                        track_scores ? track_scores->at(si).at(b.track_id) : s.first / s.second;
                    if (b.score < threshold) continue;
                }
                boxes[k].push_back(b);
            }
        }
        out.boxes.push_back(std::move(boxes));
        out.dont_care.push_back(std::move(dc));
    }
    return out;
}

struct Trajectory {
    std::vector<int> tracker;  // matched tracker id per frame the ground truth is present, -1: none
    std::vector<bool> ignored;
};

// Id switches, fragmentations and MT/PT/ML over ground-truth trajectories, by the devkit's rules
// (an ignored frame breaks the chain; a switch needs the previous frame matched too).
void score_trajectories(const std::vector<std::map<int, Trajectory>>& seqs, KittiClear& m) {
    std::size_t trajectories = 0, all_ignored = 0, mt = 0, pt = 0, ml = 0;
    for (const auto& seq : seqs) {
        for (const auto& [gt_id, tr] : seq) {
            ++trajectories;
            const std::vector<int>& g = tr.tracker;
            const std::vector<bool>& ign = tr.ignored;
            if (std::all_of(ign.begin(), ign.end(), [](bool b) { return b; })) {
                ++all_ignored;
                continue;
            }
            if (std::all_of(g.begin(), g.end(), [](int id) { return id == -1; })) {
                ++ml;
                continue;
            }
            int last_id = g[0];
            std::size_t tracked = g[0] >= 0 ? 1 : 0;
            std::size_t f = 0;
            for (f = 1; f < g.size(); ++f) {
                if (ign[f]) {
                    last_id = -1;
                    continue;
                }
                if (last_id != g[f] && last_id != -1 && g[f] != -1 && g[f - 1] != -1)
                    ++m.id_switches;
                if (f + 1 < g.size() && g[f - 1] != g[f] && last_id != -1 && g[f] != -1 &&
                    g[f + 1] != -1)
                    ++m.fragmentations;
                if (g[f] != -1) ++tracked, last_id = g[f];
            }
            f = g.size() - 1;
            if (g.size() > 1 && g[f - 1] != g[f] && last_id != -1 && g[f] != -1 && !ign[f])
                ++m.fragmentations;
            const auto unignored = static_cast<double>(std::count(ign.begin(), ign.end(), false));
            const double ratio = static_cast<double>(tracked) / unignored;
            if (ratio > 0.8)
                ++mt;
            else if (ratio < 0.2)
                ++ml;
            else
                ++pt;
        }
    }
    const std::size_t counted = trajectories - all_ignored;
    if (counted > 0) {
        m.mostly_tracked = static_cast<double>(mt) / static_cast<double>(counted);
        m.partly_tracked = static_cast<double>(pt) / static_cast<double>(counted);
        m.mostly_lost = static_cast<double>(ml) / static_cast<double>(counted);
    }
}

// AB3DMOT's evaluate.py, per sequence: each track's boxes of the class (and its neighbour) in frame
// order, their scores summed one after the other and divided by their count (Python's sum / len).
struct DevkitScores {
    std::vector<std::unordered_map<int, double>> score;       // the current score per track
    std::vector<std::unordered_map<int, std::size_t>> count;  // its boxes
};

DevkitScores devkit_means(const std::vector<KittiSequence>& seqs, const KittiEvalParams& p) {
    const std::string neighbour = p.ignore_neighbours ? neighbour_of(p.cls) : std::string();
    DevkitScores d;
    for (const KittiSequence& seq : seqs) {
        std::unordered_map<int, double> sum;
        std::unordered_map<int, std::size_t> n;
        for (const KittiFrame& f : seq) {
            for (const KittiBox& b : f) {
                if (b.track_id < 0 || !of_class(b.type, p.cls, neighbour)) continue;
                sum[b.track_id] += b.score;
                ++n[b.track_id];
            }
        }
        for (auto& [id, s] : sum) s /= static_cast<double>(n[id]);
        d.score.push_back(std::move(sum));
        d.count.push_back(std::move(n));
    }
    return d;
}

// The script's next pass: every box already carries its track's score, which is averaged again.
void devkit_reaverage(DevkitScores& d) {
    for (std::size_t s = 0; s < d.score.size(); ++s) {
        for (auto& [id, v] : d.score[s]) {
            const std::size_t n = d.count[s].at(id);
            double sum = 0.0;
            for (std::size_t i = 0; i < n; ++i) sum += v;
            v = sum / static_cast<double>(n);
        }
    }
}

}  // namespace

std::vector<std::pair<double, double>> kitti_thresholds(std::vector<double> scores,
                                                        std::size_t num_gt, int recall_steps) {
    std::vector<std::pair<double, double>> out;
    if (num_gt == 0 || scores.empty()) return out;
    std::sort(scores.begin(), scores.end(), std::greater<>());
    const double n = static_cast<double>(num_gt), step = 1.0 / recall_steps;
    double current = 0.0;
    for (std::size_t i = 0; i < scores.size(); ++i) {
        const bool last = i + 1 == scores.size();
        const double left = static_cast<double>(i + 1) / n,
                     right = last ? left : static_cast<double>(i + 2) / n;
        // Take this score when its recall is at least as close to the next step as the next
        // score's.
        if (right - current < current - left && !last) continue;
        out.emplace_back(scores[i], current);
        current += step;
    }
    if (!out.empty()) out.erase(out.begin());  // zero recall
    return out;
}

KittiClear evaluate_kitti_at(const std::vector<KittiSequence>& gt_in,
                             const std::vector<KittiSequence>& tr_in, const KittiEvalParams& p,
                             double threshold, double recall_target, std::vector<double>* tp_scores,
                             const std::vector<std::unordered_map<int, double>>* track_scores) {
    const Loaded gt = load(gt_in, p, false, -std::numeric_limits<double>::infinity());
    const Loaded tr = load(tr_in, p, true, threshold, track_scores);
    const std::string neighbour = p.ignore_neighbours ? neighbour_of(p.cls) : std::string();
    KittiClear m;
    m.threshold = threshold;
    m.recall_target = recall_target;
    double iou_sum = 0.0;
    std::vector<std::map<int, Trajectory>> trajectories(gt.boxes.size());
    const KittiFrame none;
    for (std::size_t s = 0; s < gt.boxes.size(); ++s) {
        const std::size_t frames =
            std::max(gt.boxes[s].size(), s < tr.boxes.size() ? tr.boxes[s].size() : 0);
        m.frames += frames;
        for (std::size_t k = 0; k < frames; ++k) {
            const KittiFrame& g = k < gt.boxes[s].size() ? gt.boxes[s][k] : none;
            const KittiFrame& t =
                s < tr.boxes.size() && k < tr.boxes[s].size() ? tr.boxes[s][k] : none;
            const KittiFrame& dc = k < gt.dont_care[s].size() ? gt.dont_care[s][k] : none;
            // Hungarian on 1 - IoU; pairs under the IoU threshold cost more than any match.
            std::vector<int> match(g.size(), -1);
            std::vector<double> iou(g.size(), 0.0);
            if (!g.empty() && !t.empty()) {
                Eigen::MatrixXd cost(static_cast<Eigen::Index>(g.size()),
                                     static_cast<Eigen::Index>(t.size()));
                Eigen::MatrixXd ious(cost.rows(), cost.cols());
                for (std::size_t i = 0; i < g.size(); ++i) {
                    for (std::size_t j = 0; j < t.size(); ++j) {
                        const double v = iou_3d(g[i].box, t[j].box);
                        ious(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = v;
                        cost(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) =
                            v >= p.min_iou_3d ? 1.0 - v : 1e6;
                    }
                }
                const std::vector<int> col = tracking::min_cost_assignment(cost);
                for (std::size_t i = 0; i < g.size(); ++i) {
                    if (col[i] >= 0 && ious(static_cast<Eigen::Index>(i), col[i]) >= p.min_iou_3d) {
                        match[i] = col[i];
                        iou[i] = ious(static_cast<Eigen::Index>(i), col[i]);
                    }
                }
            }
            std::vector<bool> matched_tracker(t.size(), false);
            for (std::size_t i = 0; i < g.size(); ++i) {
                if (match[i] < 0) continue;
                matched_tracker[static_cast<std::size_t>(match[i])] = true;
                ++m.tp;  // ignored ones included, as the devkit counts
                iou_sum += iou[i];
                if (tp_scores) tp_scores->push_back(t[static_cast<std::size_t>(match[i])].score);
            }
            // Unmatched tracker boxes of the neighbouring class, too small, or in a DontCare area.
            std::size_t ignored_tracker = 0;
            for (std::size_t j = 0; j < t.size(); ++j) {
                if (matched_tracker[j]) continue;
                bool ignore = !neighbour.empty() && t[j].type == neighbour;
                if (!ignore && t[j].has_bbox()) {
                    ignore = std::abs(t[j].bbox_px[3] - t[j].bbox_px[1]) <= p.min_height_px;
                    for (std::size_t d = 0; !ignore && p.use_dont_care && d < dc.size(); ++d) {
                        ignore =
                            dc[d].has_bbox() && overlap_of_a(t[j].bbox_px, dc[d].bbox_px) > 0.5;
                    }
                }
                ignored_tracker += ignore;
            }
            // Ground truth too truncated, too occluded or of the neighbouring class: ignored.
            std::size_t ignored_fn = 0, ignored_tp = 0, unmatched = 0;
            for (std::size_t i = 0; i < g.size(); ++i) {
                const bool ignore = g[i].occlusion > p.max_occlusion ||
                                    g[i].truncation > p.max_truncation ||
                                    (!neighbour.empty() && g[i].type == neighbour);
                if (match[i] < 0) ++unmatched;
                if (ignore) (match[i] < 0 ? ignored_fn : ignored_tp) += 1;
                Trajectory& traj = trajectories[s][g[i].track_id];
                traj.tracker.push_back(
                    match[i] < 0 ? -1 : t[static_cast<std::size_t>(match[i])].track_id);
                traj.ignored.push_back(ignore);
            }
            const std::size_t matched = static_cast<std::size_t>(
                std::count(matched_tracker.begin(), matched_tracker.end(), true));
            m.ignored_tp += ignored_tp;
            m.ignored_fn += ignored_fn;
            m.ignored_tracker += ignored_tracker;
            m.gt += g.size() - ignored_fn - ignored_tp;
            m.fn += unmatched - ignored_fn;
            m.fp += t.size() - matched - ignored_tracker;
        }
    }
    score_trajectories(trajectories, m);
    const double tp = static_cast<double>(m.tp), fp = static_cast<double>(m.fp),
                 fn = static_cast<double>(m.fn);
    if (m.tp + m.fn > 0 && m.tp + m.fp > 0) m.recall = tp / (tp + fn), m.precision = tp / (tp + fp);
    if (m.recall + m.precision > 0) m.f1 = 2 * m.precision * m.recall / (m.precision + m.recall);
    if (m.gt > 0) {
        const double n = static_cast<double>(m.gt),
                     errors = fn + fp + static_cast<double>(m.id_switches);
        m.mota = 1.0 - errors / n;
        m.moda = 1.0 - (fn + fp) / n;
        m.smota =
            std::clamp(1.0 - (errors - (1.0 - recall_target) * n) / (recall_target * n), 0.0, 1.0);
    }
    if (m.tp > 0) m.motp = iou_sum / tp;
    return m;
}

KittiEvalResult evaluate_kitti(const std::vector<KittiSequence>& gt,
                               const std::vector<KittiSequence>& tracks, const KittiEvalParams& p) {
    KittiEvalResult r;
    std::vector<double> scores;
    DevkitScores devkit;
    if (p.devkit_rounding) devkit = devkit_means(tracks, p);
    const auto* track_scores = p.devkit_rounding ? &devkit.score : nullptr;
    r.all = evaluate_kitti_at(gt, tracks, p, -std::numeric_limits<double>::infinity(), 1.0, &scores,
                              track_scores);
    r.best = r.all;
    for (const auto& seq : gt)
        for (const auto& f : seq)
            r.gt_boxes += static_cast<std::size_t>(std::count_if(
                f.begin(), f.end(), [&](const KittiBox& b) { return b.type == p.cls; }));
    for (const auto& seq : tracks)
        for (const auto& f : seq)
            r.tracker_boxes += static_cast<std::size_t>(std::count_if(
                f.begin(), f.end(), [&](const KittiBox& b) { return b.type == p.cls; }));
    double best_mota = 0.0;  // as the devkit: the all-boxes result unless a threshold beats MOTA 0
    double best_threshold = -std::numeric_limits<double>::infinity();
    for (const auto& [threshold, recall] :
         kitti_thresholds(scores, r.all.tp + r.all.fn, p.recall_steps)) {
        if (p.devkit_rounding) devkit_reaverage(devkit);
        const KittiClear m =
            evaluate_kitti_at(gt, tracks, p, threshold, recall, nullptr, track_scores);
        r.curve.push_back(m);
        r.samota += m.smota;
        r.amota += m.mota;
        r.amotp += m.motp;
        if (m.mota > best_mota) best_mota = m.mota, r.best = m, best_threshold = threshold;
    }
    if (p.devkit_rounding) {  // the script's best row: one more pass at the best threshold (recall
                              // 1)
        devkit_reaverage(devkit);
        r.best = evaluate_kitti_at(gt, tracks, p, best_threshold, 1.0, nullptr, track_scores);
    }
    r.samota /= p.recall_steps;
    r.amota /= p.recall_steps;
    r.amotp /= p.recall_steps;
    return r;
}

}  // namespace makeway::eval
