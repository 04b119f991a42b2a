// Format dispatch for read_mesh() and write_mesh(): the extension picks the format,
// io/*.cpp parse and write, validate_mesh() checks every mesh read.
#include "core/io/mesh_io.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <system_error>
#include <utility>

#include "core/io/file_access.h"
#include "core/io/mesh_formats.h"

namespace tetlod {
namespace {

constexpr const char* kSupportedExtensions =
    ".mesh, .meshb, .msh, .node/.ele, .vtk, .vtu, .bdf/.nas, .inp";

enum class FileKind { kMedit, kGmsh, kTetGen, kVtkLegacy, kVtu, kNastran, kAbaqus, kMeditBinary };

// The extension of the file name in `path`, lower case, without the dot.
std::string extension_of(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  const size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string extension = path.substr(dot + 1);
  for (char& c : extension) {
    if (c >= 'A' && c <= 'Z') c = char(c - 'A' + 'a');
  }
  return extension;
}

Status file_kind(const std::string& path, FileKind* kind) {
  const std::string extension = extension_of(path);
  if (extension == "mesh") {
    *kind = FileKind::kMedit;
  } else if (extension == "msh") {
    *kind = FileKind::kGmsh;
  } else if (extension == "node" || extension == "ele") {
    *kind = FileKind::kTetGen;
  } else if (extension == "vtk") {
    *kind = FileKind::kVtkLegacy;
  } else if (extension == "vtu") {
    *kind = FileKind::kVtu;
  } else if (extension == "bdf" || extension == "nas") {
    *kind = FileKind::kNastran;
  } else if (extension == "inp") {
    *kind = FileKind::kAbaqus;
  } else if (extension == "meshb") {
    *kind = FileKind::kMeditBinary;
  } else {
    return Status::error(path + ": unknown mesh file extension '" +
                         (extension.empty() ? std::string() : "." + extension) +
                         "' (supported: " + kSupportedExtensions + ")");
  }
  return Status();
}

// "foo.ele" or "foo.node" -> "foo".
std::string tetgen_base(const std::string& path) {
  return path.substr(0, path.find_last_of('.'));
}

Status finish_read(io::ParsedMesh* parsed, MeshFormat format, const std::string& source,
                   TetMesh* mesh, ReadInfo* info) {
  ValidationReport report;
  std::vector<uint32_t> neighbors;
  Status status = validate_mesh(&parsed->mesh, source, parsed->tet_lines, &report,
                                info && info->keep_face_neighbors ? &neighbors : nullptr);
  if (!status.ok()) return status;
  *mesh = std::move(parsed->mesh);
  if (info) {
    info->format = format;
    info->validation = report;
    info->notes = std::move(parsed->notes);
    info->surface_groups = std::move(parsed->surface_groups);
    info->material_names = std::move(parsed->material_names);
    // A file's names reach terminals, JSON and other files: bytes that are no UTF-8
    // become '?' (valid_utf8()), control characters (an escape sequence, a line break)
    // '_', and a name is cut to kMaxNameBytes, at a character's start (what Gmsh
    // reads of a physical name).
    size_t cut = 0;
    const auto clean = [&cut](std::string* name) {
      *name = io::valid_utf8(*name);
      for (char& c : *name)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '_';
      if (name->size() > kMaxNameBytes) {
        size_t end = kMaxNameBytes;
        while (end > 0 && (static_cast<unsigned char>((*name)[end]) & 0xc0) == 0x80) --end;
        name->resize(end);
        ++cut;
      }
    };
    for (MaterialName& n : info->material_names) clean(&n.name);
    for (InputSurfaceGroup& g : info->surface_groups) clean(&g.name);
    if (cut > 0) {
      info->notes.push_back(std::to_string(cut) + (cut == 1 ? " name was" : " names were") +
                            " cut to " + std::to_string(kMaxNameBytes) +
                            " bytes (what Gmsh reads of a physical name)");
    }
    info->surface_elements_not_kept = parsed->surface_elements_not_kept;
    info->face_neighbors = std::move(neighbors);
  }
  return Status();
}

// The checks a writer relies on, so that a bad mesh is an error, not a crash.
Status check_writable(const std::string& path, const TetMesh& mesh) {
  if (mesh.materials.size() != mesh.tets.size()) {
    return Status::error(path + ": cannot write a mesh with " + std::to_string(mesh.tet_count()) +
                         " tetrahedra and " + std::to_string(mesh.materials.size()) +
                         " material ids");
  }
  if (mesh.tets.empty()) return Status::error(path + ": cannot write a mesh without tetrahedra");
  if (mesh.vertex_count() >= kInvalidIndex) return Status::error(path + ": too many vertices");
  for (size_t t = 0; t < mesh.tet_count(); ++t) {
    for (uint32_t v : mesh.tets[t]) {
      if (v >= mesh.vertex_count()) {
        return Status::error(path + ": cannot write: tetrahedron " + std::to_string(t + 1) +
                             " uses a vertex out of range");
      }
    }
    if (mesh.materials[t] < 0) {
      return Status::error(path + ": cannot write: tetrahedron " + std::to_string(t + 1) +
                           " has the negative material id " + std::to_string(mesh.materials[t]));
    }
  }
  return Status();
}

}  // namespace

const char* format_name(MeshFormat format) {
  switch (format) {
    case MeshFormat::kMedit:
      return "Medit .mesh";
    case MeshFormat::kGmsh22:
      return "Gmsh 2.2 .msh";
    case MeshFormat::kGmsh41:
      return "Gmsh 4.1 .msh";
    case MeshFormat::kTetGen:
      return "TetGen .node/.ele";
    case MeshFormat::kVtkLegacy:
      return "VTK legacy .vtk";
    case MeshFormat::kVtu:
      return "VTK XML .vtu";
    case MeshFormat::kNastran:
      return "Nastran bulk data .bdf/.nas";
    case MeshFormat::kAbaqus:
      return "Abaqus input .inp";
    case MeshFormat::kMeditBinary:
      return "Medit binary .meshb";
  }
  return "unknown format";
}

Status read_mesh_from_memory(std::string_view data, MeshFormat format, const std::string& name,
                             TetMesh* mesh, ReadInfo* info) {
  io::ParsedMesh parsed;
  Status status;
  switch (format) {
    case MeshFormat::kMedit:
      status = io::parse_medit(data, name, &parsed);
      break;
    case MeshFormat::kGmsh22:
    case MeshFormat::kGmsh41: {
      int version = 0;
      status = io::parse_gmsh(data, name, &parsed, &version);
      format = version == 22 ? MeshFormat::kGmsh22 : MeshFormat::kGmsh41;
      break;
    }
    case MeshFormat::kTetGen:
      return Status::error(name + ": a TetGen mesh is two texts; use read_tetgen_from_memory()");
    case MeshFormat::kVtkLegacy:
      status = io::parse_vtk_legacy(data, name, &parsed);
      break;
    case MeshFormat::kVtu:
      status = io::parse_vtu(data, name, &parsed);
      break;
    case MeshFormat::kNastran:
      status = io::parse_nastran(data, name, &parsed);
      break;
    case MeshFormat::kAbaqus:
      status = io::parse_abaqus(data, name, &parsed);
      break;
    case MeshFormat::kMeditBinary:
      status = io::parse_medit_binary(data, name, &parsed);
      break;
  }
  if (!status.ok()) return status;
  return finish_read(&parsed, format, name, mesh, info);
}

Status read_tetgen_from_memory(std::string_view node_data, std::string_view ele_data,
                               const std::string& node_name, const std::string& ele_name,
                               TetMesh* mesh, ReadInfo* info) {
  io::ParsedMesh parsed;
  Status status = io::parse_tetgen(node_data, node_name, ele_data, ele_name, &parsed);
  if (!status.ok()) return status;
  return finish_read(&parsed, MeshFormat::kTetGen, ele_name, mesh, info);
}

Status read_tetgen_from_memory(std::string_view node_data, std::string_view ele_data,
                               std::string_view face_data, const std::string& node_name,
                               const std::string& ele_name, const std::string& face_name,
                               TetMesh* mesh, ReadInfo* info) {
  io::ParsedMesh parsed;
  Status status =
      io::parse_tetgen(node_data, node_name, ele_data, ele_name, &parsed, face_data, &face_name);
  if (!status.ok()) return status;
  return finish_read(&parsed, MeshFormat::kTetGen, ele_name, mesh, info);
}

Status read_mesh(const std::string& path, TetMesh* mesh, ReadInfo* info) {
  // (A directory first: without an extension it was "unknown mesh file extension ''".)
  std::error_code not_a_directory;
  if (std::filesystem::is_directory(path, not_a_directory))
    return Status::error(path + ": cannot read: it is a directory");
  FileKind kind;
  Status status = file_kind(path, &kind);
  if (!status.ok()) return status;
  if (kind == FileKind::kTetGen) {
    const std::string base = tetgen_base(path);
    std::string node_text, ele_text;
    if (!(status = io::read_file(base + ".node", &node_text)).ok()) return status;
    if (!(status = io::read_file(base + ".ele", &ele_text)).ok()) return status;
    // The .face file beside them, if any, for its surface groups.
    std::error_code error;
    if (!std::filesystem::exists(base + ".face", error))
      return read_tetgen_from_memory(node_text, ele_text, base + ".node", base + ".ele", mesh,
                                     info);
    std::string face_text;
    if (!(status = io::read_file(base + ".face", &face_text)).ok()) return status;
    return read_tetgen_from_memory(node_text, ele_text, face_text, base + ".node", base + ".ele",
                                   base + ".face", mesh, info);
  }
  std::string text;
  if (!(status = io::read_file(path, &text)).ok()) return status;
  static constexpr MeshFormat kFormats[] = {
      MeshFormat::kMedit, MeshFormat::kGmsh41,  MeshFormat::kTetGen, MeshFormat::kVtkLegacy,
      MeshFormat::kVtu,   MeshFormat::kNastran, MeshFormat::kAbaqus, MeshFormat::kMeditBinary};
  return read_mesh_from_memory(text, kFormats[int(kind)], path, mesh, info);
}

Status check_mesh_path(const std::string& path, const WriteOptions& options) {
  FileKind kind;
  Status status = file_kind(path, &kind);
  if (!status.ok()) return status;
  if (kind == FileKind::kGmsh && options.gmsh_version != 22 && options.gmsh_version != 41) {
    return Status::error(path + ": unsupported Gmsh version " +
                         std::to_string(options.gmsh_version) + " (use 22 or 41)");
  }
  return Status();
}

Status stage_mesh(OutputFiles* files, const std::string& path, const TetMesh& mesh,
                  const WriteOptions& options) {
  FileKind kind;
  Status status = file_kind(path, &kind);
  if (status.ok()) status = check_mesh_path(path, options);
  if (!status.ok()) return status;
  if (!(status = check_writable(path, mesh)).ok()) return status;
  SurfaceGroups computed;
  const SurfaceGroups* surfaces = nullptr;
  if (options.surface_groups) {
    if (!options.groups && !(status = group_surface(mesh, &computed)).ok())
      return Status::error(path + ": " + status.message());
    surfaces = options.groups ? options.groups : &computed;
  }
  std::string text;
  switch (kind) {
    case FileKind::kMedit:
      io::write_medit(mesh, surfaces, &text);
      break;
    case FileKind::kGmsh:
      io::write_gmsh(mesh, options.gmsh_version, options.gmsh_binary, surfaces,
                     options.material_names, &text);
      break;
    case FileKind::kTetGen: {
      const std::string base = tetgen_base(path);
      io::write_tetgen_node(mesh, &text);
      if (!(status = files->stage(base + ".node", text)).ok()) return status;
      text.clear();
      io::write_tetgen_ele(mesh, &text);
      if (!(status = files->stage(base + ".ele", text)).ok()) return status;
      text.clear();
      // A .face beside the pair is read with it: one from an earlier write is
      // replaced by this mesh's faces, without markers when no groups are asked for.
      std::error_code error;
      if (surfaces) {
        io::write_tetgen_face(*surfaces, &text);
      } else if (std::filesystem::exists(base + ".face", error)) {
        if (!group_surface(mesh, &computed).ok()) computed = {};  // ids past the tag range
        io::write_tetgen_face(computed, &text, false);
      } else {
        return Status();
      }
      return files->stage(base + ".face", text);
    }
    case FileKind::kVtkLegacy:
      io::write_vtk_legacy(mesh, surfaces, options.material_names, options.vtk_binary, &text);
      break;
    case FileKind::kVtu:
      io::write_vtu(mesh, surfaces, options.material_names, options.vtk_binary, &text);
      break;
    case FileKind::kNastran:
      io::write_nastran(mesh, surfaces, options.material_names, &text);
      break;
    case FileKind::kAbaqus:
      io::write_abaqus(mesh, surfaces, options.material_names, &text);
      break;
    case FileKind::kMeditBinary:
      io::write_medit_binary(mesh, surfaces, &text);
      break;
  }
  return files->stage(path, text);
}

std::vector<std::string> mesh_output_files(const std::string& path) {
  FileKind kind;
  if (!file_kind(path, &kind).ok() || kind != FileKind::kTetGen) return {path};
  const std::string base = tetgen_base(path);
  return {base + ".node", base + ".ele", base + ".face"};
}

Status write_mesh(const std::string& path, const TetMesh& mesh, const WriteOptions& options) {
  OutputFiles files;
  if (Status status = stage_mesh(&files, path, mesh, options); !status) return status;
  return files.commit();
}

Status write_vtu_with_fields(const std::string& path, const TetMesh& mesh, const MeshFields& fields,
                             bool binary) {
  if (Status status = check_writable(path, mesh); !status) return status;
  auto check = [&](const std::vector<ScalarArray>& arrays, size_t count, const char* kind) {
    for (const ScalarArray& array : arrays) {
      const bool name_ok =
          !array.name.empty() && std::all_of(array.name.begin(), array.name.end(), [](char c) {
            return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == ' ' ||
                   c == '|' || c == '-';
          });
      if (!name_ok) {
        return Status::error(path + ": " + kind + " array name \"" + array.name +
                             "\" is empty or has characters other than letters, digits, "
                             "'_', ' ', '|', '-'");
      }
      if (!array.values || array.values->size() != count) {
        return Status::error(path + ": " + kind + " array \"" + array.name + "\" has " +
                             std::to_string(array.values ? array.values->size() : 0) +
                             " values for " + std::to_string(count) + " " + kind + "s");
      }
      for (size_t i = 0; i < count; ++i) {
        if (!std::isfinite((*array.values)[i])) {
          return Status::error(path + ": " + kind + " array \"" + array.name + "\" value " +
                               std::to_string(i) + " is not finite");
        }
      }
    }
    return Status();
  };
  if (Status s = check(fields.point_data, mesh.vertex_count(), "point"); !s) return s;
  if (Status s = check(fields.cell_data, mesh.tet_count(), "cell"); !s) return s;
  std::string text;
  io::write_vtu(mesh, fields, binary, &text);
  return write_file_atomically(path, text);
}

}  // namespace tetlod
