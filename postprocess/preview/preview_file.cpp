// Extension -> renderer.
#include "postprocess/preview/preview_file.h"

#include <filesystem>

#include "postprocess/preview/preview_html.h"
#include "slicer/input_error.h"

namespace strand::post {

PreviewFormat preview_format(const std::string& path, const std::string& key) {
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext == ".png") return PreviewFormat::Png;
  if (ext == ".svg") return PreviewFormat::Svg;
  if (ext == ".html") return PreviewFormat::Html;
  if (ext == ".glb") return PreviewFormat::Glb;
  throw InputError(key + " = " + path + ": extension must be .png, .svg, .html or .glb");
}

std::string render_preview(const PreviewScene& scene, PreviewFormat format,
                           const PreviewFileOptions& o) {
  switch (format) {
    case PreviewFormat::Png: return render_png(scene, o.image);
    case PreviewFormat::Svg: return render_svg(scene, o.image);
    case PreviewFormat::Html: return render_html(scene, o.title);
    case PreviewFormat::Glb: return render_glb(scene, o.glb);
  }
  return {};
}

}  // namespace strand::post
