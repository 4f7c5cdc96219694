#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "io/cad_folder.hpp"
#include "io/error.hpp"
#include "io/furniture_folder.hpp"
#include "io/mesh_io.hpp"
#include "io/scene_io.hpp"
#include "io_test_util.hpp"
#include "makeway/sim/lidar.hpp"
#include "makeway/sim/mesh_primitives.hpp"
#include "makeway/sim/robot.hpp"
#include "makeway/sim/scene_generator.hpp"

namespace makeway::io {
namespace {

std::string scene_problem_of(const std::string& yaml) {
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
    std::ofstream(dir / "s.yaml")
        << "name: crate_room\nfloor: {min_m: [-5, -5], max_m: [5, 5]}\n"
           "objects:\n  - {id: 7, class: table, mesh: crate.stl, scale: 0.8, "
           "pose: {x_m: 2, y_m: 0, yaw_rad: 0}}\n";
    const sim::Scene s = read_scene(dir / "s.yaml");
    ASSERT_TRUE(s.objects[0].user_mesh);
    const sim::ObjectModel model = sim::model_of(s.objects[0]);
    EXPECT_NEAR(model.box_object.size_m.z(), 0.8, 1e-6);
    sim::World world(s, {model});
    sim::LidarParams lidar;
    const PointCloud c = sim::simulate_sweep(
        world, lidar,
        [](double) {
            return make_T_xyz_yaw({0, 0, 0.45}, 0);
        },
        0, 1, 0);
    std::size_t hits = 0;
    for (std::size_t i = 0; i < c.size(); ++i) {
        if (c.instance[i] != 7) continue;
        ++hits;
        EXPECT_EQ(c.label[i], static_cast<std::uint8_t>(SemanticLabel::kTable));
        EXPECT_NEAR(c.xyz[i].x(), 1.6f, 0.06f);  // the near face at x = 2 - 0.4
    }
    EXPECT_GT(hits, 200u);
}

// The caller's limits on the mesh reader reach the scene's meshes (a fuzzer gives a shorter time
// than a user's 60 s): with no time at all the read fails, naming the scene and the limit.
TEST(SceneIo, TheMeshReadersLimitsReachTheScenesMeshes) {
    const auto dir = testing_util::fresh_dir("mesh_limits");
    TriangleMesh cube;
    sim::add_box(cube, {0, 0, 0.5}, {1, 1, 1});
    write_mesh(dir / "crate.stl", cube);
    std::ofstream(dir / "s.yaml") << "name: crate_room\nfloor: {min_m: [-5, -5], max_m: [5, 5]}\n"
                                     "objects:\n  - {id: 7, class: table, mesh: crate.stl, "
                                     "pose: {x_m: 2, y_m: 0, yaw_rad: 0}}\n";
    EXPECT_TRUE(read_scene(dir / "s.yaml").objects[0].user_mesh);
    try {
        (void)read_scene(dir / "s.yaml", {.mesh_limits = {.seconds = 0.0}});
        FAIL() << "read with no time left";
    } catch (const FileError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("s.yaml"), std::string::npos) << what;
        EXPECT_NE(what.find("took longer than 0 s"), std::string::npos) << what;
    }
}

// A room given as one mesh (as a scan of a building would be): a 6 x 4 m shell of 2.5 m walls
// with a floor slab, drawn Y-up in centimetres around its own origin at the room's corner.
TriangleMesh scanned_shell_y_up_cm() {
    TriangleMesh m;
    sim::add_box(m, {300, 125, -5}, {600, 250, 10});   // east wall ... in (x, y-up, z) cm
    sim::add_box(m, {300, 125, 405}, {600, 250, 10});  // west wall
    sim::add_box(m, {-5, 125, 200}, {10, 250, 400});
    sim::add_box(m, {605, 125, 200}, {10, 250, 400});
    sim::add_box(m, {300, -1, 200}, {600, 2, 400});  // the floor, 2 cm thick, its top at 0
    return m;
}

TEST(SceneIo, AnEnvironmentMeshIsPlacedPosedSeenAndSolid) {
    const auto dir = testing_util::fresh_dir("environment");
    write_mesh(dir / "scan.ply", scanned_shell_y_up_cm());
    // The scan's x along the world's y: its corner at (1, -3), its floor 5 cm below ours.
    std::ofstream(dir / "s.yaml")
        << "name: scanned\nfloor: {min_m: [-6, -6], max_m: [6, 6]}\n"
           "environment:\n  - {mesh: scan.ply, units: cm, up_axis: y, forward_axis: x, "
           "pose: {x_m: 1, y_m: -3, z_m: -0.05, yaw_rad: 1.5707963267948966}}\n";
    const sim::Scene s = read_scene(dir / "s.yaml");
    ASSERT_EQ(s.environment.size(), 1u);
    ASSERT_TRUE(s.environment[0].mesh_world);
    Eigen::Vector3d lo, hi;
    mesh_bounds(*s.environment[0].mesh_world, lo, hi);
    // Y-up cm: the scan's z (depth) becomes -y, then the yaw turns it to +x: scan (x, z) 0..600 x
    // 0..400 cm -> world y -3..3, x 1..5, walls 10 cm thick outside that, 2.5 m tall, standing on
    // a floor 5 cm below the scene's.
    EXPECT_NEAR(lo.x(), 1.0 - 0.1, 1e-4);
    EXPECT_NEAR(hi.x(), 5.0 + 0.1, 1e-4);
    EXPECT_NEAR(lo.y(), -3.0 - 0.1, 1e-4);
    EXPECT_NEAR(hi.y(), 3.0 + 0.1, 1e-4);
    EXPECT_NEAR(hi.z(), 2.5 - 0.05, 1e-4);
    // Written back and read again: the same entry, the same mesh.
    write_scene(dir / "back.yaml", s);
    const sim::Scene back = read_scene(dir / "back.yaml");
    ASSERT_EQ(back.environment.size(), 1u);
    EXPECT_EQ(scene_to_yaml(back), scene_to_yaml(s));
    EXPECT_EQ(back.environment[0].mesh_world->num_triangles(),
              s.environment[0].mesh_world->num_triangles());
    // The LiDAR sees it as structure: from the room's middle (3, 0), 45 cm up, the wall ahead (+x)
    // with its inner face at x = 5.
    sim::World world(s, {});
    const PointCloud c = sim::simulate_sweep(
        world, sim::LidarParams{},
        [](double) {
            return make_T_xyz_yaw({3, 0, 0.45}, 0);
        },
        0, 1, 0);
    std::size_t ahead = 0;
    for (std::size_t i = 0; i < c.size(); ++i) {
        const Eigen::Vector3f& p = c.xyz[i];
        if (std::abs(p.y()) > 0.3f || p.z() < 0.2f || p.z() > 1.5f || p.x() < 0.0f) continue;
        ++ahead;
        EXPECT_EQ(c.label[i], static_cast<std::uint8_t>(SemanticLabel::kStructure));
        EXPECT_NEAR(p.x(), 2.0f, 0.06f);  // the inner face, 2 m ahead of the sensor
    }
    EXPECT_GT(ahead, 20u);
    // Solid for the robot: its footprint at the wall collides, in the middle of the room it does
    // not (the floor slab, below the body's ground clearance, is rolled over).
    const sim::CollisionChecker checker(s, {}, sim::RobotParams{});
    EXPECT_TRUE(checker.collides({4.9, 0.0, 0.0}, 0.0));
    EXPECT_FALSE(checker.collides({3.0, 0.0, 0.0}, 0.0));
    // A scene names its meshes inside its folder, environment meshes too.
    std::ofstream(dir / "out.yaml") << "name: o\nfloor: {min_m: [-6, -6], max_m: [6, 6]}\n"
                                       "environment:\n  - {mesh: ../scan.ply}\n";
    try {
        read_scene(dir / "out.yaml");
        ADD_FAILURE() << "a mesh outside the folder was read";
    } catch (const FileError& e) {
        EXPECT_NE(std::string(e.what()).find("outside the scene's folder"), std::string::npos)
            << e.what();
    }
    EXPECT_NE(scene_problem_of("name: n\nenvironment:\n  - {units: cm}\n").find("mesh: required"),
              std::string::npos);
}

TEST(SceneIo, EveryProblemIsListed) {
    EXPECT_EQ(
        scene_problem_of("objects:\n  - {id: 1, class: chair, style: throne, pose: {x_m: 0, y_m: "
                         "0, yaw_rad: 0}}\n"),
        "objects[0]: unknown style 'throne'");
    EXPECT_EQ(scene_problem_of("objects:\n  - {id: 1, class: table, style: stool}\n"),
              "objects[0]: style 'stool' is not a table");
    const std::string many = scene_problem_of(
        "floor: {min_m: [0, 0], max_m: [-1, 5]}\nobjects:\n  - {id: 1, class: sofa, style: stool}\n"
        "  - {id: 1, class: chair, style: stool, colour: red}\npushers:\n  - {chair_id: 9, "
        "period_s: 0}\n");
    EXPECT_EQ(many.rfind("6 problems: ", 0), 0u) << many;
    for (const char* part :
         {"class must be chair or table (got 'sofa')", "objects[1].colour: unknown key",
          "object 1: duplicate id", "pusher: chair 9 does not exist", "period_s must be > 0",
          "floor: max must exceed min"}) {
        EXPECT_NE(many.find(part), std::string::npos) << part << " missing from " << many;
    }
    EXPECT_EQ(scene_problem_of("walls: 3\n"), "walls: must be a list");
    EXPECT_NE(scene_problem_of("walls:\n  - {a_m: [0], b_m: [1, 1]}\n")
                  .find("walls[0].a_m: must be a pair"),
              std::string::npos);
    EXPECT_EQ(scene_problem_of("[1, 2]\n"),
              "a scene must be a mapping (name, walls, objects, ...)");
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
        std::ofstream(dir / "scene" / "s.yaml")
            << "objects:\n  - {id: 1, class: table, mesh: '" << mesh << "'}\n";
        return dir / "scene" / "s.yaml";
    };
    for (const std::string& mesh :
         {std::string("../crate.stl"), (dir / "crate.stl").string(),
          std::string("meshes/../../crate.stl"), std::string("link.stl")}) {
        try {
            read_scene(scene_with(mesh));
            ADD_FAILURE() << mesh << " was read";
        } catch (const FileError& e) {
            EXPECT_NE(
                std::string(e.what()).find("mesh '" + mesh + "' is outside the scene's folder"),
                std::string::npos)
                << e.what();
        }
        EXPECT_TRUE(
            read_scene(scene_with(mesh), {.allow_outside_paths = true}).objects[0].user_mesh)
            << mesh;
    }
    EXPECT_TRUE(read_scene(scene_with("meshes/inside.stl")).objects[0].user_mesh);
    EXPECT_TRUE(read_scene(scene_with("meshes/../meshes/inside.stl")).objects[0].user_mesh);
}

}  // namespace
}  // namespace makeway::io

