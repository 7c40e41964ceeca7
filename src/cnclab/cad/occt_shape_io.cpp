#include "cnclab/cad/occt_shape_io.hpp"

#include <unistd.h>

#include <APIHeaderSection_MakeHeader.hxx>
#include <BRepBuilderAPI_Transform.hxx>
#include <BinTools.hxx>
#include <IGESControl_Reader.hxx>
#include <IGESControl_Writer.hxx>
#include <IGESData_GlobalSection.hxx>
#include <IGESData_IGESModel.hxx>
#include <IGESData_IGESWriter.hxx>
#include <IGESData_Protocol.hxx>
#include <IGESSelect_WorkLibrary.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_PrinterOStream.hxx>
#include <STEPControl_Reader.hxx>
#include <STEPControl_Writer.hxx>
#include <Standard_Failure.hxx>
#include <StepAP214.hxx>
#include <StepAP214_Protocol.hxx>
#include <StepData_StepModel.hxx>
#include <StepData_StepWriter.hxx>
#include <StepData_UndefinedEntity.hxx>
#include <TColStd_SequenceOfAsciiString.hxx>
#include <TCollection_HAsciiString.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <UnitsMethods.hxx>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <exception>
#include <fstream>
#include <mutex>
#include <sstream>
#include <string_view>

#include "cnclab/core/error.hpp"
#include "cnclab/io/isolated_read.hpp"

