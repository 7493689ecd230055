// The 3D debug view (viewer/debug_view.h), like TU Delft's ray debugger: the scene
// rasterised into an offscreen texture shown in an ImGui window, with the pinned pixel's
// rays. Flat colours are lit on the CPU (material rho times a head-light cosine).
#define GL_GLEXT_PROTOTYPES 1
#include "debug_view.h"

#include <GL/gl.h>
#include <GL/glext.h>
#include <imgui.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "viewer.h"

namespace raylab::viewer {

namespace {

const char* kVertex = R"(#version 330 core
layout(location = 0) in vec3 p;
layout(location = 1) in vec3 c;
uniform mat4 mvp;
out vec3 colour;
void main() { gl_Position = mvp * vec4(p, 1.0); colour = c; })";
const char* kFragment = R"(#version 330 core
in vec3 colour;
out vec4 frag;
void main() { frag = vec4(colour, 1.0); })";

unsigned compile(GLenum kind, const char* text) {
    const GLuint s = glCreateShader(kind);
    glShaderSource(s, 1, &text, nullptr);
    glCompileShader(s);
    return s;
}

void push(std::vector<float>& out, const Vec3& p, const Vec3& c) {
    out.insert(out.end(), {p.x, p.y, p.z, c.x, c.y, c.z});
}

void push_triangle(std::vector<float>& out, Vec3 a, Vec3 b, Vec3 c, const Vec3& rho) {
    const Vec3 n = glm::normalize(glm::cross(b - a, c - a));
    const float shade =
        0.35f + 0.65f * std::fabs(glm::dot(n, glm::normalize(Vec3(0.3f, 0.8f, 0.5f))));
    for (const Vec3& p : {a, b, c})
        push(out, p, rho * shade);
}

// Triangles, spheres (12 x 6 UV meshes), planes (quads of the scene's size) into out
void build_scene(const Scene& s, std::vector<float>& out) {
    out.clear();
    const auto rho = [&](int m) { return s.materials[m].rho; };
    for (const SceneTriangle& t : s.triangles)
        push_triangle(out, t.v0, t.v1, t.v2, rho(t.material));
    for (const SceneSphere& sp : s.spheres) {
        const auto at = [&](int i, int j) {
            const float phi = 2.0f * kPi * float(i) / 12.0f, th = kPi * float(j) / 6.0f;
            return sp.sphere.c + sp.sphere.r * Vec3(std::sin(th) * std::cos(phi),
                                                    std::cos(th),
                                                    std::sin(th) * std::sin(phi));
        };
        for (int i = 0; i < 12; ++i)
            for (int j = 0; j < 6; ++j) {
                push_triangle(out, at(i, j), at(i + 1, j), at(i + 1, j + 1),
                              rho(sp.material));
                push_triangle(out, at(i, j), at(i + 1, j + 1), at(i, j + 1),
                              rho(sp.material));
            }
    }
    const Aabb box = s.bounds();
    const float size = box.lo.x <= box.hi.x ? 2.0f * glm::length(box.hi - box.lo) : 10.0f;
    for (const ScenePlane& pl : s.planes) {
        const Vec3 n = pl.plane.n, o = -pl.plane.d * n;
        const Vec3 u = glm::normalize(
            glm::cross(n, std::fabs(n.y) < 0.9f ? Vec3(0, 1, 0) : Vec3(1, 0, 0)));
        const Vec3 w = glm::cross(n, u);
        const Vec3 q[4] = {o + size * (-u - w), o + size * (u - w), o + size * (u + w),
                           o + size * (-u + w)};
        push_triangle(out, q[0], q[1], q[2], rho(pl.material));
        push_triangle(out, q[0], q[2], q[3], rho(pl.material));
    }
}

void line(std::vector<float>& out, const Vec3& a, const Vec3& b, const Vec3& c) {
    push(out, a, c);
    push(out, b, c);
}

