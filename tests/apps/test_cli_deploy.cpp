// The cluster files in deploy/: the Kubernetes manifest parses and wires the Indexed Job's index
// into --shard and the merge onto the same volume; the Slurm array script, run by hand with the
// array variables Slurm would set, produces shards that its merge mode joins.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <fstream>

#include "../io/io_test_util.hpp"
#include "cli_test_util.hpp"
#include "io/json_io.hpp"

namespace makeway {
namespace {

using testing_util::run_shell;

const std::filesystem::path kDeploy = std::filesystem::path(MAKEWAY_SOURCE_DIR) / "deploy";

TEST(Deploy, KubernetesIndexedJobShardsAndMerges) {
    const std::vector<YAML::Node> docs =
        YAML::LoadAllFromFile((kDeploy / "k8s" / "bench-nav.yaml").string());
    ASSERT_EQ(docs.size(), 3u);
    EXPECT_EQ(docs[0]["kind"].as<std::string>(), "PersistentVolumeClaim");
    const std::string claim = docs[0]["metadata"]["name"].as<std::string>();
    const YAML::Node shards = docs[1], merge = docs[2];
    EXPECT_EQ(shards["kind"].as<std::string>(), "Job");
    EXPECT_EQ(shards["apiVersion"].as<std::string>(), "batch/v1");
    EXPECT_EQ(shards["spec"]["completionMode"].as<std::string>(), "Indexed");
    const int n = shards["spec"]["completions"].as<int>();
    EXPECT_EQ(shards["spec"]["parallelism"].as<int>(), n);
    const YAML::Node c = shards["spec"]["template"]["spec"]["containers"][0];
    std::string shard_count;
    for (const auto& e : c["env"]) {
        if (e["name"].as<std::string>() == "SHARDS") shard_count = e["value"].as<std::string>();
    }
    EXPECT_EQ(shard_count, std::to_string(n));
    const std::string args = c["args"][0].as<std::string>();
    EXPECT_NE(args.find("--shard \"$JOB_COMPLETION_INDEX/$SHARDS\""), std::string::npos) << args;
    EXPECT_NE(args.find("/results/shard-$JOB_COMPLETION_INDEX"), std::string::npos) << args;
    EXPECT_EQ(shards["spec"]["template"]["spec"]["restartPolicy"].as<std::string>(),
              "Never");  // required by Job
    for (const YAML::Node& job : {shards, merge}) {
        EXPECT_EQ(
            job["spec"]["template"]["spec"]["volumes"][0]["persistentVolumeClaim"]["claimName"]
                .as<std::string>(),
            claim);
    }
    EXPECT_NE(merge["spec"]["template"]["spec"]["containers"][0]["args"][0].as<std::string>().find(
                  "bench merge /results/shard-*"),
              std::string::npos);
    const YAML::Node wait = merge["spec"]["template"]["spec"]["initContainers"][0];
    EXPECT_EQ(wait["env"][0]["value"].as<std::string>(), std::to_string(n));
}

TEST(Deploy, SlurmArrayScriptDryRunThenMerge) {
    const auto dir = testing_util::fresh_dir("deploy_slurm");
    std::ofstream(dir / "fast.yaml") << "lidar:\n  azimuth_step_deg: 1.0\n";
    const std::string env = "MAKEWAY=" + std::string(MAKEWAY_BIN) +
                            " RESULTS=" + (dir / "res").string() +
                            " SCENES=2 EXTRA='--methods oppo --time-limit 20 --config " +
                            (dir / "fast.yaml").string() + "'";
    const std::string script = "bash " + (kDeploy / "slurm" / "bench-nav.sbatch").string();
    EXPECT_EQ(run_shell("bash -n " + (kDeploy / "slurm" / "bench-nav.sbatch").string() +
                            " && bash -n " + (kDeploy / "slurm" / "submit.sh").string(),
                        dir)
                  .exit_code,
              0);
    // Slurm numbers this array's tasks 5 and 6 (--array=5-6): the script maps them to shards 0
    // and 1.
    for (int task : {5, 6}) {
        const auto r = run_shell(
            env + " SLURM_ARRAY_TASK_ID=" + std::to_string(task) +
                " SLURM_ARRAY_TASK_MIN=5 SLURM_ARRAY_TASK_COUNT=2 SLURM_CPUS_PER_TASK=1 " + script,
            dir);
        ASSERT_EQ(r.exit_code, 0) << r.err;
    }
    EXPECT_TRUE(std::filesystem::exists(dir / "res" / "shard-1" / "partial.json"));
    const auto merged = run_shell(env + " MODE=merge SHARDS=2 " + script, dir);
    ASSERT_EQ(merged.exit_code, 0) << merged.err;
    const io::Json results = io::read_json(dir / "res" / "merged" / "results.json");
    EXPECT_EQ(results["runs"].size(), 2u);
    EXPECT_EQ(results["runs"][1]["scene_index"], 1);
    // Outside an array, the script says what it needs.
    const auto bare = run_shell(env + " " + script, dir);
    EXPECT_NE(bare.exit_code, 0);
    EXPECT_NE(bare.err.find("SLURM_ARRAY_TASK_ID"), std::string::npos) << bare.err;
}

}  // namespace
}  // namespace makeway
