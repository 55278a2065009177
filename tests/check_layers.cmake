# The layering rule (docs/architecture.md), checked on every #include of the tree:
#   cmake -DROOT=<source dir> -P tests/check_layers.cmake
# Each folder may include the project's headers of the layers listed for it, and none of the
# libraries listed as forbidden. Link lines enforce the same for code; this catches a header
# reached without linking (an inline helper, a type) that the link lines cannot see.
# Inside the core, each folder sees only those below it: base (threads), scene (the data, math,
# the camera), geometry (primitives), accel (scene queries), shading (the equation), packet (its
# four-wide tracer), render (passes, trees), teaching (the instruments).
set(_base "core/base/")
set(_scene "${_base} core/scene/")
set(_geometry "${_scene} core/geometry/")
set(_accel "${_geometry} core/accel/")
set(_shading "${_accel} core/shading/")
set(_packet "${_shading} core/packet/")
set(_render "${_packet} core/render/")
set(_core_libs "nlohmann tiny_obj_loader stb_ imgui GL/ glad GLFW embree3")
set(_rules
  "src/core|core/|nlohmann tiny_obj_loader stb_ imgui GL/ glad GLFW embree3"
  "src/core/base|${_base}|${_core_libs}"
  "src/core/scene|${_scene}|${_core_libs}"
  "src/core/geometry|${_geometry}|${_core_libs}"
  "src/core/accel|${_accel}|${_core_libs}"
  "src/core/shading|${_shading}|${_core_libs}"
  "src/core/packet|${_packet}|${_core_libs}"
  "src/core/render|${_render}|${_core_libs}"
  "src/core/teaching|${_render} core/teaching/|${_core_libs}"
  "src/io|core/ check/ io/|imgui GL/ glad GLFW embree3"
  "src/check|core/ check/|nlohmann tiny_obj_loader stb_ imgui GL/ glad GLFW embree3"
  "src/experiments|core/ experiments/|nlohmann tiny_obj_loader stb_ imgui GL/ glad GLFW embree3"
  "src/interaction|core/ interaction/|imgui GL/ glad GLFW embree3"
  "src/session|core/ io/ check/ interaction/ session/|imgui GL/ glad GLFW embree3"
  "src/ui|core/ io/ check/ interaction/ ui/|GL/ glad GLFW embree3"
  "apps/common|core/ io/ check/ apps/common/|imgui GL/ glad GLFW embree3"
  "apps/cli|core/ io/ check/ apps/common/ apps/cli/|imgui GL/ glad GLFW embree3"
  "apps/previewer|core/ io/ check/ interaction/ session/ ui/ apps/common/ apps/previewer/|embree3"
  "apps/bench|core/ io/ check/ experiments/ apps/common/ apps/bench/|imgui GL/ glad GLFW"
  "apps/web|core/ io/ check/ interaction/ session/ apps/web/|imgui GL/ glad GLFW embree3"
)
set(_project_prefixes core/ io/ check/ experiments/ interaction/ session/ ui/ apps/)
set(_errors 0)
foreach(rule IN LISTS _rules)
  string(REPLACE "|" ";" parts "${rule}")
  list(GET parts 0 folder)
  list(GET parts 1 allowed)
  list(GET parts 2 forbidden)
  separate_arguments(allowed)
  separate_arguments(forbidden)
  file(GLOB_RECURSE files "${ROOT}/${folder}/*.h" "${ROOT}/${folder}/*.cpp")
  foreach(f IN LISTS files)
    file(STRINGS "${f}" lines REGEX "^[ \t]*#[ \t]*include[ \t]*[<\"]")
    foreach(line IN LISTS lines)
      string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]*[<\"]([^>\"]+)[>\"].*" "\\1" header "${line}")
      set(project_header FALSE)
      foreach(p IN LISTS _project_prefixes)
        string(FIND "${header}" "${p}" at)
        if(at EQUAL 0)
          set(project_header TRUE)
        endif()
      endforeach()
      set(bad "")
      if(project_header)
        set(ok FALSE)
        foreach(p IN LISTS allowed)
          string(FIND "${header}" "${p}" at)
          if(at EQUAL 0)
            set(ok TRUE)
          endif()
        endforeach()
        if(NOT ok)
          set(bad "a layer ${folder} may not see")
        endif()
      else()
        foreach(p IN LISTS forbidden)
          string(FIND "${header}" "${p}" at)
          if(at EQUAL 0)
            set(bad "a library ${folder} may not use")
          endif()
        endforeach()
      endif()
      if(bad)
        file(RELATIVE_PATH rel "${ROOT}" "${f}")
        message("${rel}: includes ${header}: ${bad}")
        math(EXPR _errors "${_errors} + 1")
      endif()
    endforeach()
  endforeach()
endforeach()
if(_errors GREATER 0)
  message(FATAL_ERROR "${_errors} include(s) break the layering rule (docs/architecture.md)")
endif()
message(STATUS "layering: every include follows docs/architecture.md")
