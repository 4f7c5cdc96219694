#include "makeway/sim/contact_judge.hpp"

namespace makeway::sim {

ContactJudge::ContactJudge(const CollisionChecker& checker, const RobotParams& robot,
                           double robot_caused_mps)
    : checker_(checker),
      length_m_(robot.length_m),
      width_m_(robot.width_m),
      robot_caused_mps_(robot_caused_mps) {}

std::vector<ContactEvent> ContactJudge::step(const RobotState& state, double t_s) {
    return step(state, t_s,
                checker_.collides(state.pose, t_s, CollisionChecker::Against::kEverything));
}

std::vector<ContactEvent> ContactJudge::step(const RobotState& state, double t_s,
                                             bool touching_anything) {
    using Against = CollisionChecker::Against;
    std::vector<ContactEvent> started;
    if (!touching_anything) {  // the common case: no contact point looked for
        for (bool& t : touching_) t = false;
        return started;
    }
    static constexpr Against kKinds[3] = {Against::kStructure, Against::kFurniture,
                                          Against::kPeople};
    static const char* const kNames[3] = {"walls", "furniture", "people"};
    for (int i = 0; i < 3; ++i) {
        const std::optional<Eigen::Vector2d> c = checker_.contact_point(state.pose, t_s, kKinds[i]);
        if (c && !touching_[i]) {
            const double toward = speed_toward_contact(state.pose, state.v_mps, state.w_radps, *c,
                                                       length_m_, width_m_);
            started.push_back({t_s, kNames[i], toward > robot_caused_mps_, toward, *c});
        }
        touching_[i] = c.has_value();
    }
    return started;
}

}  // namespace makeway::sim
