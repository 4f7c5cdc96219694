#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <iterator>

#include "io/error.hpp"
#include "io/mesh_io.hpp"
#include "io_test_util.hpp"

namespace makeway::io {
namespace {

TriangleMesh unit_cube() {
    TriangleMesh m;
    for (int i = 0; i < 8; ++i) m.vertices_m.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
    const int faces[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                              {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
    for (const auto& f : faces) m.triangles.emplace_back(f[0], f[1], f[2]);
    return m;
}

// Compares meshes as sets of triangles given by their corner positions (writers may reorder or
// duplicate vertices).
std::vector<std::array<float, 9>> triangle_set(const TriangleMesh& m) {
    std::vector<std::array<float, 9>> out;
    for (const auto& t : m.triangles) {
        std::array<Eigen::Vector3f, 3> c{m.vertices_m[t[0]], m.vertices_m[t[1]],
                                         m.vertices_m[t[2]]};
        // Rotate so the smallest corner comes first, keeping the winding.
        const auto less = [](const Eigen::Vector3f& a, const Eigen::Vector3f& b) {
            return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
        };
        std::rotate(c.begin(), std::min_element(c.begin(), c.end(), less), c.end());
        std::array<float, 9> key;
        for (int k = 0; k < 3; ++k) std::copy(c[k].data(), c[k].data() + 3, key.begin() + 3 * k);
        out.push_back(key);
    }
    std::sort(out.begin(), out.end());
    return out;
}

class MeshRoundTrip : public ::testing::TestWithParam<const char*> {};

TEST_P(MeshRoundTrip, WriteThenReadKeepsTriangles) {
    const auto dir = testing_util::fresh_dir("mesh");
    const auto path = dir / (std::string("cube.") + GetParam());
    write_mesh(path, unit_cube());
    const TriangleMesh back = read_mesh(path);
    EXPECT_EQ(back.num_triangles(), 12u);
    EXPECT_EQ(triangle_set(back), triangle_set(unit_cube()));
}

INSTANTIATE_TEST_SUITE_P(Formats, MeshRoundTrip, ::testing::Values("obj", "ply", "stl"),
                         [](const ::testing::TestParamInfo<const char*>& p) {
                             return std::string(p.param);
                         });

TEST(MeshIo, ReadsTextFormatsOfOtherTools) {
    const std::string obj = "# quad\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
    EXPECT_EQ(parse_mesh(obj, "obj").num_triangles(), 2u);  // triangulated
    const std::string stl =
        "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
        "endloop\nendfacet\nendsolid t\n";
    EXPECT_EQ(parse_mesh(stl, "stl").num_triangles(), 1u);
    const std::string dae = R"(<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
 <asset><unit meter="1" name="meter"/><up_axis>Z_UP</up_axis></asset>
 <library_geometries><geometry id="g"><mesh>
  <source id="p"><float_array id="pa" count="9">0 0 0 1 0 0 0 1 0</float_array>
   <technique_common><accessor source="#pa" count="3" stride="3">
    <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
   </accessor></technique_common></source>
  <vertices id="v"><input semantic="POSITION" source="#p"/></vertices>
  <triangles count="1"><input semantic="VERTEX" source="#v" offset="0"/><p>0 1 2</p></triangles>
 </mesh></geometry></library_geometries>
 <library_visual_scenes><visual_scene id="s"><node id="n"><instance_geometry url="#g"/></node>
 </visual_scene></library_visual_scenes><scene><instance_visual_scene url="#s"/></scene>
</COLLADA>)";
    EXPECT_EQ(parse_mesh(dae, "dae").num_triangles(), 1u);
}

TEST(MeshIo, BadMeshesNameTheFileAndProblem) {
    const auto dir = testing_util::fresh_dir("bad");
    std::ofstream(dir / "garbage.obj") << "this is not a mesh at all\n";
    std::ofstream(dir / "points.obj") << "v 0 0 0\nv 1 0 0\n";
    std::ofstream(dir / "empty.stl").close();
    for (const char* name : {"garbage.obj", "points.obj", "empty.stl", "missing.dae"}) {
        try {
            read_mesh(dir / name);
            ADD_FAILURE() << name << " accepted";
        } catch (const FileError& e) {
            EXPECT_EQ(std::string(e.what()).rfind((dir / name).string() + ": ", 0), 0u) << e.what();
        }
    }
    EXPECT_THROW(write_mesh(dir / "x.fbx", unit_cube()), FileError);
    TriangleMesh broken = unit_cube();
    broken.triangles[0][1] = 99;
    EXPECT_THROW(write_mesh(dir / "x.obj", broken), FileError);
    EXPECT_FALSE(std::filesystem::exists(dir / "x.obj"));
}

TEST(MeshIo, ATruncatedBinaryPlyIsBadInputNotACrash) {
    // Cut short by 1 byte or more, a binary PLY mesh made assimp's post-processing read past the
    // buffer (SIGSEGV through `verify --cad` and a scene's `mesh:`); now every cut is exit-2 input.
    const auto dir = testing_util::fresh_dir("trunc_ply");
    write_mesh(dir / "cube.ply", unit_cube());
    std::ifstream in(dir / "cube.ply", std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    ASSERT_EQ(read_mesh(dir / "cube.ply").triangles.size(), 12u);
    const std::size_t header = bytes.find("end_header\n") + 11;
    for (std::size_t cut = 1; cut < bytes.size() - header; cut += 7) {
        std::ofstream(dir / "cut.ply", std::ios::binary) << bytes.substr(0, bytes.size() - cut);
        EXPECT_THROW(read_mesh(dir / "cut.ply"), FileError) << cut;
    }
}

}  // namespace
}  // namespace makeway::io
