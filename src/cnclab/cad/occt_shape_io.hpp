#pragma once
// (Internal to the cad module: OCCT types.) Reading and writing whole shapes.
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>
#include <filesystem>
#include <string>
#include <vector>

#include "cnclab/cad/cad_format.hpp"

namespace cnclab::occt {

// The file's shape in mm, and its faces in TopExp::MapShapes order (each
// with the orientation it has in the shape: a solid's faces point out).
// ConfigError naming the file when it cannot be read, is not a STEP/IGES
// file, holds no shape, only a mesh or no face, or the reader takes longer
// than `timeout_seconds` (cad_surface.hpp: CadReadOptions).
struct CadShape {
  TopoDS_Shape shape;
  std::vector<TopoDS_Face> faces;
  std::string unit;    // the length unit the file declares ("MILLIMETRE", "INCH", "MM", ...)
  std::string writer;  // the system that wrote it (STEP originating system, IGES system id)
};
CadShape read_cad_shape(const std::filesystem::path& file, double timeout_seconds);

// The file text of `shape` (mm; reals with 17 significant digits).
std::string cad_shape_text(const TopoDS_Shape& shape, CadFormat format);

// OCCT reports through Message::DefaultMessenger(), which prints to stdout by
// default; our commands print their own results there. Removes its stream
// printers once per process (OCCT's messenger is a process-wide singleton).
void silence_occt_messages();

// The message of an OCCT exception (Standard_Failure) or of a std::exception.
std::string occt_failure_text();

}  // namespace cnclab::occt
