// Scene files (docs/scene-format.md): JSON text <-> Scene, with positioned diagnostics.
// Part of the phonglab_io library (nlohmann-json); the core renderer does not depend on it.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/scene/scene.h"
#include "io/diagnostic.h"
#include "io/obj_io.h"

namespace phonglab {

// One problem found in a scene file, printed as `file:line:col: json.path: message`.

struct LoadResult {
  std::optional<Scene> scene;            // set when there are no errors
  std::vector<Diagnostic> errors;        // empty on success
  std::vector<Diagnostic> warnings;      // what was tolerated (mesh files' quirks, emitter hints)
  bool ok() const { return scene.has_value(); }
  std::string error_text() const;        // all errors, one per line
};

// Parses scene JSON. `file_name` is used in diagnostics; `base_dir` resolves mesh paths (with
// `embedded_meshes`, relative mesh paths name the embedded scenes' files instead).
LoadResult load_scene_text(const std::string& text, const std::string& file_name,
                           const std::string& base_dir = ".", bool embedded_meshes = false);

// Parses scene JSON whose mesh files (and their MTLs) come from `files` by the names the scene
// and its OBJs give them: scenes held in memory, and the OBJ/MTL fuzzer.
LoadResult load_scene_text_with(const std::string& text, const std::string& file_name, const FileReader& files);

// Reads and parses a scene file; an unreadable file is an error, not an exception. A path
// ending in .obj opens that mesh alone, with a camera framing it and a light.
LoadResult load_scene_file(const std::string& path);

// Whether `path` names a Wavefront OBJ (by its extension, any case): such a path opens as a mesh
// alone, and a scene must never be saved over it.
bool is_obj_path(const std::string& path);

// Resolves SCENE as the CLI takes it: an embedded scene's name, else a file path.
LoadResult load_scene_arg(const std::string& scene_arg);

// The scene with its meshes read again from their files (and their MTL materials), as the
// scene saved in `base_dir` would load: after an edit adds a mesh object, moves one or changes
// the material table under one. `embedded`: relative mesh paths name the embedded scenes'
// files. MTL materials keep the coefficients edited since they were read.
LoadResult reload_meshes(const Scene& scene, const std::string& base_dir, bool embedded);

// Serialises a scene to JSON text that load_scene_text reads back to an equal scene. With
// `save_dir`, the folder the text will be saved in, mesh files read from disk are named
// relative to it (else as they were written).
std::string scene_to_json(const Scene& scene, const std::string& save_dir = "");

// The same text with every number in plain decimal notation (0.000001, never 1e-06), each with
// the fewest digits that read back to the same double: what `phonglab-cli scene --plain` prints
// for a student's own parser (docs/your-ray-tracer.md). Every key is written, defaults included;
// mesh objects stay as the scene names them (the OBJ file, its transform), their MTL materials
// with them. load_scene_text reads it back to an equal scene.
std::string scene_to_plain_json(const Scene& scene, const std::string& save_dir = "");

// Writes text to `path` through a temporary file and a rename, so a crash never leaves a
// half-written file. Returns an empty string on success, else the error.
std::string write_file_atomically(const std::string& path, const std::string& text);

// Writes the embedded mesh files (each OBJ and the MTL files it names) that the scene's meshes
// name without a file on disk (an embedded scene's, a lesson step's) into `dir`, where a scene
// saved there looks for them: a saved copy of the Cornell box opens again anywhere. A file
// already there with the same bytes stays; one with other bytes is never overwritten (the
// error says so, and the scene should be saved elsewhere). Empty on success, else the error.
std::string write_embedded_meshes(const Scene& scene, const std::string& dir);

// The same files as text: each embedded OBJ a mesh names without a file on disk and the MTL files
// it names, by their paths relative to the scene's folder ("cornell/CornellBox-Sphere.mtl"), each
// once, in the scene's order. The page puts them in one download beside the scene.
struct SceneFileText {
  std::string path;
  std::string text;
};
std::vector<SceneFileText> embedded_mesh_files(const Scene& scene);

// A number as scene files write it: the shortest decimal that reads back to the same double, in
// plain or exponent notation, whichever is shorter (plain on a tie): 40, 0.04, 1e-05, as
// std::to_chars writes it. Computed with printf alone, so WebAssembly (whose libc++ has no
// floating-point to_chars) writes the same text as the desktop; not for inf or NaN.
std::string shortest_number_text(double x);
// A number in plain decimal notation with the fewest significant digits that read back to the
// same double (1e-06 as 0.000001, 1e22 as 10000000000000000000000; -0 as -0.0); "null" for inf
// or NaN. printf alone, as shortest_number_text.
std::string plain_number_text(double x);

}  // namespace phonglab
