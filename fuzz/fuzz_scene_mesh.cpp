// libFuzzer target: a scene that loads user meshes (read_scene with its folder) must either read
// or throw FileError; never crash, hang or leak. The input is the scene YAML, a NUL byte, then the
// bytes of the mesh file the scene may name as m.ply, m.obj, m.stl or m.dae (all four are written).
// The mesh reader's time limit (2 s; 60 s for users) stays below libFuzzer's -timeout (10 s), as
// in fuzz_mesh.
#include <cstddef>
#include <cstdint>

#include "fuzz/fuzz_util.hpp"
#include "io/error.hpp"
#include "io/file_util.hpp"
#include "io/scene_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto [scene, mesh] = makeway::fuzz::split_at_nul(data, size);
    const auto& dir = makeway::fuzz::private_dir();
    try {
        for (const char* name : {"m.ply", "m.obj", "m.stl", "m.dae"})
            makeway::io::write_file_atomic(dir / name, mesh);
        makeway::io::write_file_atomic(dir / "scene.yaml", scene);
        makeway::io::read_scene(dir / "scene.yaml", {.mesh_limits = {.seconds = 2.0}});
    } catch (const makeway::io::FileError&) {
    }
    return 0;
}
