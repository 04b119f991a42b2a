// Small helpers shared by the subcommands: option parsing and mesh loading that
// reports errors on stderr.
#pragma once

#include <cstdio>
#include <optional>
#include <string>

#include "app/commands.h"
#include "core/io/mesh_io.h"
#include "core/mesh_stats.h"

namespace tetlod::app {

// True if `args` holds -h or --help.
bool wants_help(const Args& args);

// Parses a finite double / a whole number; nullopt if `text` is not one entirely.
std::optional<double> parse_double(const std::string& text);
std::optional<long long> parse_integer(const std::string& text);

// Reads a mesh; on failure prints "tetlod: <message>" to stderr and returns false.
// Notes about repairs (reoriented tets, dropped vertices) go to stderr too.
bool load_mesh(const std::string& path, TetMesh* mesh, ReadInfo* info);

// Prints the Table I rows (whole mesh, then each material) as an aligned table.
void print_property_table(const MeshStats& stats);

// Escapes a string for a JSON string literal (without the quotes).
std::string json_escape(const std::string& text);

}  // namespace tetlod::app
