// Hershey text layouts and their expected strokes for tests (see text_strokes.h).
#include "tests/support/text_strokes.h"

#include <gtest/gtest.h>

#include <cstddef>

extern "C" {
#include <hersheyfont.h>
}

#include "slicer/svg_import.h"

namespace strand::testing {

std::string svg_doc(const std::string& body) {
  return "<svg xmlns='http://www.w3.org/2000/svg' width='200mm' height='100mm' viewBox='0 0 200 "
         "100'>" +
         body + "</svg>";
}

slicer::TextDrawing hershey_text(const std::string& body, const std::string& font) {
  return slicer::layout_text(slicer::import_svg(svg_doc(body), "t.svg").texts,
                             {slicer::TextMode::Hershey, font});
}

std::vector<slicer::Vec2> text_vertices(const slicer::TextDrawing& t) {
  std::vector<slicer::Vec2> out;
  for (const auto& s : t.shapes) {
    for (const auto& p : s.paths) {
      out.push_back(p.start);
      for (const auto& c : p.pieces) out.push_back(c.end());
    }
  }
  return out;
}

std::vector<slicer::Vec2> hershey_expected(const std::string& s, const char* font, double x0,
                                           double y0, double size) {
  hershey_font* f = hershey_font_load(font);
  EXPECT_NE(f, nullptr);
  std::vector<slicer::Vec2> out;
  const double k = size / 32.0;
  double x = x0;
  for (unsigned char ch : s) {
    const hershey_glyph* g = hershey_font_glyph(f, ch);
    for (const hershey_path* p = g->paths; p; p = p->next) {
      if (p->nverts < 2) continue;
      for (int i = 0; i < p->nverts; ++i)
        out.emplace_back(x + p->verts[i].x * k, y0 - p->verts[i].y * k);
    }
    x += g->width * k;
  }
  hershey_font_free(f);
  return out;
}

void expect_same_points(const std::vector<slicer::Vec2>& got,
                        const std::vector<slicer::Vec2>& want) {
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < got.size(); ++i) EXPECT_LT((got[i] - want[i]).norm(), 0.01) << i;
}

double hershey_width(const std::string& s, const char* font, double size) {
  hershey_font* f = hershey_font_load(font);
  double w = 0;
  for (unsigned char ch : s) w += hershey_font_glyph(f, ch)->width;
  hershey_font_free(f);
  return w * size / 32.0;
}

}  // namespace strand::testing
