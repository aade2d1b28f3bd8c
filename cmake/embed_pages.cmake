# Writes OUT: a C++ table of the workbench pages in DIR (name, text), served by `strand serve`
# from the binary (no files to install, no network).
set(body "// Generated from serve/pages/*; do not edit.\n#include \"serve/pages.h\"\n\nnamespace strand::serve {\n\nconst std::vector<Page>& pages() {\n  static const std::vector<Page> kPages = {\n")
file(GLOB FILES ${DIR}/*.html)
list(SORT FILES)
foreach(f ${FILES})
  get_filename_component(name ${f} NAME)
  file(READ ${f} text)
  string(APPEND body "      {\"${name}\", R\"strand_page(${text})strand_page\"},\n")
endforeach()
string(APPEND body "  };\n  return kPages;\n}\n\n}  // namespace strand::serve\n")
file(WRITE ${OUT}.new "${body}")
execute_process(COMMAND ${CMAKE_COMMAND} -E copy_if_different ${OUT}.new ${OUT})