// The lights as crosses; the pinned pixel's camera ray (white), normal (cyan) and
// shadow rays (green: free, red: up to the blocker)
void build_lines(const Viewer& v, float size, std::vector<float>& out) {
    for (const PointLight& l : v.state.scene.lights)
        for (const Vec3& axis : {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)})
            line(out, l.p - 0.03f * size * axis, l.p + 0.03f * size * axis,
                 Vec3(1, 1, 0.3f));
    if (!v.inspector.pinned || !v.inspector.pin.probe) return;
    const PixelProbe& p = *v.inspector.pin.probe;
    const float t = p.hit ? p.hit->t : size;
    line(out, p.ray.o, p.ray.o + t * p.ray.w, Vec3(1.0f));
    if (!p.hit) return;
    line(out, p.hit->position, p.hit->position + 0.1f * size * p.hit->ns,
         Vec3(0.2f, 1, 1));
    for (const LightProbe& lp : p.lights) {
        if (lp.rays.empty()) continue;
        const Ray& r = lp.rays.front();
        const bool hit = lp.blocker.has_value();
        const float end = hit ? lp.blocker->t : std::min(r.tmax, 1e3f);
        line(out, r.o, r.o + end * r.w, hit ? Vec3(1, 0.3f, 0.3f) : Vec3(0.3f, 1, 0.3f));
    }
}

void ensure_gl(DebugView& d, int w, int h) {
    if (!d.program) {
        d.program = glCreateProgram();
        const unsigned vs = compile(GL_VERTEX_SHADER, kVertex);
        const unsigned fs = compile(GL_FRAGMENT_SHADER, kFragment);
        glAttachShader(d.program, vs);
        glAttachShader(d.program, fs);
        glLinkProgram(d.program);
        glDeleteShader(vs);
        glDeleteShader(fs);
        glGenVertexArrays(1, &d.vao);
        glGenBuffers(1, &d.vbo);
        glGenFramebuffers(1, &d.fbo);
        glGenTextures(1, &d.colour);
        glGenRenderbuffers(1, &d.depth);
    }
    if (w == d.width && h == d.height) return;
    d.width = w;
    d.height = h;
    glBindTexture(GL_TEXTURE_2D, d.colour);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glBindRenderbuffer(GL_RENDERBUFFER, d.depth);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, w, h);
    glBindFramebuffer(GL_FRAMEBUFFER, d.fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, d.colour,
                           0);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER,
                              d.depth);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

// Orbit camera about the scene's centre
glm::mat4 view_projection(const DebugView& d, const Scene& s, float aspect, float& size) {
    const Aabb box = s.bounds();
    Vec3 centre(0.0f);
    size = 5.0f;
    if (box.lo.x <= box.hi.x) {
        centre = box.centre();
        size = std::max(glm::length(box.hi - box.lo), 1e-3f);
    }
    const float dist = 1.6f * size * d.zoom;
    const Vec3 eye =
        centre + dist * Vec3(std::cos(d.pitch) * std::sin(d.yaw), std::sin(d.pitch),
                             std::cos(d.pitch) * std::cos(d.yaw));
    return glm::perspective(glm::radians(45.0f), aspect, 0.01f * size, 20.0f * size) *
           glm::lookAt(eye, centre, Vec3(0, 1, 0));
}