namespace makeway::io {
namespace {

// A chair-like block 0.5 wide, 0.4 deep, 0.9 tall with a back rest (a thin slab at its rear),
// written as an author would: in `unit`s, with `up` and `forward` axes, its origin at a corner.
TriangleMesh authored_chair(const Eigen::Vector3d& up, const Eigen::Vector3d& forward,
                            double unit) {
    const Eigen::Vector3d side = up.cross(forward);
    TriangleMesh seat, back;
    sim::add_box(seat, Eigen::Vector3d(0, 0, 0.225), Eigen::Vector3d(0.4, 0.5, 0.45));
    sim::add_box(back, Eigen::Vector3d(-0.18, 0, 0.675), Eigen::Vector3d(0.04, 0.5, 0.45));
    seat.append(back);
    Eigen::Matrix3d R;  // object frame (x forward, z up) into the author's axes
    R.col(0) = forward;
    R.col(1) = side;
    R.col(2) = up;
    for (auto& v : seat.vertices_m)
        v = ((R * (v.cast<double>() + Eigen::Vector3d(0.2, 0.25, 0.0))) / unit).cast<float>();
    return seat;
}

std::string collada(const TriangleMesh& m, const char* up_axis) {
    std::ostringstream pos, idx;
    for (const auto& v : m.vertices_m) pos << v.x() << " " << v.y() << " " << v.z() << " ";
    for (const auto& t : m.triangles) idx << t.x() << " " << t.y() << " " << t.z() << " ";
    std::ostringstream out;
    out << R"(<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1"><asset><unit meter="1" name="meter"/>)"
        << (up_axis ? std::string("<up_axis>") + up_axis + "</up_axis>" : "") << R"(</asset>
<library_geometries><geometry id="g"><mesh><source id="p"><float_array id="pa" count=")"
        << 3 * m.vertices_m.size() << "\">" << pos.str()
        << R"(</float_array><technique_common><accessor source="#pa" count=")"
        << m.vertices_m.size() << R"(" stride="3">
<param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/></accessor></technique_common></source>
<vertices id="v"><input semantic="POSITION" source="#p"/></vertices><triangles count=")"
        << m.triangles.size() << R"("><input semantic="VERTEX" source="#v" offset="0"/><p>)"
        << idx.str() << R"(</p></triangles></mesh></geometry></library_geometries>
<library_visual_scenes><visual_scene id="s"><node id="n"><instance_geometry url="#g"/></node></visual_scene></library_visual_scenes>
<scene><instance_visual_scene url="#s"/></scene></COLLADA>)";
    return out.str();
}

