// Textures and screenshots (viewer/gl_image.h).
#include "gl_image.h"

#include <GL/gl.h>

#include <algorithm>

#include "raylab/error.h"
#include "raylab/image.h"

namespace raylab::viewer {

unsigned create_texture() {
    GLuint texture = 0;
    glGenTextures(1, &texture);
    glBindTexture(GL_TEXTURE_2D, texture);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return texture;
}

void delete_texture(unsigned texture) {
    const GLuint id = texture;
    glDeleteTextures(1, &id);
}

void upload_texture(unsigned texture, int width, int height,
                    const std::vector<std::uint8_t>& rgb) {
    glBindTexture(GL_TEXTURE_2D, texture);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);  // rows of 3 * width bytes, unpadded
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB8, width, height, 0, GL_RGB, GL_UNSIGNED_BYTE,
                 rgb.data());
}

void write_screenshot(const std::string& path, int width, int height) {
    std::vector<std::uint8_t> pixels(static_cast<size_t>(width) * height * 3);
    glReadBuffer(GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, pixels.data());
    // OpenGL's row 0 is the bottom one: flip
    const size_t row = static_cast<size_t>(width) * 3;
    std::vector<std::uint8_t> flipped(pixels.size());
    for (int y = 0; y < height; ++y) {
        std::copy_n(&pixels[(height - 1 - y) * row], row, &flipped[y * row]);
    }
    write_file(path, encode_png(width, height, flipped.data()), "screenshot");
}

}  // namespace raylab::viewer