void draw(Viewer& v, int w, int h) {
    DebugView& d = v.debug;
    ensure_gl(d, w, h);
    float size = 1.0f;
    const glm::mat4 mvp = view_projection(d, v.state.scene, float(w) / float(h), size);
    if (d.version != v.state.scene_version) {
        build_scene(v.state.scene, d.vertices);
        d.scene_vertices = int(d.vertices.size() / 6);
        d.version = v.state.scene_version;
    }
    d.vertices.resize(size_t(d.scene_vertices) * 6);
    build_lines(v, size, d.vertices);
    const int line_vertices = int(d.vertices.size() / 6) - d.scene_vertices;

    GLint old_fbo = 0, old_viewport[4];
    glGetIntegerv(GL_FRAMEBUFFER_BINDING, &old_fbo);
    glGetIntegerv(GL_VIEWPORT, old_viewport);
    glBindFramebuffer(GL_FRAMEBUFFER, d.fbo);
    glViewport(0, 0, w, h);
    glClearColor(0.08f, 0.08f, 0.1f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glUseProgram(d.program);
    glUniformMatrix4fv(glGetUniformLocation(d.program, "mvp"), 1, GL_FALSE, &mvp[0][0]);
    glBindVertexArray(d.vao);
    glBindBuffer(GL_ARRAY_BUFFER, d.vbo);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(d.vertices.size() * sizeof(float)),
                 d.vertices.data(), GL_STREAM_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), nullptr);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float),
                          reinterpret_cast<void*>(3 * sizeof(float)));
    glDrawArrays(GL_TRIANGLES, 0, d.scene_vertices);
    glDisable(GL_DEPTH_TEST);  // rays stay visible through walls
    glDrawArrays(GL_LINES, d.scene_vertices, line_vertices);
    glBindVertexArray(0);
    glBindFramebuffer(GL_FRAMEBUFFER, GLuint(old_fbo));
    glViewport(old_viewport[0], old_viewport[1], old_viewport[2], old_viewport[3]);
}

}  // namespace

void debug_view_window(Viewer& v) {
    DebugView& d = v.debug;
    if (!d.open) return;
    // Opens at the bottom right, over the image, where it hides none of the panel's
    // controls; scaled with the UI
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    const float scale = v.state.ui_scale;
    const ImVec2 size(std::min(480.0f * scale, 0.5f * (display.x - v.panel_width)),
                      std::min(400.0f * scale, 0.55f * display.y));
    ImGui::SetNextWindowSize(size, ImGuiCond_FirstUseEver);
    // down to the image's bottom edge: the line below it keeps its notes (still stubs)
    const float image_bottom = v.image_rect.y + v.image_rect.height;
    const float bottom = v.image_rect.height > 0.0f
                             ? std::min(display.y - 8.0f, image_bottom)
                             : display.y - 8.0f;
    ImGui::SetNextWindowPos(ImVec2(display.x - 8.0f, bottom), ImGuiCond_FirstUseEver,
                            ImVec2(1.0f, 1.0f));
    if (!ImGui::Begin("3D debug view", &d.open)) {
        ImGui::End();
        return;
    }
    // Wrapped: at a large UI scale the window is narrower than the lines
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_TextDisabled]);
    ImGui::TextWrapped(
        "drag: orbit, wheel: zoom; white camera ray, cyan normal, green free / red "
        "blocked shadow rays, yellow lights");
    ImGui::PopStyleColor();
    const ImVec2 avail = ImGui::GetContentRegionAvail();
    const int w = std::max(16, int(avail.x)), h = std::max(16, int(avail.y));
    draw(v, w, h);
    ImGui::Image(reinterpret_cast<ImTextureID>(static_cast<std::intptr_t>(d.colour)),
                 ImVec2(float(w), float(h)), ImVec2(0, 1), ImVec2(1, 0));
    if (ImGui::IsItemHovered()) {
        const ImGuiIO& io = ImGui::GetIO();
        if (ImGui::IsMouseDragging(ImGuiMouseButton_Left)) {
            d.yaw -= io.MouseDelta.x * 0.01f;
            d.pitch = std::clamp(d.pitch + io.MouseDelta.y * 0.01f, -1.5f, 1.5f);
        }
        if (io.MouseWheel != 0.0f)
            d.zoom = std::clamp(d.zoom * std::pow(0.9f, io.MouseWheel), 0.05f, 20.0f);
    }
    ImGui::End();
}

void debug_view_free(DebugView& d) {
    if (!d.program) return;
    glDeleteProgram(d.program);
    glDeleteVertexArrays(1, &d.vao);
    glDeleteBuffers(1, &d.vbo);
    glDeleteFramebuffers(1, &d.fbo);
    glDeleteTextures(1, &d.colour);
    glDeleteRenderbuffers(1, &d.depth);
    d = DebugView{};
}

}  // namespace raylab::viewer
