// Draws a picture (8-bit sRGB, already tone-mapped) over the whole
// viewport: how the window shows the refinement at rest in place of the
// Gouraud view. A full-screen triangle and one texture; GL 3.3 core.
#pragma once

#include <string>

#include "image/image.h"

namespace bounce {

// Uploads `picture` (linear radiance) into `texture` (made if 0) as
// radiance x exposure through the sRGB curve, 8 bits, bilinear, clamped.
void upload_srgb_texture(unsigned& texture, const image& picture, double exposure);

class picture_quad {
 public:
  picture_quad() = default;
  ~picture_quad();
  picture_quad(const picture_quad&) = delete;
  picture_quad& operator=(const picture_quad&) = delete;

  bool init(std::string& error);
  // Uploads `picture` (linear radiance) as radiance x exposure through the sRGB curve.
  void upload(const image& picture, double exposure);
  void draw() const;
  bool has_picture() const { return width_ > 0; }
  void clear() { width_ = 0; }

 private:
  unsigned program_ = 0, vao_ = 0, texture_ = 0;
  int width_ = 0, height_ = 0;
};

}  // namespace bounce
