#include "io/mesh_io.hpp"

#include <assimp/Exporter.hpp>
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <memory>

#include "io/error.hpp"
#include "io/file_util.hpp"
#include "io/ply.hpp"

namespace makeway::io {
namespace {

TriangleMesh collect_triangles(const aiScene& scene) {
    TriangleMesh out;
    for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
        const aiMesh& mesh = *scene.mMeshes[m];
        const int offset = static_cast<int>(out.vertices_m.size());
        for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
            const aiVector3D& p = mesh.mVertices[v];
            out.vertices_m.emplace_back(p.x, p.y, p.z);
        }
        for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
            const aiFace& face = mesh.mFaces[f];
            if (face.mNumIndices != 3) continue;
            out.triangles.emplace_back(offset + static_cast<int>(face.mIndices[0]),
                                       offset + static_cast<int>(face.mIndices[1]),
                                       offset + static_cast<int>(face.mIndices[2]));
        }
    }
    return out;
}

}  // namespace

TriangleMesh parse_mesh(std::string_view bytes, const std::string& extension_hint) {
    // assimp's post-processing reads past a truncated binary PLY (SIGSEGV): the file's structure is
    // checked by our own reader first, which stops at the first byte that is not there.
    if (extension_hint == "ply") (void)parse_ply(bytes);
    Assimp::Importer importer;
    importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
    const unsigned flags = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                           aiProcess_PreTransformVertices | aiProcess_SortByPType;
    const aiScene* scene =
        importer.ReadFileFromMemory(bytes.data(), bytes.size(), flags, extension_hint.c_str());
    if (!scene) throw FormatError(std::string("cannot read mesh: ") + importer.GetErrorString());
    TriangleMesh mesh = collect_triangles(*scene);
    if (mesh.triangles.empty()) throw FormatError("mesh holds no triangles");
    if (const std::string err = mesh.validity_error(); !err.empty()) throw FormatError(err);
    return mesh;
}

TriangleMesh read_mesh(const std::filesystem::path& path) {
    const std::string bytes = read_file(path);
    try {
        return parse_mesh(bytes, lower_extension(path));
    } catch (const FormatError& e) {
        throw FileError(path.string(), e.what());
    }
}

void write_mesh(const std::filesystem::path& path, const TriangleMesh& mesh) {
    const std::string ext = lower_extension(path);
    const char* format_id = ext == "obj" ? "objnomtl" : ext == "ply" ? "plyb" : ext == "stl" ? "stlb" : nullptr;
    if (!format_id) throw FileError(path.string(), "unknown mesh extension (expected .obj, .ply or .stl)");
    if (const std::string err = mesh.validity_error(); !err.empty()) {
        throw FileError(path.string(), "invalid mesh: " + err);
    }

    aiScene scene;
    scene.mRootNode = new aiNode();
    scene.mMaterials = new aiMaterial*[1]{new aiMaterial()};
    scene.mNumMaterials = 1;
    auto* ai_mesh = new aiMesh();
    scene.mMeshes = new aiMesh*[1]{ai_mesh};
    scene.mNumMeshes = 1;
    scene.mRootNode->mMeshes = new unsigned[1]{0};
    scene.mRootNode->mNumMeshes = 1;
    ai_mesh->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
    ai_mesh->mNumVertices = static_cast<unsigned>(mesh.vertices_m.size());
    ai_mesh->mVertices = new aiVector3D[mesh.vertices_m.size()];
    for (std::size_t i = 0; i < mesh.vertices_m.size(); ++i) {
        const auto& v = mesh.vertices_m[i];
        ai_mesh->mVertices[i] = aiVector3D(v.x(), v.y(), v.z());
    }
    ai_mesh->mNumFaces = static_cast<unsigned>(mesh.triangles.size());
    ai_mesh->mFaces = new aiFace[mesh.triangles.size()];
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        aiFace& face = ai_mesh->mFaces[t];
        face.mNumIndices = 3;
        face.mIndices = new unsigned[3];
        for (int k = 0; k < 3; ++k) face.mIndices[k] = static_cast<unsigned>(mesh.triangles[t][k]);
    }

    Assimp::Exporter exporter;
    const aiExportDataBlob* blob = exporter.ExportToBlob(&scene, format_id);
    if (!blob) throw FileError(path.string(), std::string("mesh export failed: ") + exporter.GetErrorString());
    write_file_atomic(path, std::string_view(static_cast<const char*>(blob->data), blob->size));
}

}  // namespace makeway::io
