#include <gtest/gtest.h>

#include <fstream>

#include "io/error.hpp"
#include "io/mesh_io.hpp"
#include "io/scene_io.hpp"
#include "io_test_util.hpp"
#include "makeway/sim/lidar.hpp"
#include "makeway/sim/mesh_primitives.hpp"
#include "makeway/sim/scene_generator.hpp"

namespace makeway::io {
namespace {

std::string problem_of(const std::string& yaml) {
    try {
        parse_scene(yaml);
    } catch (const FormatError& e) {
        return e.what();
    }
    return "";
}

TEST(SceneIo, GeneratedSceneRoundTripsExactly) {
    const auto dir = testing_util::fresh_dir("rt");
    const sim::Scene s = sim::generate_scene({.seed = 5, .density = sim::Density::kDense});
    write_scene(dir / "s.yaml", s);
    const sim::Scene back = read_scene(dir / "s.yaml");
    EXPECT_EQ(scene_to_yaml(back), scene_to_yaml(s));
    ASSERT_EQ(back.objects.size(), s.objects.size());
    for (std::size_t i = 0; i < s.objects.size(); ++i) {
        EXPECT_EQ(back.objects[i].pose.x_m, s.objects[i].pose.x_m);  // 17 digits: exact
        EXPECT_EQ(back.objects[i].pose.yaw_rad, s.objects[i].pose.yaw_rad);
        EXPECT_EQ(back.objects[i].model_seed, s.objects[i].model_seed);
        EXPECT_EQ(back.objects[i].table_id, s.objects[i].table_id);
    }
    EXPECT_EQ(back.walkers.size(), s.walkers.size());
    EXPECT_EQ(back.pushers.size(), s.pushers.size());
}

TEST(SceneIo, UserMeshIsLoadedScaledAndHitByRays) {
    const auto dir = testing_util::fresh_dir("mesh");
    TriangleMesh cube;
    sim::add_box(cube, {0, 0, 0.5}, {1, 1, 1});
    write_mesh(dir / "crate.stl", cube);
    std::ofstream(dir / "s.yaml") << "name: crate_room\nfloor: {min_m: [-5, -5], max_m: [5, 5]}\n"
                                     "objects:\n  - {id: 7, class: table, mesh: crate.stl, scale: 0.8, "
                                     "pose: {x_m: 2, y_m: 0, yaw_rad: 0}}\n";
    const sim::Scene s = read_scene(dir / "s.yaml");
    ASSERT_TRUE(s.objects[0].user_mesh);
    const sim::ObjectModel model = sim::model_of(s.objects[0]);
    EXPECT_NEAR(model.box_object.size_m.z(), 0.8, 1e-6);
    sim::World world(s, {model});
    sim::LidarParams lidar;
    const PointCloud c = sim::simulate_sweep(world, lidar, [](double) { return make_T_xyz_yaw({0, 0, 0.45}, 0); }, 0, 1, 0);
    std::size_t hits = 0;
    for (std::size_t i = 0; i < c.size(); ++i) {
        if (c.instance[i] != 7) continue;
        ++hits;
        EXPECT_EQ(c.label[i], static_cast<std::uint8_t>(SemanticLabel::kTable));
        EXPECT_NEAR(c.xyz[i].x(), 1.6f, 0.06f);  // the near face at x = 2 - 0.4
    }
    EXPECT_GT(hits, 200u);
}

TEST(SceneIo, EveryProblemIsListed) {
    EXPECT_EQ(problem_of("objects:\n  - {id: 1, class: chair, style: throne, pose: {x_m: 0, y_m: 0, yaw_rad: 0}}\n"),
              "objects[0]: unknown style 'throne'");
    EXPECT_EQ(problem_of("objects:\n  - {id: 1, class: table, style: stool}\n"),
              "objects[0]: style 'stool' is not a table");
    const std::string many = problem_of(
        "floor: {min_m: [0, 0], max_m: [-1, 5]}\nobjects:\n  - {id: 1, class: sofa, style: stool}\n"
        "  - {id: 1, class: chair, style: stool, colour: red}\npushers:\n  - {chair_id: 9, period_s: 0}\n");
    EXPECT_EQ(many.rfind("6 problems: ", 0), 0u) << many;
    for (const char* part : {"class must be chair or table (got 'sofa')", "objects[1].colour: unknown key",
                             "object 1: duplicate id", "pusher: chair 9 does not exist", "period_s must be > 0",
                             "floor: max must exceed min"}) {
        EXPECT_NE(many.find(part), std::string::npos) << part << " missing from " << many;
    }
    EXPECT_EQ(problem_of("walls: 3\n"), "walls: must be a list");
    EXPECT_NE(problem_of("walls:\n  - {a_m: [0], b_m: [1, 1]}\n").find("walls[0].a_m: must be a pair"), std::string::npos);
    EXPECT_EQ(problem_of("[1, 2]\n"), "a scene must be a mapping (name, walls, objects, ...)");
}

TEST(SceneIo, MissingMeshNamesBothFiles) {
    const auto dir = testing_util::fresh_dir("missing");
    std::ofstream(dir / "s.yaml") << "objects:\n  - {id: 1, class: chair, mesh: nope.obj}\n";
    try {
        read_scene(dir / "s.yaml");
        FAIL();
    } catch (const FileError& e) {
        const std::string msg = e.what();
        EXPECT_EQ(msg.rfind((dir / "s.yaml").string() + ": objects[0]: mesh ", 0), 0u) << msg;
        EXPECT_NE(msg.find("nope.obj: no such file"), std::string::npos) << msg;
    }
}

TEST(SceneIo, MeshPathsStayInsideTheScenesFolder) {
    // A scene file from elsewhere must not read other files: ../, absolute paths and links out are
    // refused unless allowed (was: any path was read).
    const auto dir = testing_util::fresh_dir("outside");
    TriangleMesh cube;
    sim::add_box(cube, {0, 0, 0.5}, {1, 1, 1});
    write_mesh(dir / "crate.stl", cube);
    std::filesystem::create_directories(dir / "scene" / "meshes");
    write_mesh(dir / "scene" / "meshes" / "inside.stl", cube);
    std::filesystem::create_symlink(dir / "crate.stl", dir / "scene" / "link.stl");
    const auto scene_with = [&](const std::string& mesh) {
        std::ofstream(dir / "scene" / "s.yaml") << "objects:\n  - {id: 1, class: table, mesh: '" << mesh << "'}\n";
        return dir / "scene" / "s.yaml";
    };
    for (const std::string& mesh : {std::string("../crate.stl"), (dir / "crate.stl").string(), std::string("meshes/../../crate.stl"),
                                   std::string("link.stl")}) {
        try {
            read_scene(scene_with(mesh));
            ADD_FAILURE() << mesh << " was read";
        } catch (const FileError& e) {
            EXPECT_NE(std::string(e.what()).find("mesh '" + mesh + "' is outside the scene's folder"), std::string::npos) << e.what();
        }
        EXPECT_TRUE(read_scene(scene_with(mesh), {.allow_outside_paths = true}).objects[0].user_mesh) << mesh;
    }
    EXPECT_TRUE(read_scene(scene_with("meshes/inside.stl")).objects[0].user_mesh);
    EXPECT_TRUE(read_scene(scene_with("meshes/../meshes/inside.stl")).objects[0].user_mesh);
}

}  // namespace
}  // namespace makeway::io
