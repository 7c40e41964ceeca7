#pragma once
// (Internal to the cad module: OCCT types.) Reading and writing whole shapes.
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>
#include <filesystem>
#include <string>
#include <vector>

#include "cnclab/cad/cad_format.hpp"

namespace cnclab::occt {

// The file's shape in mm, and its faces in TopExp::MapShapes order. ConfigError
// naming the file when it cannot be read, is not a STEP/IGES file, holds no
// shape or no face.
struct CadShape {
  TopoDS_Shape shape;
  std::vector<TopoDS_Face> faces;
};
CadShape read_cad_shape(const std::filesystem::path& file);

// The file text of `shape` (mm; reals with 17 significant digits).
std::string cad_shape_text(const TopoDS_Shape& shape, CadFormat format);

// OCCT reports through Message::DefaultMessenger(), which prints to stdout by
// default; our commands print their own results there. Removes its stream
// printers once per process (OCCT's messenger is a process-wide singleton).
void silence_occt_messages();

// The message of an OCCT exception (Standard_Failure) or of a std::exception.
std::string occt_failure_text();

}  // namespace cnclab::occt
