# The WebAssembly build's libraries (apps/web): the header-only ones from this machine's Debian
# packages, each through its own include folder of links, because -I/usr/include would mix glibc's
# headers into Emscripten's sysroot. Their compiled parts (stb_image_write, tinyobjloader) are
# built from the same headers in apps/web/web_libraries.cpp.
set(_web_include ${CMAKE_BINARY_DIR}/web-include)
file(MAKE_DIRECTORY ${_web_include})
foreach(entry glm nlohmann tiny_obj_loader.h stb)
  if(NOT EXISTS ${_web_include}/${entry})
    file(CREATE_LINK /usr/include/${entry} ${_web_include}/${entry} SYMBOLIC)
  endif()
endforeach()
add_library(glm::glm INTERFACE IMPORTED)
target_include_directories(glm::glm INTERFACE ${_web_include})
add_library(nlohmann_json::nlohmann_json INTERFACE IMPORTED)
target_include_directories(nlohmann_json::nlohmann_json INTERFACE ${_web_include})
add_library(tinyobjloader::tinyobjloader_double INTERFACE IMPORTED)
target_include_directories(tinyobjloader::tinyobjloader_double INTERFACE ${_web_include})
target_compile_definitions(tinyobjloader::tinyobjloader_double INTERFACE TINYOBJLOADER_USE_DOUBLE)
add_library(PkgConfig::STB INTERFACE IMPORTED)
target_include_directories(PkgConfig::STB INTERFACE ${_web_include}/stb)
