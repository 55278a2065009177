// An OBJ read with its triangles spelled out, for the tests (the programs use load_obj_indexed).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "io/obj_io.h"

namespace phonglab {

struct ObjMesh {
  std::vector<Triangle> triangles;  // OBJ coordinates; material = index into `materials`
  std::vector<int> source_face;     // each triangle's face number (0-based, file order)
  std::vector<Material> materials;  // from the MTL, plus a default one when a face has none
  std::vector<Emitter> emitters;
  int skipped_degenerate = 0;       // zero-area triangles left out
  std::vector<Diagnostic> warnings;
  std::vector<Diagnostic> errors;   // a mesh with errors must not be used
};

// load_obj_indexed with every triangle made, in file order.
inline ObjMesh load_obj(const std::string& obj_text, const std::string& obj_name, const FileReader& read_mtl, NsMapping ns = NsMapping::kAsIs) {
  ObjIndexedMesh indexed = load_obj_indexed(obj_text, obj_name, read_mtl, ns);
  ObjMesh out;
  out.triangles.reserve(indexed.triangles.size());
  out.source_face.reserve(indexed.triangles.size());
  for (std::size_t i = 0; i < indexed.triangles.size(); ++i) {
    out.triangles.push_back(indexed.triangle(i));
    out.source_face.push_back(indexed.triangles[i].face);
  }
  out.materials = std::move(indexed.materials);
  out.emitters = std::move(indexed.emitters);
  out.skipped_degenerate = indexed.skipped_degenerate;
  out.warnings = std::move(indexed.warnings);
  out.errors = std::move(indexed.errors);
  return out;
}

}  // namespace phonglab
