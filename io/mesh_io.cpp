#include "io/mesh_io.hpp"

#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <poll.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <assimp/Exporter.hpp>
#include <assimp/Importer.hpp>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>

#include "io/error.hpp"
#include "io/file_util.hpp"
#include "io/ply.hpp"
#include "makeway/common/mesh_placement.hpp"

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

namespace {

// The up axis a Collada file declares (<asset><up_axis>), Y_UP when it declares none (the spec's
// default).
MeshAxis collada_up_axis(std::string_view bytes) {
    const std::size_t open = bytes.find("<up_axis>");
    if (open == std::string_view::npos) return MeshAxis::kPosY;
    const std::string_view rest = bytes.substr(open + 9, 16);
    if (rest.find("Z_UP") != std::string_view::npos) return MeshAxis::kPosZ;
    if (rest.find("X_UP") != std::string_view::npos) return MeshAxis::kPosX;
    return MeshAxis::kPosY;
}

// assimp in this process: throws FormatError.
TriangleMesh import_with_assimp(std::string_view bytes, const std::string& extension_hint) {
    Assimp::Importer importer;
    importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE,
                                aiPrimitiveType_POINT | aiPrimitiveType_LINE);
    // assimp turns a Z-up Collada file into its own Y-up; makeway is Z-up, so the file's
    // coordinates are kept and its declared up axis turned to +z below (units stay assimp's: <unit
    // meter>).
    const bool collada = extension_hint == "dae";
    if (collada) importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
    const unsigned flags = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                           aiProcess_PreTransformVertices | aiProcess_SortByPType;
    const aiScene* scene =
        importer.ReadFileFromMemory(bytes.data(), bytes.size(), flags, extension_hint.c_str());
    if (!scene) throw FormatError(std::string("cannot read mesh: ") + importer.GetErrorString());
    TriangleMesh mesh = collect_triangles(*scene);
    if (collada) {
        const MeshAxis up = collada_up_axis(bytes);
        if (up != MeshAxis::kPosZ) {
            MeshPlacement turn;
            turn.up = up;
            turn.forward =
                up == MeshAxis::kPosX ? MeshAxis::kNegZ : MeshAxis::kPosX;  // the least turn
            turn.recentre = false;
            mesh = place_mesh(std::move(mesh), turn);
        }
    }
    return mesh;
}

bool write_all(int fd, const void* data, std::size_t size) {
    const char* p = static_cast<const char*>(data);
    while (size > 0) {
        const ssize_t n = ::write(fd, p, size);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return false;
        p += n;
        size -= static_cast<std::size_t>(n);
    }
    return true;
}

// The child's side: import, then send 'M' + counts + arrays, or 'E' + the message.
[[noreturn]] void import_in_child(int fd, std::string_view bytes, const std::string& extension_hint,
                                  std::size_t memory_cap) {
    // Memory cap on top of what the process has mapped already (sanitizers map terabytes).
    std::size_t mapped_pages = 0;
    if (std::FILE* statm = std::fopen("/proc/self/statm", "r")) {
        if (std::fscanf(statm, "%zu", &mapped_pages) != 1) mapped_pages = 0;
        std::fclose(statm);
    }
    if (mapped_pages > 0) {
        const rlim_t cap =
            static_cast<rlim_t>(mapped_pages) * static_cast<rlim_t>(::sysconf(_SC_PAGESIZE)) +
            memory_cap;
        const struct rlimit limit { cap, cap };
        ::setrlimit(RLIMIT_AS, &limit);
    }
    std::string message;
    try {
        const TriangleMesh mesh = import_with_assimp(bytes, extension_hint);
        const std::uint64_t counts[2] = {mesh.vertices_m.size(), mesh.triangles.size()};
        const bool ok =
            write_all(fd, "M", 1) && write_all(fd, counts, sizeof(counts)) &&
            write_all(fd, mesh.vertices_m.data(),
                      mesh.vertices_m.size() * sizeof(Eigen::Vector3f)) &&
            write_all(fd, mesh.triangles.data(), mesh.triangles.size() * sizeof(Eigen::Vector3i));
        ::_exit(ok ? 0 : 3);
    } catch (const FormatError& e) {
        message = e.what();
    } catch (const std::bad_alloc&) {
        message = "cannot read mesh: it asks for more memory than any mesh needs";
    } catch (const std::exception& e) {
        message = std::string("cannot read mesh: ") + e.what();
    }
    write_all(fd, "E", 1);
    write_all(fd, message.data(), message.size());
    ::_exit(0);
}

}  // namespace

