// Headless software rasterizer for the samples: perspective camera, z-buffer,
// smooth two-sided Lambert + ambient shading, a ground grid and 2x2 supersampling,
// written to PNG with stb_image_write. It is hand-written because it is small and no
// Debian package offers a headless mesh rasterizer we would want as a dependency.
#include "render_png.h"

#include <stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace cloth_samples {
namespace {

constexpr float kPi = 3.14159265358979f;
constexpr float kNear = 0.01f;
// Shading = ambient + a weak headlight (keeps the shape readable on the unlit side)
// + Lambert for the main light; the three weights sum to 1.
constexpr float kAmbient = 0.22f;
constexpr float kHeadlight = 0.18f;
constexpr int kMaxSize = 8192;
constexpr size_t kMaxSupersampledPixels = size_t{2048} * 2048;

struct Vec3 {
    float x, y, z;
};

Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec3 operator*(Vec3 a, float s) { return {a.x * s, a.y * s, a.z * s}; }
float dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec3 cross(Vec3 a, Vec3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
float length(Vec3 a) { return std::sqrt(dot(a, a)); }
Vec3 load(const float* p) { return {p[0], p[1], p[2]}; }

bool normalize(Vec3* v) {
    const float len = length(*v);
    if (!(len > 1e-20f) || !std::isfinite(len)) return false;
    *v = *v * (1.0f / len);
    return true;
}

float clamp01(float v) { return std::min(1.0f, std::max(0.0f, v)); }

bool all_finite(const float* values, size_t count) {
    for (size_t i = 0; i < count; ++i) {
        if (!std::isfinite(values[i])) return false;
    }
    return true;
}

bool fail(std::string* error, const std::string& message) {
    if (error) *error = "render_png: " + message;
    return false;
}

// Camera frame plus the projection onto the sample raster (width x height samples).
struct View {
    Vec3 eye, right, up, forward;
    float tan_half_y, aspect;
    int width, height;

    Vec3 to_view(Vec3 p) const {
        const Vec3 d = p - eye;
        return {dot(d, right), dot(d, up), dot(d, forward)};
    }
    float screen_x(Vec3 v) const { return (0.5f + 0.5f * v.x / (v.z * tan_half_y * aspect)) * width; }
    float screen_y(Vec3 v) const { return (0.5f - 0.5f * v.y / (v.z * tan_half_y)) * height; }
    // Ray through a sample position; scaled so that its view-space depth is 1.
    Vec3 ray(float sx, float sy) const {
        const float nx = (2.0f * sx / width - 1.0f) * tan_half_y * aspect;
        const float ny = (1.0f - 2.0f * sy / height) * tan_half_y;
        return forward + right * nx + up * ny;
    }
};

struct Target {
    std::vector<float> inv_depth;  // 1 / view depth; 0 is "nothing drawn"
    std::vector<uint8_t> rgb;
};

bool validate(const Camera& camera, const RenderMesh* meshes, size_t mesh_count, const RenderOptions& options,
              std::string* error) {
    if (options.width < 1 || options.width > kMaxSize || options.height < 1 || options.height > kMaxSize) {
        return fail(error, "image size must be in 1.." + std::to_string(kMaxSize) + ", got " +
                               std::to_string(options.width) + "x" + std::to_string(options.height));
    }
    if (!all_finite(camera.eye, 3) || !all_finite(camera.target, 3) || !all_finite(camera.up, 3)) {
        return fail(error, "camera eye, target and up must be finite");
    }
    if (!(camera.fov_y_degrees > 0.0f && camera.fov_y_degrees < 180.0f)) {
        return fail(error, "camera fov_y_degrees must be in (0, 180)");
    }
    Vec3 forward = load(camera.target) - load(camera.eye);
    if (!normalize(&forward)) return fail(error, "camera eye and target coincide");
    Vec3 right = cross(forward, load(camera.up));
    if (!normalize(&right)) return fail(error, "camera up is zero or parallel to the view direction");
    if (!all_finite(options.light_dir, 3) || !all_finite(&options.ground_y, 1)) {
        return fail(error, "light_dir and ground_y must be finite");
    }
    Vec3 light = load(options.light_dir);
    if (!normalize(&light)) return fail(error, "light_dir must not be zero");
    if (mesh_count > 0 && meshes == nullptr) return fail(error, "meshes is null but mesh_count > 0");
    for (size_t m = 0; m < mesh_count; ++m) {
        const RenderMesh& mesh = meshes[m];
        const std::string name = "mesh " + std::to_string(m) + ": ";
        if (mesh.vertex_count > 0 && mesh.positions == nullptr) {
            return fail(error, name + "positions is null");
        }
        if (mesh.triangle_count > 0 && mesh.indices == nullptr) return fail(error, name + "indices is null");
        const size_t coords = size_t{mesh.vertex_count} * 3;
        if (mesh.vertex_count > 0 && !all_finite(mesh.positions, coords)) {
            return fail(error, name + "positions contain a non-finite value");
        }
        if (mesh.normals && !all_finite(mesh.normals, coords)) {
            return fail(error, name + "normals contain a non-finite value");
        }
        for (size_t i = 0; i < size_t{mesh.triangle_count} * 3; ++i) {
            if (mesh.indices[i] >= mesh.vertex_count) {
                return fail(error, name + "index " + std::to_string(mesh.indices[i]) + " at position " +
                                       std::to_string(i) + " is out of range (vertex_count " +
                                       std::to_string(mesh.vertex_count) + ")");
            }
        }
    }
    return true;
}

// Grid lines on y = ground_y: ray-cast per sample, spacing and extent follow the
// meshes' bounding box, line width is about one output pixel, lines fade out where
// they would become denser than a few samples and towards the grid border.
void draw_ground_grid(const View& view, const RenderMesh* meshes, size_t mesh_count,
                      const RenderOptions& options, int samples_per_pixel, Target* target) {
    Vec3 lo{1e30f, 1e30f, 1e30f}, hi{-1e30f, -1e30f, -1e30f};
    for (size_t m = 0; m < mesh_count; ++m) {
        for (uint32_t v = 0; v < meshes[m].vertex_count; ++v) {
            const Vec3 p = load(meshes[m].positions + size_t{v} * 3);
            lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
            hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
        }
    }
    const bool has_bounds = lo.x <= hi.x;
    float size = has_bounds ? std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z}) : 0.0f;
    if (!(size > 1e-6f)) size = 1.0f;
    // A "nice" spacing (1, 2 or 5 times a power of ten) giving roughly eight cells across the scene.
    const float magnitude = std::pow(10.0f, std::floor(std::log10(size / 8.0f)));
    const float ratio = size / 8.0f / magnitude;
    const float spacing = magnitude * (ratio < 1.5f ? 1.0f : ratio < 3.5f ? 2.0f : 5.0f);
    const float center_x = has_bounds ? std::round(0.5f * (lo.x + hi.x) / spacing) * spacing : 0.0f;
    const float center_z = has_bounds ? std::round(0.5f * (lo.z + hi.z) / spacing) * spacing : 0.0f;
    const float half_extent = std::ceil(1.5f * size / spacing) * spacing;
    const float ground_y = options.ground_y;