namespace cnclab::occt {
namespace fs = std::filesystem;

namespace {

// "%.16E": 17 significant digits, enough for any double to read back
// identically (the writers' default keeps 12).
constexpr const char* kOcctRealFormat = "%.16E";
// A fixed time stamp instead of the writing time: the same shape gives the
// same bytes, hence the same content hash and dataset identity.
constexpr const char* kStepTimeStamp = "2000-01-01T00:00:00";
constexpr const char* kIgesDate = "20000101.000000";

// The text without surrounding blanks ("" for none).
std::string text_of(const Handle(TCollection_HAsciiString) & s) {
  if (s.IsNull()) return {};
  const std::string text = s->ToCString();
  const std::size_t first = text.find_first_not_of(" \t");
  if (first == std::string::npos) return {};
  return text.substr(first, text.find_last_not_of(" \t") - first + 1);
}

// Entities of AP242's tessellated geometry (ISO 10303-42: TRIANGULATED_FACE,
// TESSELLATED_SHELL, ...): OCCT 7.6 does not translate them, so it keeps them
// as undefined entities with their type names.
int tessellated_entities(const StepData_StepModel& model) {
  int count = 0;
  for (int i = 1; i <= model.NbEntities(); ++i) {
    const auto undefined = Handle(StepData_UndefinedEntity)::DownCast(model.Value(i));
    if (undefined.IsNull()) continue;
    const std::string_view type = undefined->StepType();
    count += type.starts_with("TESSELLATED_") || type.starts_with("TRIANGULATED_") ||
             type.starts_with("COMPLEX_TRIANGULATED_");
  }
  return count;
}

struct ReadShape {
  TopoDS_Shape shape;
  std::string unit, writer;
};

std::string mesh_only_message(const fs::path& file, int entities) {
  return file.string() + ": holds only a mesh (" + std::to_string(entities) +
         " tessellated entities such as TRIANGULATED_FACE, AP242) and no B-rep face: tool "
         "paths need the exact surfaces; export the part as a B-rep (AP203, AP214 or AP242 "
         "geometry) instead";
}

ReadShape read_step_shape(const fs::path& file) {
  STEPControl_Reader reader;
  if (reader.ReadFile(file.c_str()) != IFSelect_RetDone) {
    throw ConfigError(file.string() + ": not a readable STEP file (the STEP parser failed)");
  }
  ReadShape out;
  APIHeaderSection_MakeHeader header(reader.StepModel());
  out.writer = text_of(header.OriginatingSystem());
  if (out.writer.empty()) out.writer = text_of(header.PreprocessorVersion());
  TColStd_SequenceOfAsciiString lengths, angles, solid_angles;
  reader.FileUnits(lengths, angles, solid_angles);
  if (!lengths.IsEmpty()) out.unit = lengths.First().ToCString();
  const int mesh = tessellated_entities(*reader.StepModel());
  // Shapes in mm whatever unit the file declares (SI_UNIT(.MILLI.,.METRE.),
  // CONVERSION_BASED_UNIT('INCH', ...), ...): the reader scales to this unit.
  reader.SetSystemLengthUnit(1.0);
  if (reader.TransferRoots() == 0) {
    if (mesh > 0) throw ConfigError(mesh_only_message(file, mesh));
    throw ConfigError(file.string() + ": holds no shape");
  }
  out.shape = reader.OneShape();
  if (mesh > 0 && !out.shape.IsNull() && !TopExp_Explorer(out.shape, TopAbs_FACE).More()) {
    throw ConfigError(mesh_only_message(file, mesh));
  }
  return out;
}

ReadShape read_iges_shape(const fs::path& file) {
  IGESControl_Reader reader;
  if (reader.ReadFile(file.c_str()) != IFSelect_RetDone) {
    throw ConfigError(file.string() + ": not a readable IGES file (the IGES parser failed)");
  }
  ReadShape out;
  const IGESData_GlobalSection& header = reader.IGESModel()->GlobalSection();
  out.unit = text_of(header.UnitName());
  out.writer = text_of(header.SystemId());
  if (reader.TransferRoots() == 0) throw ConfigError(file.string() + ": holds no shape");
  out.shape = reader.OneShape();
  // The IGES reader converts from the file's unit (global section) to OCCT's
  // session unit, GetCasCadeLengthUnit() mm (1 unless a program changed it).
  const double mm_per_unit = UnitsMethods::GetCasCadeLengthUnit();
  if (mm_per_unit != 1.0 && !out.shape.IsNull()) {
    gp_Trsf scale;
    scale.SetScaleFactor(mm_per_unit);
    out.shape = BRepBuilderAPI_Transform(out.shape, scale, true).Shape();
  }
  return out;
}

std::string megabytes(std::uintmax_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f MB", static_cast<double>(bytes) / 1e6);
  return text;
}

}  // namespace

void silence_occt_messages() {
  static std::once_flag once;
  std::call_once(once, [] {
    Message::DefaultMessenger()->RemovePrinters(STANDARD_TYPE(Message_PrinterOStream));
  });
}

std::string occt_failure_text() {
  try {
    throw;
  } catch (const Standard_Failure& e) {
    const char* text = e.GetMessageString();
    return std::string(e.DynamicType()->Name()) + (text && *text ? std::string(": ") + text : "");
  } catch (const std::exception& e) {
    return e.what();
  }
}

CadShape read_cad_shape(const fs::path& file, double timeout_seconds) {
  const CadFormat format = require_cad_format(file);
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) throw ConfigError(file.string() + ": no such file");
  if (!std::ifstream(file)) throw ConfigError(file.string() + ": cannot be opened for reading");
  silence_occt_messages();
  const char* format_name = format == CadFormat::step ? "STEP" : "IGES";
  const auto read = [&] {
    try {
      return format == CadFormat::step ? read_step_shape(file) : read_iges_shape(file);
    } catch (const ConfigError&) {
      throw;
    } catch (...) {
      throw ConfigError(file.string() + ": OCCT could not read it (" + occt_failure_text() + ")");
    }
  };
  // OCCT's parsers are not memory-safe on damaged files (a truncated IGES
  // B-spline entity crashes 7.6's IGES reader): the file is read in a forked
  // child (io/isolated_read.hpp), which hands the shape over as an exact
  // binary BRep file (BinTools: doubles as bytes) and the header's unit and
  // writer as a text file beside it. The child's own ConfigErrors come back
  // marked as such.
  static constexpr std::string_view kOwnError = "cnclab-cad-error: ";
  static std::atomic<unsigned> handover_count{0};
  const fs::path handover =
      fs::temp_directory_path() / ("cnclab_cad_" + std::to_string(::getpid()) + "_" +
                                   std::to_string(handover_count++) + ".brep");
  const fs::path handover_header = handover.string() + ".header";
  const auto remove_handover = [&] {
    fs::remove(handover, ec);
    fs::remove(handover_header, ec);
  };
  try {
    probe_in_child(
        file,
        [&] {
          try {
            const ReadShape shape = read();
            std::ofstream header(handover_header);
            header << shape.unit << '\n' << shape.writer << '\n';
            if (!header || !BinTools::Write(shape.shape, handover.c_str())) {
              throw ConfigError(file.string() + ": cannot hand the shape over (" +
                                handover.string() + ")");
            }
          } catch (const ConfigError& e) {
            throw IoError(std::string(kOwnError) + e.what());
          }
        },
        timeout_seconds);
  } catch (const ProbeTimedOut&) {
    remove_handover();
    char seconds[32];
    std::snprintf(seconds, sizeof seconds, "%g", timeout_seconds);
    throw ConfigError(file.string() + ": timed out after " + seconds + " s reading it (OCCT's " +
                      format_name + " reader, " + megabytes(fs::file_size(file, ec)) +
                      "); allow longer with read_timeout (seconds) in the dataset's surface: "
                      "{file, face, read_timeout}, or --read-timeout of `cnclab surface`");
  } catch (const IoError& e) {
    remove_handover();
    const std::string message = e.what();
    if (message.starts_with(kOwnError)) throw ConfigError(message.substr(kOwnError.size()));
    throw ConfigError(file.string() + ": not a readable " + format_name +
                      " file: OCCT's reader crashed on it (truncated or damaged?)");
  }
  CadShape out;
  const bool handed_over = BinTools::Read(out.shape, handover.c_str());
  std::ifstream header(handover_header);
  std::getline(header, out.unit);
  std::getline(header, out.writer);
  remove_handover();
  if (!handed_over) throw ConfigError(file.string() + ": the shape read could not be handed over");
  if (out.shape.IsNull()) throw ConfigError(file.string() + ": holds no shape");
  TopTools_IndexedMapOfShape map;
  TopExp::MapShapes(out.shape, TopAbs_FACE, map);
  for (int i = 1; i <= map.Extent(); ++i) out.faces.push_back(TopoDS::Face(map(i)));
  if (out.faces.empty()) {
    throw ConfigError(file.string() + ": holds no face (only points, curves or wires)");
  }
  return out;
}

