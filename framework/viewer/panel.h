// viewer/panel.h: the ImGui panel beside the image, one function per section.
#pragma once

#include "viewer.h"

namespace raylab::viewer {

/// The whole panel, left of the image (panel.cpp).
void draw_panel(Viewer& v);

/// Logs where the last item is, once per name ("panel: widget NAME at X,Y size WxH",
/// window pixels): the GUI tests click there, whatever the panel's layout.
void note_widget(Viewer& v, const char* name);

// panel_scene.cpp
void scene_section(Viewer& v);
void camera_section(Viewer& v);
void lights_section(Viewer& v);

// panel_render.cpp
void rendering_section(Viewer& v);
void stats_section(Viewer& v);
/// Frame time, rays per second and the time history, over the image's top right.
void frame_overlay(Viewer& v);
void files_section(Viewer& v);
void log_section(Viewer& v);

// panel_modules.cpp
void modules_section(Viewer& v);
void compare_section(Viewer& v);
void inspector_section(Viewer& v);
/// A pixel's probes as text lines (the tooltip and the section share them).
void probe_lines(const Viewer& v, const PixelReport& report);

// panel_inspector.cpp
/// The pinned pixel's lights: samples, shadow rays and blockers, student and reference.
void light_lines(const Viewer& v, const PixelReport& report);
/// One line per light and side: shadow or lit, and the blocker (the hover tooltip).
void light_tooltip(const PixelReport& report);

// image_view.cpp
/// Uploads the image (or heat map) when it changed.
void refresh_texture(Viewer& v);
/// Draws the image right of the panel and tracks the pixel under the mouse.
void draw_image(Viewer& v);

}  // namespace raylab::viewer
