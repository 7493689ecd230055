// viewer/gl_image.h: the image as an OpenGL texture, and window screenshots.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace raylab::viewer {

/// A texture for 8-bit RGB images, sampled nearest (one texel per image pixel, so the
/// inspector's pixel is the one on screen).
unsigned create_texture();
void delete_texture(unsigned texture);

/// Replaces the texture's contents with width x height RGB bytes, row 0 on top.
void upload_texture(unsigned texture, int width, int height,
                    const std::vector<std::uint8_t>& rgb);

/// Reads the back buffer (call before swapping) of a width x height framebuffer and
/// writes it as PNG, row 0 on top. Throws raylab::Error when the file cannot be written.
void write_screenshot(const std::string& path, int width, int height);

}  // namespace raylab::viewer
