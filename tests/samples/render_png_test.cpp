// Facts about the samples' PNG rasterizer: the file is written at the requested
// size, the mesh covers the centre but not the corners, the z-buffer keeps the
// nearer triangle, shading is two-sided, and bad input writes nothing.
#include "render_png.h"

#include <gtest/gtest.h>
#include <stb_image.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <filesystem>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

namespace {

using cloth_samples::Camera;
using cloth_samples::render_png;
using cloth_samples::RenderMesh;
using cloth_samples::RenderOptions;

using Pixel = std::array<uint8_t, 3>;

// A 2 x 2 quad in the plane z = 0, centred on (0, 1, 0), wound counter-clockwise
// as seen from +z (face normal +z).
const float kQuadPositions[] = {-1.0f, 0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 1.0f, 2.0f, 0.0f, -1.0f, 2.0f, 0.0f};
const uint32_t kQuadIndices[] = {0, 1, 2, 0, 2, 3};
const uint32_t kQuadIndicesReversed[] = {0, 2, 1, 0, 3, 2};

// Looks at the quad centre from +z; the quad fills the middle of the image only.
Camera front_camera() { return Camera{{0.0f, 1.0f, 4.0f}, {0.0f, 1.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, 45.0f}; }

RenderMesh quad_mesh(const uint32_t* indices, Pixel color) {
    return RenderMesh{kQuadPositions, nullptr, 4, indices, 2, {color[0], color[1], color[2]}};
}

RenderOptions small_options() {
    RenderOptions options;
    options.width = 160;
    options.height = 120;
    options.draw_ground_grid = false;
    return options;
}

struct Image {
    int width = 0;
    int height = 0;
    std::vector<uint8_t> rgb;
    Pixel at(int x, int y) const {
        const size_t i = (static_cast<size_t>(y) * width + x) * 3;
        return {rgb[i], rgb[i + 1], rgb[i + 2]};
    }
    Pixel centre() const { return at(width / 2, height / 2); }
};

class RenderPngTest : public ::testing::Test {
  protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = std::filesystem::temp_directory_path() /
               ("cloth_render_png_" + std::to_string(::getpid()) + "_" + info->name());
        std::filesystem::remove_all(dir_);
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }

    std::string path(const std::string& name) const { return (dir_ / name).string(); }

    // Renders and decodes; fails the test if either step fails.
    Image render(const std::string& name, const RenderMesh* meshes, size_t count,
                 const RenderOptions& options, const Camera& camera = front_camera()) {
        std::string error;
        const std::string file = path(name);
        EXPECT_TRUE(render_png(file, camera, meshes, count, options, &error)) << error;
        Image image;
        int channels = 0;
        uint8_t* data = stbi_load(file.c_str(), &image.width, &image.height, &channels, 3);
        EXPECT_NE(data, nullptr) << "cannot decode " << file;
        if (data) {
            image.rgb.assign(data, data + static_cast<size_t>(image.width) * image.height * 3);
            stbi_image_free(data);
        }
        return image;
    }

    // Expects render_png to reject the input with a message and to create no file.
    void expect_rejected(const std::string& name, const RenderMesh* meshes, size_t count,
                         const RenderOptions& options, const Camera& camera = front_camera()) {
        std::string error;
        const std::string file = path(name);
        EXPECT_FALSE(render_png(file, camera, meshes, count, options, &error));
        EXPECT_FALSE(error.empty());
        EXPECT_FALSE(std::filesystem::exists(file)) << file;
    }

    std::filesystem::path dir_;
};

Pixel background_of(const RenderOptions& options) {
    return {options.background[0], options.background[1], options.background[2]};
}

TEST_F(RenderPngTest, WritesPngOfRequestedSize) {
    const RenderMesh quad = quad_mesh(kQuadIndices, {200, 40, 45});
    const RenderOptions options = small_options();
    const Image image = render("quad.png", &quad, 1, options);
    EXPECT_TRUE(std::filesystem::exists(path("quad.png")));
    EXPECT_EQ(image.width, 160);
    EXPECT_EQ(image.height, 120);
}

TEST_F(RenderPngTest, QuadCoversCentreButNotCorners) {
    const RenderMesh quad = quad_mesh(kQuadIndices, {200, 40, 45});
    const RenderOptions options = small_options();
    const Image image = render("quad.png", &quad, 1, options);
    ASSERT_EQ(image.width, 160);
    const Pixel background = background_of(options);
    EXPECT_NE(image.centre(), background);
    EXPECT_EQ(image.at(0, 0), background);
    EXPECT_EQ(image.at(159, 0), background);
    EXPECT_EQ(image.at(0, 119), background);
    EXPECT_EQ(image.at(159, 119), background);
    // Red mesh colour, shaded: red dominates.
    EXPECT_GT(image.centre()[0], image.centre()[1]);
}

TEST_F(RenderPngTest, GroundGridIsDrawnBelowHorizon) {
    const RenderMesh quad = quad_mesh(kQuadIndices, {200, 40, 45});
    RenderOptions options = small_options();
    const Pixel background = background_of(options);
    options.draw_ground_grid = true;
    const Image with_grid = render("grid.png", &quad, 1, options);
    ASSERT_EQ(with_grid.height, 120);
    // The camera looks horizontally from y = 1: the bottom rows see the ground.
    int grid_pixels = 0;
    for (int y = 100; y < 120; ++y) {
        for (int x = 0; x < 160; ++x) grid_pixels += with_grid.at(x, y) != background;
    }
    EXPECT_GT(grid_pixels, 0);
    EXPECT_EQ(with_grid.at(0, 0), background);  // sky stays clear
}

TEST_F(RenderPngTest, NearerTriangleWinsRegardlessOfOrder) {
    // Two large triangles covering the centre: red at z = 0, blue at z = 0.5 (nearer the camera).
    const float far_positions[] = {-2.0f, -1.0f, 0.0f, 2.0f, -1.0f, 0.0f, 0.0f, 3.0f, 0.0f};
    const float near_positions[] = {-2.0f, -1.0f, 0.5f, 2.0f, -1.0f, 0.5f, 0.0f, 3.0f, 0.5f};
    const uint32_t triangle[] = {0, 1, 2};
    const RenderMesh red{far_positions, nullptr, 3, triangle, 1, {220, 20, 20}};
    const RenderMesh blue{near_positions, nullptr, 3, triangle, 1, {20, 20, 220}};
    const RenderOptions options = small_options();

    const RenderMesh far_first[] = {red, blue};
    const RenderMesh near_first[] = {blue, red};
    const Image a = render("far_first.png", far_first, 2, options);
    const Image b = render("near_first.png", near_first, 2, options);
    ASSERT_EQ(a.width, 160);
    ASSERT_EQ(b.width, 160);
    EXPECT_GT(a.centre()[2], a.centre()[0]);
    EXPECT_GT(b.centre()[2], b.centre()[0]);
    EXPECT_EQ(a.centre(), b.centre());
}

TEST_F(RenderPngTest, BackLitFaceIsStillVisible) {
    const RenderMesh quad = quad_mesh(kQuadIndices, {200, 200, 200});
    RenderOptions options = small_options();
    const Pixel background = background_of(options);

    options.light_dir[0] = 0.0f;
    options.light_dir[1] = 0.0f;
    options.light_dir[2] = 1.0f;  // light from the camera side
    const Image front_lit = render("front_lit.png", &quad, 1, options);

    options.light_dir[2] = -1.0f;  // light from behind the quad
    const Image back_lit = render("back_lit.png", &quad, 1, options);
    ASSERT_EQ(front_lit.width, 160);
    ASSERT_EQ(back_lit.width, 160);

    EXPECT_NE(back_lit.centre(), background);
    EXPECT_GT(back_lit.centre()[0], 0);
    EXPECT_LT(back_lit.centre()[0], front_lit.centre()[0]);  // darker, but drawn
}

TEST_F(RenderPngTest, ShadingIsTwoSided) {
    // Same quad, opposite winding (face normal away from the camera), or explicit
    // normals pointing away from the camera: no culling, shaded like the front face.
    const float away_normals[] = {0, 0, -1, 0, 0, -1, 0, 0, -1, 0, 0, -1};
    const RenderMesh front = quad_mesh(kQuadIndices, {200, 200, 200});
    const RenderMesh reversed = quad_mesh(kQuadIndicesReversed, {200, 200, 200});
    RenderMesh with_away_normals = front;
    with_away_normals.normals = away_normals;
    RenderOptions options = small_options();
    options.light_dir[0] = 0.0f;
    options.light_dir[1] = 0.0f;
    options.light_dir[2] = 1.0f;

    const Image a = render("front.png", &front, 1, options);
    const Image b = render("reversed.png", &reversed, 1, options);
    const Image c = render("away_normals.png", &with_away_normals, 1, options);
    ASSERT_EQ(a.width, 160);
    ASSERT_EQ(b.width, 160);
    ASSERT_EQ(c.width, 160);
    EXPECT_NE(a.centre(), background_of(options));
    EXPECT_EQ(a.centre(), b.centre());
    EXPECT_EQ(a.centre(), c.centre());
}

TEST_F(RenderPngTest, RejectsZeroWidth) {
    const RenderMesh quad = quad_mesh(kQuadIndices, {200, 40, 45});
    RenderOptions options = small_options();
    options.width = 0;
    expect_rejected("zero_width.png", &quad, 1, options);
    options.width = 8193;
    expect_rejected("too_wide.png", &quad, 1, options);
}

TEST_F(RenderPngTest, RejectsNullPositions) {
    RenderMesh quad = quad_mesh(kQuadIndices, {200, 40, 45});
    quad.positions = nullptr;
    expect_rejected("null_positions.png", &quad, 1, small_options());
}

TEST_F(RenderPngTest, RejectsIndexOutOfRange) {
    const uint32_t bad_indices[] = {0, 1, 2, 0, 2, 4};
    const RenderMesh quad = quad_mesh(bad_indices, {200, 40, 45});
    expect_rejected("bad_index.png", &quad, 1, small_options());
}

TEST_F(RenderPngTest, RejectsOtherBadInput) {
    const RenderMesh quad = quad_mesh(kQuadIndices, {200, 40, 45});
    expect_rejected("null_meshes.png", nullptr, 1, small_options());

    float nan_positions[12];
    std::copy(std::begin(kQuadPositions), std::end(kQuadPositions), nan_positions);
    nan_positions[4] = std::numeric_limits<float>::quiet_NaN();
    RenderMesh nan_quad = quad;
    nan_quad.positions = nan_positions;
    expect_rejected("nan.png", &nan_quad, 1, small_options());

    Camera degenerate = front_camera();
    degenerate.target[2] = degenerate.eye[2];
    expect_rejected("eye_is_target.png", &quad, 1, small_options(), degenerate);

    // A null error pointer is allowed.
    RenderOptions options = small_options();
    options.height = 0;
    EXPECT_FALSE(render_png(path("no_error.png"), front_camera(), &quad, 1, options, nullptr));
    EXPECT_FALSE(std::filesystem::exists(path("no_error.png")));
}

}  // namespace