std::string cad_shape_text(const TopoDS_Shape& shape, CadFormat format) {
  silence_occt_messages();
  std::ostringstream text;
  if (format == CadFormat::step) {
    STEPControl_Writer writer;
    if (writer.Transfer(shape, STEPControl_AsIs) != IFSelect_RetDone) {
      throw Error("STEP writer: the shape could not be translated");
    }
    APIHeaderSection_MakeHeader(writer.Model())
        .SetTimeStamp(new TCollection_HAsciiString(kStepTimeStamp));
    StepData_StepWriter out(writer.Model());
    out.FloatWriter().SetFormat(kOcctRealFormat);
    out.SendModel(StepAP214::Protocol());
    if (!out.Print(text)) throw Error("STEP writer: printing the model failed");
  } else {
    IGESControl_Writer writer("MM", 0);  // 0: faces as trimmed surfaces (144), widely read
    if (!writer.AddShape(shape)) throw Error("IGES writer: the shape could not be translated");
    writer.ComputeModel();
    IGESData_GlobalSection header = writer.Model()->GlobalSection();
    header.SetDate(new TCollection_HAsciiString(kIgesDate));
    header.SetLastChangeDate(new TCollection_HAsciiString(kIgesDate));
    header.SetAuthorName(new TCollection_HAsciiString("cnclab"));  // not the user name
    writer.Model()->SetGlobalSection(header);
    IGESData_IGESWriter out(writer.Model());
    out.FloatWriter().SetFormat(kOcctRealFormat);
    out.SendModel(IGESSelect_WorkLibrary::DefineProtocol());
    if (!out.Print(text)) throw Error("IGES writer: printing the model failed");
  }
  return text.str();
}

}  // namespace cnclab::occt
