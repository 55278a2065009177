# phonglab: the interactive previewer (GLFW window, GL 3.3 core through glad, ImGui panels).
# Included from app/CMakeLists.txt when PHONGLAB_GUI is ON.

# glad 2 generates the GL 3.3 core loader at build time. /usr/bin/glad is called directly
# (its own #! interpreter has the generator installed; a `python3` earlier on PATH may not).
set(PHONGLAB_GLAD_DIR ${CMAKE_BINARY_DIR}/glad)
add_custom_command(
  OUTPUT ${PHONGLAB_GLAD_DIR}/src/gl.c ${PHONGLAB_GLAD_DIR}/include/glad/gl.h
         ${PHONGLAB_GLAD_DIR}/include/KHR/khrplatform.h
  COMMAND /usr/bin/glad --quiet --reproducible --api gl:core=3.3 --extensions=
          --out-path ${PHONGLAB_GLAD_DIR} c
  COMMENT "Generating the GL 3.3 core loader (glad)" VERBATIM)
add_library(phonglab_glad STATIC ${PHONGLAB_GLAD_DIR}/src/gl.c)
target_include_directories(phonglab_glad SYSTEM PUBLIC ${PHONGLAB_GLAD_DIR}/include)
# Generated code: our warning flags are not its business.
target_compile_options(phonglab_glad PRIVATE -w)
target_link_libraries(phonglab_glad PUBLIC ${CMAKE_DL_LIBS})

add_executable(phonglab
  previewer_main.cpp
  viewer_app.cpp
  viewer_files.cpp
  viewer_instruments.cpp
  viewer_overlays.cpp
  viewer_sidebar.cpp
  viewer_document.cpp
  viewer_gl.cpp
  viewer_platform.cpp
  viewer_script.cpp
  viewer_state.cpp)
target_link_libraries(phonglab PRIVATE phonglab_ui phonglab_io phonglab_glad glfw PkgConfig::IMGUI)
target_compile_definitions(phonglab PRIVATE PHONGLAB_VERSION="${PROJECT_VERSION}" GLFW_INCLUDE_NONE)