    auto hit = [&](float sx, float sy, Vec3* point, float* depth) {
        const Vec3 d = view.ray(sx, sy);
        if (std::fabs(d.y) < 1e-12f) return false;
        const float t = (ground_y - view.eye.y) / d.y;
        if (!(t > kNear)) return false;
        *point = view.eye + d * t;
        *depth = t;
        return true;
    };
    auto coverage = [&](float coord, float footprint) {
        if (!(footprint > 0.0f)) return 0.0f;
        const float cells = coord / spacing;
        const float dist = std::fabs(cells - std::round(cells)) * spacing;
        const float half_width = 0.5f * footprint * samples_per_pixel;
        const float density_fade = clamp01((0.3f - footprint / spacing) / 0.2f);
        return clamp01((half_width + 0.5f * footprint - dist) / footprint) * density_fade;
    };

    const uint8_t* bg = options.background;
    for (int y = 0; y < view.height; ++y) {
        for (int x = 0; x < view.width; ++x) {
            Vec3 p, px, py;
            float depth, unused;
            if (!hit(x + 0.5f, y + 0.5f, &p, &depth) || !hit(x + 1.5f, y + 0.5f, &px, &unused) ||
                !hit(x + 0.5f, y + 1.5f, &py, &unused)) {
                continue;
            }
            const float border = std::max(std::fabs(p.x - center_x), std::fabs(p.z - center_z));
            const float edge_fade = clamp01((half_extent - border) / spacing);
            const float foot_x = std::max(std::fabs(px.x - p.x), std::fabs(py.x - p.x));
            const float foot_z = std::max(std::fabs(px.z - p.z), std::fabs(py.z - p.z));
            const float alpha = 0.75f * edge_fade * std::max(coverage(p.x, foot_x), coverage(p.z, foot_z));
            if (alpha < 1.0f / 255.0f) continue;
            const size_t i = static_cast<size_t>(y) * view.width + x;
            for (int c = 0; c < 3; ++c) {
                const float line = 0.55f * bg[c];
                target->rgb[i * 3 + c] = static_cast<uint8_t>(bg[c] + (line - bg[c]) * alpha + 0.5f);
            }
            // Slightly farther than the plane so that cloth lying on the ground wins.
            target->inv_depth[i] = (1.0f / depth) * (1.0f - 1e-5f);
        }
    }
}

