#pragma once
// What an rsl::api::Renderer holds (api_renderer.cpp, api_gl.cpp): the
// renderer's own copy of the scene, which the per-frame setters edit (a posed
// part gets a root node of its own; the environment rotation, camera, lights
// and materials are written into the scene too), so that the renderer, image
// formation and the ground truth all read one scene.
#include <memory>
#include <utility>
#include <vector>

#include "rsl/rsl.h"
#include "src/backend/render_session.h"
#include "src/rays/posed_scene.h"

namespace rsl::api {

struct Renderer::State {
    RenderOptions options;
    std::unique_ptr<RenderSession> session;  // its scene: the copy every setter edits
    float time = 0;
    bool frame_stale = true;          // the renderer is not posed at `time` with the latest edits
    std::vector<int> posed_node;      // per part: its node from set_part_pose, or −1
    mutable std::unique_ptr<PosedScene> posed;  // image formation, made at the first image
    mutable std::pair<int, int> memory_checked_size{0, 0};  // the image size last found within the memory limit

    rsl::Scene& scene() { return session->scene(); }
    const rsl::Scene& scene() const { return session->scene(); }
    VertexRenderer& renderer() { return session->renderer(); }
    const VertexRenderer& renderer() const { return session->renderer(); }
    // Poses the renderer at `time` when an edit or set_time made it stale.
    void update_frame() {
        if (!frame_stale) return;
        session->set_time(time);
        frame_stale = false;
    }
    // The image of any internal vertex colours, layered parts' textures
    // applied per pixel (the scene posed at `time`); the renderer's own
    // image of its last shade() is VertexRenderer::form_image.
    Image form_image(const ::rsl::VertexColors& colors, const ImageSettings& settings) const;
    // The image's width and height (0: the camera's); throws for bad settings.
    std::pair<int, int> image_size(const ImageSettings& settings) const;
    int part_index(const std::string& part) const;  // throws naming the parts
    void check_part(int part) const;
};

}  // namespace rsl::api