// The placed mesh is the chair upright, 0.4 deep along x, its back rest at -x, on the floor,
// centred.
void expect_upright_facing_x(const TriangleMesh& m, const std::string& what) {
    Eigen::Vector3f lo = m.vertices_m[0], hi = lo;
    for (const auto& v : m.vertices_m) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
    EXPECT_NEAR(hi.z() - lo.z(), 0.9, 1e-4) << what;
    EXPECT_NEAR(hi.x() - lo.x(), 0.4, 1e-4) << what;
    EXPECT_NEAR(hi.y() - lo.y(), 0.5, 1e-4) << what;
    EXPECT_NEAR(lo.z(), 0.0, 1e-4) << what;
    EXPECT_NEAR(lo.x() + hi.x(), 0.0, 1e-4) << what;
    EXPECT_NEAR(lo.y() + hi.y(), 0.0, 1e-4) << what;
    // Every vertex above the seat (z > 0.5) belongs to the back rest, behind the seat's centre.
    for (const auto& v : m.vertices_m) {
        if (v.z() > 0.5f) {
            EXPECT_LT(v.x(), -0.15f) << what;
        }
    }
}

TEST(SceneIo, MeshesOfOtherToolsArePlacedAsTheirFilesAndTheSceneSay) {
    const auto dir = testing_util::fresh_dir("mesh_axes");
    const Eigen::Vector3d Y = Eigen::Vector3d::UnitY(), Z = Eigen::Vector3d::UnitZ();
    // Collada declares its up axis: Z_UP (Gazebo's worlds) and Y_UP (Blender's default export), and
    // none (the spec's default, Y_UP). Facing -y in the Z-up file, +z in the Y-up ones.
    std::ofstream(dir / "zup.dae") << collada(authored_chair(Z, -Y, 1.0), "Z_UP");
    std::ofstream(dir / "yup.dae") << collada(authored_chair(Y, Z, 1.0), "Y_UP");
    std::ofstream(dir / "noup.dae") << collada(authored_chair(Y, Z, 1.0), nullptr);
    // OBJ from a Y-up tool in centimetres facing -z; binary STL Z-up in millimetres facing +y.
    write_mesh(dir / "yup_cm.obj", authored_chair(Y, -Z, 0.01));
    write_mesh(dir / "zup_mm.stl", authored_chair(Z, Y, 0.001));
    std::ofstream(dir / "s.yaml")
        << "floor: {min_m: [-5, -5], max_m: [5, 5]}\nobjects:\n"
           "  - {id: 1, class: chair, mesh: zup.dae, forward_axis: -y, pose: {x_m: 0, y_m: 0, "
           "yaw_rad: 0}}\n"
           "  - {id: 2, class: chair, mesh: yup.dae, forward_axis: -y, pose: {x_m: 1, y_m: 0, "
           "yaw_rad: 0}}\n"
           "  - {id: 3, class: chair, mesh: noup.dae, forward_axis: -y, pose: {x_m: 2, y_m: 0, "
           "yaw_rad: 0}}\n"
           "  - {id: 4, class: chair, mesh: yup_cm.obj, units: cm, up_axis: y, forward_axis: -z, "
           "pose: {x_m: 3, y_m: 0, yaw_rad: 0}}\n"
           "  - {id: 5, class: chair, mesh: zup_mm.stl, units: mm, forward_axis: y, pose: {x_m: 4, "
           "y_m: 0, yaw_rad: 0}}\n";
    // The Y-up Collada files are turned Z-up by the reader (their +z front becomes -y).
    std::vector<std::string> warnings;
    SceneReadOptions options;
    options.warn = [&](const std::string& w) { warnings.push_back(w); };
    const sim::Scene s = read_scene(dir / "s.yaml", options);
    ASSERT_EQ(s.objects.size(), 5u);
    for (const sim::SceneObject& o : s.objects) {
        ASSERT_TRUE(o.user_mesh) << o.mesh_file;
        expect_upright_facing_x(*o.user_mesh, o.mesh_file);
    }
    EXPECT_TRUE(warnings.empty()) << warnings.front();
    // Written back and read again: the same placement.
    write_scene(dir / "again.yaml", s);
    const sim::Scene again = read_scene(dir / "again.yaml", options);
    for (const sim::SceneObject& o : again.objects)
        expect_upright_facing_x(*o.user_mesh, "again " + o.mesh_file);
    // Units forgotten: readable, with a warning naming the object and the file.
    std::ofstream(dir / "w.yaml")
        << "objects:\n  - {id: 1, class: chair, mesh: yup_cm.obj, up_axis: y, forward_axis: -z}\n";
    read_scene(dir / "w.yaml", options);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("objects[0]: mesh yup_cm.obj: "), std::string::npos) << warnings[0];
    EXPECT_NE(warnings[0].find("wrong units or up axis"), std::string::npos) << warnings[0];
    // Bad axes and units are problems of the scene file.
    std::ofstream(dir / "bad.yaml") << "objects:\n  - {id: 1, class: chair, mesh: zup.dae, "
                                       "up_axis: y, forward_axis: -y, units: cubits}\n";
    try {
        read_scene(dir / "bad.yaml", options);
        ADD_FAILURE() << "no error";
    } catch (const FileError& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find("up_axis and forward_axis are parallel"), std::string::npos) << msg;
        EXPECT_NE(msg.find("units must be m, cm, mm, in or ft (got 'cubits')"), std::string::npos)
            << msg;
    }
}