TriangleMesh parse_mesh(std::string_view bytes, const std::string& extension_hint,
                        const MeshReadLimits& limits) {
    // assimp's post-processing reads past a truncated binary PLY (SIGSEGV): the file's structure is
    // checked by our own reader first, which stops at the first byte that is not there.
    if (extension_hint == "ply") (void)parse_ply(bytes);
    // assimp is not hardened against damaged files: fuzzing found crashes (out-of-range face
    // indices in post-processing) and multi-gigabyte allocations (Collada counts). It runs in a
    // child process with a memory cap and a time limit; triangles come back through a pipe.
    int fds[2];
    if (::pipe(fds) != 0)
        throw FormatError(std::string("cannot read mesh: ") + std::strerror(errno));
    const pid_t pid = ::fork();
    if (pid < 0) {
        ::close(fds[0]);
        ::close(fds[1]);
        throw FormatError(std::string("cannot read mesh: ") + std::strerror(errno));
    }
    if (pid == 0) {
        ::close(fds[0]);
        import_in_child(fds[1], bytes, extension_hint, limits.memory_bytes);
    }
    ::close(fds[1]);
    std::string reply;
    const auto deadline =
        std::chrono::steady_clock::now() + std::chrono::duration<double>(limits.seconds);
    bool timed_out = false;
    char buf[1 << 16];
    for (;;) {
        const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                              deadline - std::chrono::steady_clock::now())
                              .count();
        struct pollfd pfd {
            fds[0], POLLIN, 0
        };
        const int ready =
            left > 0 ? ::poll(&pfd, 1, static_cast<int>(std::min<long long>(left, 1000))) : 0;
        if (ready < 0 && errno == EINTR) continue;
        if (ready == 0 && left <= 0) {
            timed_out = true;
            break;
        }
        if (ready <= 0) continue;
        const ssize_t n = ::read(fds[0], buf, sizeof(buf));
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) break;
        reply.append(buf, static_cast<std::size_t>(n));
    }
    ::close(fds[0]);
    if (timed_out) ::kill(pid, SIGKILL);
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    if (timed_out)
        throw FormatError("cannot read mesh: the reader took longer than " +
                          std::to_string(static_cast<int>(limits.seconds)) + " s");
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        throw FormatError(WIFSIGNALED(status)
                              ? "cannot read mesh: the reader crashed on this file (signal " +
                                    std::to_string(WTERMSIG(status)) + ")"
                              : "cannot read mesh: the reader failed on this file");
    }
    if (!reply.empty() && reply[0] == 'E') throw FormatError(reply.substr(1));
    std::uint64_t counts[2];
    if (reply.size() < 1 + sizeof(counts) || reply[0] != 'M')
        throw FormatError("cannot read mesh: no answer from the reader");
    std::memcpy(counts, reply.data() + 1, sizeof(counts));
    const std::size_t expected = 1 + sizeof(counts) + counts[0] * sizeof(Eigen::Vector3f) +
                                 counts[1] * sizeof(Eigen::Vector3i);
    if (counts[0] > reply.size() || counts[1] > reply.size() || reply.size() != expected) {
        throw FormatError("cannot read mesh: a short answer from the reader");
    }
    if (counts[1] == 0) throw FormatError("mesh holds no triangles");
    TriangleMesh mesh;
    mesh.vertices_m.resize(counts[0]);
    mesh.triangles.resize(counts[1]);
    const char* p = reply.data() + 1 + sizeof(counts);
    if (counts[0] > 0)
        std::memcpy(static_cast<void*>(mesh.vertices_m.data()), p,
                    counts[0] * sizeof(Eigen::Vector3f));
    std::memcpy(static_cast<void*>(mesh.triangles.data()), p + counts[0] * sizeof(Eigen::Vector3f),
                counts[1] * sizeof(Eigen::Vector3i));
    if (const std::string err = mesh.validity_error(); !err.empty()) throw FormatError(err);
    return mesh;
}

TriangleMesh read_mesh(const std::filesystem::path& path, const MeshReadLimits& limits) {
    const std::string bytes = read_file(path);
    try {
        return parse_mesh(bytes, lower_extension(path), limits);
    } catch (const FormatError& e) {
        throw FileError(path.string(), e.what());
    }
}

void write_mesh(const std::filesystem::path& path, const TriangleMesh& mesh) {
    const std::string ext = lower_extension(path);
    const char* format_id = ext == "obj"   ? "objnomtl"
                            : ext == "ply" ? "plyb"
                            : ext == "stl" ? "stlb"
                                           : nullptr;
    if (!format_id)
        throw FileError(path.string(), "unknown mesh extension (expected .obj, .ply or .stl)");
    if (const std::string err = mesh.validity_error(); !err.empty()) {
        throw FileError(path.string(), "invalid mesh: " + err);
    }

    aiScene scene;
    scene.mRootNode = new aiNode();
    scene.mMaterials = new aiMaterial* [1] { new aiMaterial() };
    scene.mNumMaterials = 1;
    auto* ai_mesh = new aiMesh();
    scene.mMeshes = new aiMesh* [1] { ai_mesh };
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
    if (!blob)
        throw FileError(path.string(),
                        std::string("mesh export failed: ") + exporter.GetErrorString());
    write_file_atomic(path, std::string_view(static_cast<const char*>(blob->data), blob->size));
}

}  // namespace makeway::io
