// The workbench pages, embedded at build time from serve/pages/ (cmake/embed_pages.cmake).
#pragma once

#include <string>
#include <vector>

namespace strand::serve {

struct Page {
  const char* name;  // "design.html"
  const char* text;
};

const std::vector<Page>& pages();

}  // namespace strand::serve
