// The compiled parts of two header libraries, for the WebAssembly build alone (the native builds
// link Debian's libstb and libtinyobjloader): stb_image_write (PNG) and tinyobjloader (OBJ/MTL, in
// double precision as the native target defines).
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>
