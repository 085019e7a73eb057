// The viewer's ImGui panel: materials, lights, visibility factors, timings.
#include <imgui.h>

#include <algorithm>
#include <string>

#include "src/lightfit/scene_lights.h"
#include "src/core/error.h"
#include "tools/viewer/viewer_state.h"
#include "src/render/cpu_renderer.h"

namespace rsl::gl {

namespace {

// Slider range for a material parameter, from its name.
void parameter_range(const std::string& key, float& lo, float& hi) {
    lo = 0.0f, hi = 1.0f;
    if (key.find("exponent") != std::string::npos) lo = 1.0f, hi = 500.0f;
    if (key.find("roughness") != std::string::npos || key.find("alpha") != std::string::npos) lo = 0.01f;
}

void material_editor(ViewerState& state, int material) {
    MaterialLibrary& library = state.renderer->materials();
    MaterialDesc desc = library.desc(material);
    ImGui::PushID(material);
    if (ImGui::TreeNode(desc.name.c_str(), "%s (%s)", desc.name.c_str(), desc.model.c_str())) {
        for (auto& [key, value] : desc.params) {
            bool changed = false;
            if (value.size() == 3) {
                changed = ImGui::ColorEdit3(key.c_str(), value.data(), ImGuiColorEditFlags_Float);
            } else if (value.size() == 1) {
                float lo, hi;
                parameter_range(key, lo, hi);
                changed = ImGui::SliderFloat(key.c_str(), &value[0], lo, hi, "%.3f",
                                             hi > 10.0f ? ImGuiSliderFlags_Logarithmic : 0);
            }
            if (changed) {
                try {
                    library.set_parameter(material, key, value);  // the renderer uploads it before the next frame
                } catch (const Error&) {
                    // Out of the model's range: the library kept the old value.
                }
            }
        }
        // Emission, any model's (src/core/emission.h): radiance added to what the surface reflects.
        Color emissive = desc.emissive;
        if (ImGui::ColorEdit3("emissive", &emissive[0], ImGuiColorEditFlags_Float | ImGuiColorEditFlags_HDR)) {
            try {
                library.set_parameter(material, "emissive", {emissive.r, emissive.g, emissive.b});
            } catch (const Error&) {
                // Negative or past the limit: the library kept the old value.
            }
        }
        ImGui::TreePop();
    }
    ImGui::PopID();
}

// Panel section: what the window shows (R cycles) and the reference's rays.
void view_section(ViewerState& state) {
    int mode = int(state.mode);
    ImGui::RadioButton("RSL", &mode, int(ViewMode::Rsl));
    ImGui::SameLine();
    ImGui::RadioButton("GPU rays", &mode, int(ViewMode::Rays));
    ImGui::SameLine();
    ImGui::RadioButton("split (R)", &mode, int(ViewMode::Split));
    state.mode = ViewMode(mode);
    if (state.mode != ViewMode::Rsl)
        ImGui::SliderInt("rays per side (S)", &state.reference_rays, 1, GpuRayOptions::kMaxSamplesPerSide);
}

// Panel section: frame rate, GPU pass times and the renderer's counts.
void timings_section(ViewerState& state) {
    const PassTimings t = state.renderer->timings();
    ImGui::Text("%.1f fps, %.2f ms/frame", state.fps, state.frame_ms);
    view_section(state);
    ImGui::Text("GPU%s: shading %.2f ms, display %.2f ms", t.clock ? " (clock, software GL)" : "", t.shade_ms,
                t.display_ms);
    if (t.shadow_ms > 0) ImGui::Text("shadow maps %.2f ms", t.shadow_ms);  // the shadow-map baseline's depth pass
    ImGui::Text("%d vertices, %zu lights, occluder pairs %zu (%zu culled)", state.renderer->vertex_count(),
                state.renderer->stats().lights, state.renderer->stats().occluder_pairs,
                state.renderer->stats().occluder_pairs_culled);
}

// Starts fitting state.rsl_count RSLs to the environment (and its second
// map) in the background; apply_pending hands them to the renderer.
void start_refit(ViewerState& state) {
    const CubeMap* environment = state.environment;
    const CubeMap* second = state.second_environment;
    // The suns join each set, taken here: the fit runs while the scene may change.
    const std::vector<RotatableSquareLight> suns = sun_lights(*state.scene);
    const int count = state.rsl_count;
    state.refit_count = count;
    state.refit = std::async(std::launch::async, [environment, second, count, suns] {
        const auto with_suns = [&](const CubeMap& map) {
            RslSet set = fit_environment_lights(map, count);
            set.lights.insert(set.lights.end(), suns.begin(), suns.end());
            return set;
        };
        return EnvironmentLights(with_suns(*environment), second ? with_suns(*second) : RslSet{});
    });
}

// Panel section: play and time, environment turn, exposure, the RSL count and the first local light.
void animation_and_lighting_section(ViewerState& state) {
    if (!ImGui::CollapsingHeader("Animation and lighting", ImGuiTreeNodeFlags_DefaultOpen)) return;
    ImGui::Checkbox("play (space)", &state.playing);
    ImGui::SameLine();
    ImGui::SliderFloat("t", &state.time, state.scene->animation.start, std::max(state.scene->animation.end, 1e-3f));
    ImGui::SliderFloat("environment turn", &state.environment_degrees, -180.0f, 180.0f, "%.0f deg");
    ImGui::SliderFloat("exposure", &state.exposure, -6.0f, 6.0f, "%.1f stops");
    if (state.environment && state.environment->resolution() > 0) {
        ImGui::SliderInt("RSLs", &state.rsl_count, 1, 100);
        if (ImGui::IsItemDeactivatedAfterEdit() && !state.refit.valid()) start_refit(state);
        if (state.refit.valid()) ImGui::Text("fitting %d RSLs...", state.refit_count);
        else ImGui::Text("%zu RSLs in use", state.renderer->environment_lights().light_count());
    }
    if (!state.scene->lights.empty()) {
        LocalLight& light = state.scene->lights.front();
        if (ImGui::DragFloat3("light (shift+drag)", &light.position.x, 0.01f)) {
            light.path.reset();
            light.node = -1;  // a glTF light leaves its node (position and axis hold its pose at the start)
            state.lights_dirty = true;
        }
    }
}

// Panel section: the renderer's toggles of lights and visibility factors.
void visibility_section(ViewerState& state) {
    if (!ImGui::CollapsingHeader("Visibility factors", ImGuiTreeNodeFlags_DefaultOpen)) return;
    RenderOptions& o = state.toggles;
    bool changed = ImGui::Checkbox("environment RSLs", &o.environment);
    changed |= ImGui::Checkbox("local lights", &o.local_lights);
    changed |= ImGui::Checkbox("self-visibility (SVDF)", &o.self_visibility);
    changed |= ImGui::Checkbox("other parts' shadows (OVDF)", &o.occluders);
    changed |= ImGui::Checkbox("occluder culling", &o.occluder_culling);
    // The per-pixel pass (docs/design/GPU_DESIGN.md): grounds' sharp shadows, glossy parts' highlights.
    bool ground_pixels = o.pixel_shadows != PixelShadows::Off;
    if (ImGui::Checkbox("shadows per pixel on grounds", &ground_pixels)) {
        o.pixel_shadows = ground_pixels ? PixelShadows::Planes : PixelShadows::Off;
        changed = true;
    }
    changed |= ImGui::Checkbox("highlights per pixel", &o.pixel_highlights);
    if (changed) state.renderer->set_toggles(o);
}

// Panel section: each part's material, then every material's parameters.
void materials_section(ViewerState& state) {
    if (!ImGui::CollapsingHeader("Materials")) return;
    MaterialLibrary& library = state.renderer->materials();
    for (int p = 0; p < library.part_count(); ++p) {
        const int current = library.part_material(p);
        if (ImGui::BeginCombo(state.scene->parts[p].name.c_str(), library.desc(current).name.c_str())) {
            for (int m = 0; m < library.material_count(); ++m)
                if (ImGui::Selectable(library.desc(m).name.c_str(), m == current)) library.assign(p, m);
            ImGui::EndCombo();
        }
    }
    ImGui::Separator();
    for (int m = 0; m < library.material_count(); ++m) material_editor(state, m);
}

}  // namespace

void apply_pending(ViewerState& state) {
    if (state.refit.valid() && state.refit.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
        state.renderer->set_environment_lights(state.refit.get());
        if (state.reference) state.reference->set_environment_lights(state.renderer->environment_lights());
    }
    if (state.lights_dirty) {
        state.renderer->set_local_lights(state.scene->lights);
        if (state.reference) state.reference->set_local_lights(state.scene->lights);
        state.lights_dirty = false;
    }
}

void view_overlay(const ViewerState& state) {
    if (state.mode == ViewMode::Rsl || !state.reference) return;
    // The shading pass of each side, as the panel's GPU line times it.
    const double rsl_ms = state.renderer->timings().shade_ms, rays_ms = state.reference->timings().shade_ms;
    const ImGuiViewport* viewport = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(ImVec2(viewport->Pos.x + 0.5f * viewport->Size.x, viewport->Pos.y + 8), ImGuiCond_Always,
                            ImVec2(0.5f, 0.0f));
    ImGui::SetNextWindowBgAlpha(0.6f);
    ImGui::Begin("view", nullptr,
                 ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoInputs |
                     ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav);
    const int lights = int(state.renderer->environment_lights().light_count());
    if (state.mode == ViewMode::Split)
        ImGui::Text("RSL, K = %d: %.2f ms    |    GPU rays, S = %d: %.2f ms", lights, rsl_ms, state.reference_rays,
                    rays_ms);
    else
        ImGui::Text("GPU rays, S = %d: %.2f ms", state.reference_rays, rays_ms);
    ImGui::End();
}

void viewer_panel(ViewerState& state) {
    view_overlay(state);
    if (!state.panel) return;
    ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(340, 0), ImGuiCond_FirstUseEver);
    ImGui::Begin("rsl view");
    timings_section(state);
    animation_and_lighting_section(state);
    visibility_section(state);
    materials_section(state);
    ImGui::End();
}

}  // namespace rsl::gl
