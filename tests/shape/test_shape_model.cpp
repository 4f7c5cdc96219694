// The shape networks: the differentiable solve agrees with the closed form, a few training steps
// lower every loss, a saved model answers exactly as before, bad model files are refused.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "makeway/eval/shape_dataset.hpp"
#include "makeway/neural/shape_nets.hpp"
#include "makeway/shape/mesh_sdf.hpp"
#include "makeway/shape/shape_completion.hpp"
#include "makeway/shape/shape_training.hpp"

namespace makeway::shape {
namespace {

namespace fs = std::filesystem;

TEST(ShapeModel, TorchSolveMatchesTheClosedForm) {
    torch::manual_seed(3);
    const torch::Tensor v = torch::randn({2, 40, 3}), p = torch::randn({2, 40, 3}),
                        w = torch::rand({2, 40}) + 0.1;
    const TorchSimilarity T = solve_upright_similarity(v, p, w);
    for (int b = 0; b < 2; ++b) {
        std::vector<Eigen::Vector3d> vv, pp;
        std::vector<double> ww;
        for (int i = 0; i < 40; ++i) {
            vv.emplace_back(v[b][i][0].item<double>(), v[b][i][1].item<double>(),
                            v[b][i][2].item<double>());
            pp.emplace_back(p[b][i][0].item<double>(), p[b][i][1].item<double>(),
                            p[b][i][2].item<double>());
            ww.push_back(w[b][i].item<double>());
        }
        const auto ref = solve_similarity(vv, pp, ww, true);
        ASSERT_TRUE(ref.has_value());
        EXPECT_NEAR(T.scale[b].item<double>(), ref->scale, 1e-4);
        for (int r = 0; r < 3; ++r) {
            EXPECT_NEAR(T.translation[b][r].item<double>(), ref->translation[r], 1e-4);
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(T.rotation[b][r][c].item<double>(), ref->rotation(r, c), 1e-4);
        }
    }
    // And it is differentiable: a gradient reaches the weights.
    const torch::Tensor wg = w.clone().set_requires_grad(true);
    solve_upright_similarity(v, p, wg).scale.sum().backward();
    EXPECT_GT(wg.grad().abs().sum().item<double>(), 0.0);
}

// One small simulated room: a few dozen views and shapes with light targets.
const eval::ShapeDataset& small_dataset() {
    static const eval::ShapeDataset data = [] {
        eval::ShapeDatasetParams p;
        p.scenes = 1;
        p.seed = 5;
        p.viewpoints_per_scene = 3;
        p.sdf_samples = 600;
        p.occupancy_samples = 600;
        p.surface_samples = 256;
        return eval::generate_shape_dataset(p);
    }();
    return data;
}

TEST(ShapeModel, TheDatasetHoldsBothClassesWithTruthThatFitsThePoints) {
    const auto& data = small_dataset();
    int classes[2] = {0, 0};
    for (const auto& v : data.views) {
        const ShapeExample& ex = data.shapes[static_cast<std::size_t>(v.shape)];
        ++classes[shape_class_index(ex.cls)];
        // The object's own returns lie on its surface under the true pose (range noise aside).
        const MeshSdf sdf(data.mesh_object[static_cast<std::size_t>(v.shape)],
                          data.box_object[static_cast<std::size_t>(v.shape)].centre_m,
                          1.0 / data.scale_m[static_cast<std::size_t>(v.shape)]);
        std::vector<double> d;
        for (std::size_t i = 0; i < v.points.size(); ++i) {
            if (!v.outlier[i])
                d.push_back(sdf.unsigned_distance(v.truth.inverse_apply(v.points[i])) *
                            v.truth.scale);
        }
        ASSERT_FALSE(d.empty());
        std::sort(d.begin(), d.end());
        EXPECT_LT(d[d.size() / 2], 0.03);  // median under 3 cm (sigma 1.5 cm range noise)
    }
    EXPECT_GT(classes[0], 3);
    EXPECT_GT(classes[1], 1);
    for (const auto& s : data.shapes) {
        EXPECT_EQ(s.sdf.size(), 600u);
        EXPECT_GT(std::count(s.occupied.begin(), s.occupied.end(), 1), 20);  // some samples inside
        if (s.style == "round_table") {
            EXPECT_GT(s.symmetry_yaws.size(), 2u);
        }
        if (s.style == "four_leg_chair" || s.style == "office_chair" || s.style == "armchair") {
            EXPECT_EQ(s.symmetry_yaws.size(), 1u) << s.style;
        }
    }
}

TEST(ShapeModel, AFewTrainingStepsLowerEveryLoss) {
    ShapeModelParams mp;
    mp.points = 64;
    mp.grid.resolution = 16;
    ShapeModel model(mp);
    ShapeTrainParams tp;
    tp.correspondence_steps = 80;
    tp.sdf_steps = 80;
    tp.occupancy_steps = 40;
    tp.correspondence_batch = 8;
    tp.sdf_batch_shapes = 4;
    tp.sdf_samples = 128;
    tp.occupancy_batch = 4;
    tp.occupancy_samples = 128;
    tp.fusions_per_shape = 1;
    tp.learning_rate = 2e-3;
    tp.threads = 1;
    const ShapeTrainReport r = train_shape_model(model, small_dataset(), tp);
    for (int c = 0; c < 2; ++c) {
        SCOPED_TRACE(c);
        EXPECT_LT(r.correspondence[c].last, 0.9 * r.correspondence[c].first);
        EXPECT_LT(r.sdf[c].last, 0.9 * r.sdf[c].first);
        EXPECT_LT(r.occupancy[c].last, 0.9 * r.occupancy[c].first);
    }

    // Saved and loaded, it answers exactly as before.
    const fs::path dir = fs::temp_directory_path() / "makeway_test_shape_model";
    fs::create_directories(dir);
    model.save(dir / "shape.pt");
    const ShapeModel loaded = ShapeModel::load(dir / "shape.pt");
    EXPECT_EQ(loaded.parameter_count(), model.parameter_count());
    const ShapeView& view = small_dataset().views.front();
    for (const ObjectClass cls : {ObjectClass::kChair, ObjectClass::kTable}) {
        const Correspondences a = model.correspond(cls, view.points),
                              b = loaded.correspond(cls, view.points);
        ASSERT_EQ(a.canonical.size(), b.canonical.size());
        for (std::size_t i = 0; i < a.canonical.size(); ++i) {
            EXPECT_EQ(a.canonical[i], b.canonical[i]);
            EXPECT_EQ(a.confidence[i], b.confidence[i]);
        }
        Latent z{};
        z[3] = 0.2f;
        const std::vector<Eigen::Vector3d> q{{0, 0, 0}, {0.5, -0.2, 0.1}, {1, 1, 1}};
        EXPECT_EQ(model.sdf(cls, z, q), loaded.sdf(cls, z, q));
        TsdfVolume tsdf(mp.grid, mp.truncation_cells);
        std::vector<Eigen::Vector3d> canonical;
        for (const auto& p : view.points) canonical.push_back(view.truth.inverse_apply(p));
        tsdf.integrate(canonical, view.truth.inverse_apply(view.origin));
        EXPECT_EQ(model.occupancy(cls, tsdf, z, q), loaded.occupancy(cls, tsdf, z, q));
        const Completion ca =
            complete_shape(model, cls, {canonical}, {view.truth.inverse_apply(view.origin)});
        const Completion cb =
            complete_shape(loaded, cls, {canonical}, {view.truth.inverse_apply(view.origin)});
        EXPECT_EQ(ca.code, cb.code);
        EXPECT_EQ(ca.occupancy, cb.occupancy);
        EXPECT_GT(ca.observed_cells, 0u);
    }
    fs::remove_all(dir);
}

TEST(ShapeModel, BadFilesAreRefusedNamingTheFile) {
    const fs::path dir = fs::temp_directory_path() / "makeway_test_shape_bad";
    fs::create_directories(dir);
    EXPECT_THROW(
        {
            try {
                ShapeModel::load(dir / "missing.pt");
            } catch (const std::runtime_error& e) {
                EXPECT_NE(std::string(e.what()).find("missing.pt"), std::string::npos);
                throw;
            }
        },
        std::runtime_error);
    std::ofstream(dir / "junk.pt") << "not a model at all";
    EXPECT_THROW(ShapeModel::load(dir / "junk.pt"), std::runtime_error);
    // A detector file is a torch archive too, but not a shape model.
    ShapeModel tiny(ShapeModelParams{});
    tiny.save(dir / "ok.pt");
    std::string bytes;
    {
        std::ifstream in(dir / "ok.pt", std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(in), {});
    }
    bytes[bytes.size() / 2] ^= 0x5a;  // one flipped byte: the CRC check refuses it
    std::ofstream(dir / "flipped.pt", std::ios::binary) << bytes;
    EXPECT_THROW(ShapeModel::load(dir / "flipped.pt"), std::runtime_error);
    EXPECT_THROW(tiny.correspond(static_cast<ObjectClass>(9), {{0, 0, 0}}), std::invalid_argument);
    fs::remove_all(dir);
}

}  // namespace
}  // namespace makeway::shape