TEST(FurnitureFolder, AnIndexSaysHowEachMeshWasDrawn) {
    const auto dir = testing_util::fresh_dir("furniture");
    const Eigen::Vector3d Y = Eigen::Vector3d::UnitY(), Z = Eigen::Vector3d::UnitZ();
    std::filesystem::create_directories(dir / "f" / "chairs");
    std::ofstream(dir / "f" / "cafe.dae") << collada(authored_chair(Z, -Y, 1.0), "Z_UP");
    write_mesh(dir / "f" / "chairs" / "stacking.obj", authored_chair(Y, -Z, 0.01));
    write_mesh(dir / "f" / "bench.stl", authored_chair(Z, Y, 0.001));
    std::ofstream(dir / "f" / "furniture.yaml")
        << "furniture:\n"
           "  - {file: cafe.dae, class: table, forward_axis: -y}\n"
           "  - {file: chairs/stacking.obj, class: chair, units: cm, up_axis: y, forward_axis: "
           "-z}\n"
           "  - {file: bench.stl, class: chair, units: mm, forward_axis: y}\n";
    std::vector<std::string> warnings;
    const auto meshes =
        read_furniture_folder(dir / "f", [&](const std::string& w) { warnings.push_back(w); });
    ASSERT_EQ(meshes.size(), 3u);
    EXPECT_EQ(meshes[0].name, "cafe");
    EXPECT_EQ(meshes[0].cls, ObjectClass::kTable);
    EXPECT_EQ(meshes[1].name, "chairs/stacking");
    for (const FurnitureMesh& m : meshes) expect_upright_facing_x(*m.mesh_object, m.name);
    EXPECT_TRUE(warnings.empty());
    // The same folder is a CAD library for verify, run and label.
    EXPECT_EQ(read_cad_folder(dir / "f").models().size(), 3u);
    // Every problem of the index at once, naming the index; files outside the folder refused.
    std::ofstream(dir / "f" / "furniture.yaml")
        << "furniture:\n"
           "  - {file: cafe.dae, class: sofa}\n"
           "  - {file: ../outside.obj, class: chair}\n"
           "  - {file: bench.stl, class: chair, up_axis: q}\n";
    try {
        read_furniture_folder(dir / "f");
        ADD_FAILURE() << "no error";
    } catch (const FileError& e) {
        const std::string msg = e.what();
        EXPECT_EQ(msg.rfind((dir / "f" / "furniture.yaml").string(), 0), 0u) << msg;
        EXPECT_NE(msg.find("furniture[0]: class must be chair or table (got 'sofa')"),
                  std::string::npos)
            << msg;
        EXPECT_NE(msg.find("furniture[1]: file '../outside.obj' is outside the folder"),
                  std::string::npos)
            << msg;
        EXPECT_NE(msg.find("furniture[2]: up_axis must be"), std::string::npos) << msg;
    }
    // Without an index: names say the class.
    std::filesystem::create_directories(dir / "g");
    write_mesh(dir / "g" / "table_a.stl", authored_chair(Z, Eigen::Vector3d::UnitX(), 1.0));
    EXPECT_EQ(read_furniture_folder(dir / "g").front().cls, ObjectClass::kTable);
    write_mesh(dir / "g" / "lamp.stl", authored_chair(Z, Eigen::Vector3d::UnitX(), 1.0));
    EXPECT_THROW(read_furniture_folder(dir / "g"), FileError);
}

}  // namespace
}  // namespace makeway::io
