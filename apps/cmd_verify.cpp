// makeway bench verify: the CAD verification benchmark (matched and mismatched models).
#include <iostream>

#include "apps/commands.hpp"
#include "io/json_io.hpp"
#include "io/progress.hpp"
#include "makeway/eval/verify_bench.hpp"

namespace makeway::apps {
namespace {

io::Json to_json(const eval::OrientationStats& s) {
    return {{"objects", s.objects},
            {"yaw_within_10deg", s.yaw_within_10deg},
            {"yaw_within_30deg", s.yaw_within_30deg},
            {"median_yaw_error_deg", s.median_yaw_error_deg},
            {"median_centre_error_m", s.median_centre_error_m}};
}

io::Json to_json(const eval::VerifyBenchArm& a) {
    return {{"before", to_json(a.before)},
            {"after", to_json(a.after)},
            {"true_rejection_rate", a.true_rejection_rate},
            {"false_acceptance_rate", a.false_acceptance_rate},
            {"ms_per_object_median", a.ms_per_object_median},
            {"ms_per_object_p99", a.ms_per_object_p99}};
}

}  // namespace

int run_bench_verify(const BenchVerifyOptions& options) {
    eval::VerifyBenchParams p;
    p.scenes = options.scenes;
    p.seed = options.seed;
    io::ProgressBar bar("bench verify", static_cast<std::size_t>(p.scenes));
    const eval::VerifyBenchResult r = eval::run_verify_bench(p, [&](int done, int) { bar.update(static_cast<std::size_t>(done)); });
    bar.finish();
    const io::Json j = {{"scenes", p.scenes},
                        {"seed", p.seed},
                        {"true_boxes", r.true_boxes},
                        {"false_boxes", r.false_boxes},
                        {"matched", to_json(r.matched)},
                        {"mismatched", to_json(r.mismatched)}};
    io::write_json(std::filesystem::path(options.out_dir) / "summary.json", j);
    std::cout << j.dump(2) << "\n";
    return 0;
}

}  // namespace makeway::apps
