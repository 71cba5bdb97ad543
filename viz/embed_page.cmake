# cmake -DINPUT=page.html -DOUTPUT=page_template.cc -P embed_page.cmake
# Writes the page as a C++ raw string, animat::viz::kPageTemplate.
file(READ ${INPUT} page)
string(FIND "${page}" ")animat_page\"" clash)
if(NOT clash EQUAL -1)
  message(FATAL_ERROR "${INPUT} contains the raw-string delimiter")
endif()
file(WRITE ${OUTPUT}
  "// Generated from viz/page.html by viz/embed_page.cmake; do not edit.\n"
  "#include \"viz/page_template.h\"\n\n"
  "namespace animat::viz {\n\n"
  "const char kPageTemplate[] = R\"animat_page(${page})animat_page\";\n\n"
  "}  // namespace animat::viz\n")
