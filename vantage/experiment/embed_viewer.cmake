# Writes OUTPUT, a C++ source that holds share/viewer/view.html and view.js (under VIEWER_DIR) as
# strings, so `vantage view` needs no files of ours at run time. Run at build time by
# vantage/experiment/CMakeLists.txt.
set(out "// Generated from ${VIEWER_DIR} by embed_viewer.cmake; do not edit.\n")
string(APPEND out "#include \"vantage/experiment/viewer_assets.hpp\"\n\nnamespace vantage {\n\n")
foreach(pair "view.html;viewer_page_template" "view.js;viewer_app_script")
  list(GET pair 0 file)
  list(GET pair 1 function)
  file(READ "${VIEWER_DIR}/${file}" text)
  string(FIND "${text}" ")vantage_web\"" clash)
  if(NOT clash EQUAL -1)
    message(FATAL_ERROR "${VIEWER_DIR}/${file} holds the raw string's end marker")
  endif()
  string(APPEND out "std::string_view ${function}() {\n  return R\"vantage_web(${text})vantage_web\";\n}\n\n")
endforeach()
string(APPEND out "}  // namespace vantage\n")
file(WRITE "${OUTPUT}.tmp" "${out}")
file(COPY_FILE "${OUTPUT}.tmp" "${OUTPUT}" ONLY_IF_DIFFERENT)
file(REMOVE "${OUTPUT}.tmp")