void draw_mesh(const View& view, const RenderMesh& mesh, Vec3 light, Target* target) {
    const Vec3 base{static_cast<float>(mesh.color[0]), static_cast<float>(mesh.color[1]),
                    static_cast<float>(mesh.color[2])};
    for (uint32_t t = 0; t < mesh.triangle_count; ++t) {
        Vec3 world[3], cam[3], normal[3];
        float sx[3], sy[3];
        bool visible = true;
        for (int k = 0; k < 3; ++k) {
            const size_t v = mesh.indices[size_t{t} * 3 + k];
            world[k] = load(mesh.positions + v * 3);
            cam[k] = view.to_view(world[k]);
            visible = visible && cam[k].z >= kNear;
            if (mesh.normals) normal[k] = load(mesh.normals + v * 3);
        }
        if (!visible) continue;
        if (!mesh.normals) {
            Vec3 face = cross(world[1] - world[0], world[2] - world[0]);
            if (!normalize(&face)) continue;
            normal[0] = normal[1] = normal[2] = face;
        }
        for (int k = 0; k < 3; ++k) {
            sx[k] = view.screen_x(cam[k]);
            sy[k] = view.screen_y(cam[k]);
        }
        const float area = (sx[1] - sx[0]) * (sy[2] - sy[0]) - (sx[2] - sx[0]) * (sy[1] - sy[0]);
        if (!(std::fabs(area) > 1e-12f)) continue;
        const float fw = static_cast<float>(view.width - 1), fh = static_cast<float>(view.height - 1);
        const int x0 = static_cast<int>(std::clamp(std::floor(std::min({sx[0], sx[1], sx[2]})), 0.0f, fw));
        const int x1 = static_cast<int>(std::clamp(std::ceil(std::max({sx[0], sx[1], sx[2]})), 0.0f, fw));
        const int y0 = static_cast<int>(std::clamp(std::floor(std::min({sy[0], sy[1], sy[2]})), 0.0f, fh));
        const int y1 = static_cast<int>(std::clamp(std::ceil(std::max({sy[0], sy[1], sy[2]})), 0.0f, fh));
        const float inv_area = 1.0f / area;
        for (int y = y0; y <= y1; ++y) {
            const float py = y + 0.5f;
            for (int x = x0; x <= x1; ++x) {
                const float px = x + 0.5f;
                const float b0 = ((sx[2] - sx[1]) * (py - sy[1]) - (sy[2] - sy[1]) * (px - sx[1])) * inv_area;
                const float b1 = ((sx[0] - sx[2]) * (py - sy[2]) - (sy[0] - sy[2]) * (px - sx[2])) * inv_area;
                const float b2 = 1.0f - b0 - b1;
                if (b0 < 0.0f || b1 < 0.0f || b2 < 0.0f) continue;
                // Perspective-correct weights; their sum is 1 / view depth.
                const float q0 = b0 / cam[0].z, q1 = b1 / cam[1].z, q2 = b2 / cam[2].z;
                const float inv_z = q0 + q1 + q2;
                const size_t i = static_cast<size_t>(y) * view.width + x;
                if (!(inv_z > target->inv_depth[i])) continue;
                target->inv_depth[i] = inv_z;
                const Vec3 position = (world[0] * q0 + world[1] * q1 + world[2] * q2) * (1.0f / inv_z);
                Vec3 to_eye = view.eye - position;
                normalize(&to_eye);
                Vec3 n = normal[0] * q0 + normal[1] * q1 + normal[2] * q2;
                if (!normalize(&n)) n = to_eye;
                const float facing = dot(n, to_eye);
                if (facing < 0.0f) n = n * -1.0f;  // two-sided: shade the side facing the eye
                const float shade = kAmbient + kHeadlight * std::fabs(facing) +
                                    (1.0f - kAmbient - kHeadlight) * std::max(0.0f, dot(n, light));
                const Vec3 c = base * shade;
                target->rgb[i * 3 + 0] = static_cast<uint8_t>(std::min(255.0f, c.x + 0.5f));
                target->rgb[i * 3 + 1] = static_cast<uint8_t>(std::min(255.0f, c.y + 0.5f));
                target->rgb[i * 3 + 2] = static_cast<uint8_t>(std::min(255.0f, c.z + 0.5f));
            }
        }
    }
}

}  // namespace

