# Writes OUT: a C++ function NAME() returning the text of IN (the viewer's bundle, built from
# web/ by esbuild), so the binary carries it and nothing is fetched at run time.
file(READ ${IN} text)
string(FIND "${text}" ")strand_js\"" clash)
if(NOT clash EQUAL -1)
  message(FATAL_ERROR "${IN} contains the raw-string delimiter )strand_js\"")
endif()
string(FIND "${text}" "</script" clash)
if(NOT clash EQUAL -1)
  message(FATAL_ERROR "${IN} contains </script, which would end the page's inline script")
endif()
file(WRITE ${OUT}.new "// Generated from ${IN}; do not edit.\n#include <string>\n\nnamespace strand::post {\n\nconst std::string& ${NAME}() {\n  static const std::string kText = R\"strand_js(${text})strand_js\";\n  return kText;\n}\n\n}  // namespace strand::post\n")
execute_process(COMMAND ${CMAKE_COMMAND} -E copy_if_different ${OUT}.new ${OUT})
