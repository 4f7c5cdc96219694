#include "makeway/zones/zone_learning.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>
#include <tuple>

#include "makeway/common/angles.hpp"
#include "makeway/common/param_table.hpp"
#include "makeway/tracking/hungarian.hpp"

namespace makeway::zones {
namespace {

constexpr double kFar = 1e6;

Pose2 pose_of(const OrientedBox& b) { return {b.centre_m.x(), b.centre_m.y(), b.yaw_rad}; }

// The footprint is symmetric under a half turn, so only dyaw modulo pi matters: (-pi/2, pi/2].
double fold_half_turn(double a) {
    a = wrap_angle(a);
    if (a > M_PI_2) a -= M_PI;
    if (a <= -M_PI_2) a += M_PI;
    return a;
}

double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
}

bool admissible(const SessionObject& a, const SessionObject& b, const ZoneLearnParams& p) {
    const double size = std::abs(a.box_world.size_m.x() - b.box_world.size_m.x()) +
                        std::abs(a.box_world.size_m.y() - b.box_world.size_m.y());
    return size <= p.max_size_difference_m;
}

ClassLearning& of(ZoneLearning& l, ObjectClass cls) {
    return cls == ObjectClass::kChair ? l.chair : l.table;
}

// Matches the objects of one class between sessions a and b; appends both directions' motions.
void match_pair(const std::vector<const SessionObject*>& in_a,
                const std::vector<const SessionObject*>& in_b, ObjectClass cls,
                const ZoneLearnParams& p, ZoneLearning& out, std::vector<bool>& matched_a,
                std::vector<bool>& matched_b) {
    if (in_a.empty() || in_b.empty()) return;
    Eigen::MatrixXd cost(in_a.size(), in_b.size());
    for (std::size_t i = 0; i < in_a.size(); ++i) {
        for (std::size_t j = 0; j < in_b.size(); ++j) {
            const double d =
                (in_a[i]->box_world.centre_m.head<2>() - in_b[j]->box_world.centre_m.head<2>())
                    .norm();
            cost(i, j) = d <= p.match_gate_m && admissible(*in_a[i], *in_b[j], p) ? d : kFar;
        }
    }
    const std::vector<int> assign = tracking::min_cost_assignment(cost);
    ClassLearning& stats = of(out, cls);
    for (std::size_t i = 0; i < in_a.size(); ++i) {
        const int j = assign[i];
        if (j < 0 || cost(i, j) >= kFar) continue;
        const double d = cost(i, j);
        double next = kFar;
        for (std::size_t k = 0; k < in_b.size(); ++k)
            if (static_cast<int>(k) != j) next = std::min(next, cost(i, k));
        for (std::size_t k = 0; k < in_a.size(); ++k)
            if (k != i) next = std::min(next, cost(k, j));
        const double confidence = next >= kFar ? 1.0 : std::clamp(1.0 - d / next, 0.0, 1.0);
        matched_a[i] = matched_b[j] = true;
        if (confidence < p.min_match_confidence) {
            ++stats.unsure;
            continue;
        }
        const Pose2 pa = pose_of(in_a[i]->box_world), pb = pose_of(in_b[j]->box_world);
        const int place = in_a[i]->place;
        out.motions.push_back(
            {cls, place, in_a[i]->session, in_b[j]->session, between(pa, pb), confidence});
        if (p.both_directions)
            out.motions.push_back(
                {cls, place, in_b[j]->session, in_a[i]->session, between(pb, pa), confidence});
    }
}

}  // namespace

std::vector<std::string> ZoneLearnParams::validate() const {
    std::vector<std::string> out;
    const auto check = [&](bool ok, const char* message) {
        if (!ok) out.push_back(message);
    };
    check(std::isfinite(match_gate_m) && match_gate_m > 0.0 &&
              match_gate_m <= costmap::kMaxZoneMotion_m,
          "match_gate_m must be in (0, 5]");
    check(std::isfinite(max_size_difference_m) && max_size_difference_m >= 0.0,
          "max_size_difference_m must be >= 0");
    check(min_match_confidence >= 0.0 && min_match_confidence <= 1.0,
          "min_match_confidence must be in [0, 1]");
    check(std::isfinite(bin_m) && bin_m > 0.0 && bin_m <= 1.0, "bin_m must be in (0, 1]");
    check(std::isfinite(bin_deg) && bin_deg > 0.0 && bin_deg <= 90.0, "bin_deg must be in (0, 90]");
    for (const std::string& m : zone.validate()) out.push_back(m);
    return out;
}

costmap::ClassZone bin_motions(const std::vector<Pose2>& motions, ObjectClass cls,
                               const ZoneLearnParams& p) {
    std::map<std::tuple<long, long, long>, double> bins;
    const double bin_rad = deg_to_rad(p.bin_deg);
    const auto add = [&](double dx, double dy, double dyaw, double w) {
        bins[{std::lround(dx / p.bin_m), std::lround(dy / p.bin_m),
              std::lround(fold_half_turn(dyaw) / bin_rad)}] += w;
    };
    for (const Pose2& m : motions) {
        if (!(std::hypot(m.x_m, m.y_m) <= costmap::kMaxZoneMotion_m)) continue;
        if (!p.symmetric) {
            add(m.x_m, m.y_m, m.yaw_rad, 1.0);
        } else if (cls == ObjectClass::kChair) {
            add(m.x_m, m.y_m, m.yaw_rad, 0.5);
            add(m.x_m, -m.y_m, -m.yaw_rad, 0.5);
        } else {
            add(m.x_m, m.y_m, m.yaw_rad, 0.25);
            add(m.x_m, -m.y_m, -m.yaw_rad, 0.25);
            add(-m.x_m, m.y_m, -m.yaw_rad, 0.25);
            add(-m.x_m, -m.y_m, m.yaw_rad, 0.25);
        }
    }
    costmap::ClassZone zone;
    zone.observations = static_cast<double>(motions.size());
    for (const auto& [key, w] : bins) {
        const auto [ix, iy, iyaw] = key;
        zone.motions.push_back({ix * p.bin_m, iy * p.bin_m, iyaw * bin_rad, w});
    }
    return zone;
}