bool render_png(const std::string& path, const Camera& camera, const RenderMesh* meshes, size_t mesh_count,
                const RenderOptions& options, std::string* error) {
    if (path.empty()) return fail(error, "output path is empty");
    std::vector<uint8_t> image;
    if (!render_rgb(camera, meshes, mesh_count, options, &image, error)) return false;
    if (!stbi_write_png(path.c_str(), options.width, options.height, 3, image.data(), options.width * 3)) {
        return fail(error, "cannot write '" + path + "'");
    }
    return true;
}

bool render_rgb(const Camera& camera, const RenderMesh* meshes, size_t mesh_count,
                const RenderOptions& options, std::vector<uint8_t>* rgb, std::string* error) {
    if (rgb == nullptr) return fail(error, "rgb is null");
    if (!validate(camera, meshes, mesh_count, options, error)) return false;

    const int ss = static_cast<size_t>(options.width) * options.height <= kMaxSupersampledPixels ? 2 : 1;
    View view;
    view.eye = load(camera.eye);
    view.forward = load(camera.target) - view.eye;
    normalize(&view.forward);
    view.right = cross(view.forward, load(camera.up));
    normalize(&view.right);
    view.up = cross(view.right, view.forward);
    view.tan_half_y = std::tan(camera.fov_y_degrees * 0.5f * kPi / 180.0f);
    view.aspect = static_cast<float>(options.width) / static_cast<float>(options.height);
    view.width = options.width * ss;
    view.height = options.height * ss;

    Vec3 light = load(options.light_dir);
    normalize(&light);

    const size_t sample_count = static_cast<size_t>(view.width) * view.height;
    Target target;
    target.inv_depth.assign(sample_count, 0.0f);
    target.rgb.resize(sample_count * 3);
    for (size_t i = 0; i < sample_count; ++i) {
        std::copy(options.background, options.background + 3, target.rgb.begin() + i * 3);
    }

    if (options.draw_ground_grid) draw_ground_grid(view, meshes, mesh_count, options, ss, &target);
    for (size_t m = 0; m < mesh_count; ++m) draw_mesh(view, meshes[m], light, &target);

    // Resolve the supersampled raster to the output image (box filter).
    std::vector<uint8_t> image(static_cast<size_t>(options.width) * options.height * 3);
    const int samples = ss * ss;
    for (int y = 0; y < options.height; ++y) {
        for (int x = 0; x < options.width; ++x) {
            for (int c = 0; c < 3; ++c) {
                int sum = 0;
                for (int dy = 0; dy < ss; ++dy) {
                    for (int dx = 0; dx < ss; ++dx) {
                        const size_t s = static_cast<size_t>(y * ss + dy) * view.width + (x * ss + dx);
                        sum += target.rgb[s * 3 + c];
                    }
                }
                image[(static_cast<size_t>(y) * options.width + x) * 3 + c] =
                    static_cast<uint8_t>((sum + samples / 2) / samples);
            }
        }
    }

    rgb->swap(image);
    return true;
}

bool write_panels_png(const std::string& path, const std::vector<std::vector<uint8_t>>& panels,
                      int panel_width, int panel_height, std::string* error) {
    const size_t panel_bytes = static_cast<size_t>(panel_width) * panel_height * 3;
    const int rows = static_cast<int>((panels.size() + 1) / 2), width = 2 * panel_width;
    std::vector<uint8_t> image(static_cast<size_t>(width) * rows * panel_height * 3, 255);
    for (size_t i = 0; i < panels.size(); ++i) {
        if (panels[i].size() != panel_bytes) {
            if (error)
                *error = "a panel is not " + std::to_string(panel_width) + "x" + std::to_string(panel_height);
            return false;
        }
        const int px = static_cast<int>(i % 2) * panel_width, py = static_cast<int>(i / 2) * panel_height;
        for (int y = 0; y < panel_height; ++y)
            std::copy(panels[i].begin() + static_cast<size_t>(y) * panel_width * 3,
                      panels[i].begin() + static_cast<size_t>(y + 1) * panel_width * 3,
                      image.begin() + (static_cast<size_t>(py + y) * width + px) * 3);
    }
    if (panels.empty() ||
        !stbi_write_png(path.c_str(), width, rows * panel_height, 3, image.data(), width * 3)) {
        if (error) *error = "cannot write " + path;
        return false;
    }
    return true;
}

}  // namespace cloth_samples