std::vector<ObjectMotion> track_motions(const std::vector<TrackedObject>& objects, double gap_s) {
    std::map<std::pair<int, std::uint32_t>, std::vector<const TrackedObject*>> tracks;
    for (const TrackedObject& o : objects) tracks[{o.place, o.track}].push_back(&o);
    std::vector<ObjectMotion> out;
    for (auto& [key, seen] : tracks) {
        std::stable_sort(seen.begin(), seen.end(),
                         [](const auto* a, const auto* b) { return a->stamp_s < b->stamp_s; });
        const TrackedObject* last = nullptr;
        int index = 0;
        for (const TrackedObject* o : seen) {
            if (last != nullptr && o->stamp_s - last->stamp_s < gap_s) continue;
            if (last != nullptr && o->cls == last->cls) {
                out.push_back({o->cls, key.first, index, index + 1,
                               between(pose_of(last->box_world), pose_of(o->box_world)), 1.0});
                ++index;
            }
            last = o;
        }
    }
    return out;
}

ZoneLearning learn_zones(const std::vector<SessionObject>& objects, const ZoneLearnParams& p,
                         const std::vector<ObjectMotion>& more) {
    throw_if_problems(p.validate(), "zone learning");
    ZoneLearning out;
    out.zones = p.zone;
    using Session = std::pair<int, int>;  // place, session
    std::set<Session> sessions;
    for (const SessionObject& o : objects) {
        ++of(out, o.cls).observations;
        sessions.insert({o.place, o.session});
    }
    const auto usable = [&](const Session& session, ObjectClass cls) {
        std::vector<const SessionObject*> v;
        for (const SessionObject& o : objects) {
            if (o.place == session.first && o.session == session.second && o.cls == cls &&
                (o.facing_known || cls != ObjectClass::kChair))
                v.push_back(&o);
        }
        return v;
    };
    for (const SessionObject& o : objects)
        if (o.cls == ObjectClass::kChair && !o.facing_known) ++out.chair.facing_unknown;

    for (ObjectClass cls : {ObjectClass::kChair, ObjectClass::kTable}) {
        std::map<Session, std::vector<bool>> ever_matched;
        for (const Session& s : sessions) ever_matched[s].assign(usable(s, cls).size(), false);
        for (auto a = sessions.begin(); a != sessions.end(); ++a) {
            for (auto b = std::next(a); b != sessions.end() && b->first == a->first; ++b) {
                const auto in_a = usable(*a, cls), in_b = usable(*b, cls);
                std::vector<bool> ma(in_a.size(), false), mb(in_b.size(), false);
                match_pair(in_a, in_b, cls, p, out, ma, mb);
                for (std::size_t i = 0; i < ma.size(); ++i)
                    if (ma[i]) ever_matched[*a][i] = true;
                for (std::size_t j = 0; j < mb.size(); ++j)
                    if (mb[j]) ever_matched[*b][j] = true;
            }
        }
        ClassLearning& stats = of(out, cls);
        for (const auto& [s, flags] : ever_matched)
            stats.unmatched +=
                static_cast<std::size_t>(std::count(flags.begin(), flags.end(), false));
    }

    const std::size_t matched = out.motions.size();
    for (const ObjectMotion& m : more) {
        if (m.confidence >= p.min_match_confidence) out.motions.push_back(m);
    }
    for (ObjectClass cls : {ObjectClass::kChair, ObjectClass::kTable}) {
        std::vector<Pose2> motions;
        double confidence = 0.0;
        double observations = 0.0;  // both directions of a match are one observation
        std::size_t moved = 0;
        for (std::size_t k = 0; k < out.motions.size(); ++k) {
            const ObjectMotion& m = out.motions[k];
            if (m.cls != cls) continue;
            observations += k < matched && p.both_directions ? 0.5 : 1.0;
            of(out, cls).tracked += k >= matched;
            motions.push_back(m.motion);
            confidence += m.confidence;
            moved += std::hypot(m.motion.x_m, m.motion.y_m) > 0.05 ||
                     std::abs(fold_half_turn(m.motion.yaw_rad)) > deg_to_rad(5.0);
        }
        ClassLearning& stats = of(out, cls);
        stats.motions = motions.size();
        if (motions.empty()) continue;
        stats.mean_confidence = confidence / static_cast<double>(motions.size());
        stats.moved_share = static_cast<double>(moved) / static_cast<double>(motions.size());
        costmap::ClassZone zone = bin_motions(motions, cls, p);
        std::vector<double> lengths, widths;
        for (const SessionObject& o : objects) {
            if (o.cls != cls) continue;
            lengths.push_back(o.box_world.size_m.x());
            widths.push_back(o.box_world.size_m.y());
        }
        zone.typical_size_m = {median(lengths), median(widths)};
        zone.observations = observations;
        (cls == ObjectClass::kChair ? out.zones.chair : out.zones.table) = std::move(zone);
    }
    return out;
}

}  // namespace makeway::zones
