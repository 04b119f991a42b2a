// The one place TetLOD calls TetGen 1.5 (H. Si, "TetGen, a Delaunay-based quality
// tetrahedral mesh generator", ACM TOMS 41(2), 2015).
//
// Why TetGen runs in a child process: built with TETLIBRARY, TetGen 1.5.0 reports a
// failure by throwing an int from terminatetetgen() (tetgen.h), but that function
// first calls tetgenmesh::freememory(), and the tetgenmesh local to tetrahedralize()
// frees the same pools again in its destructor while the exception unwinds: the
// process crashes before any catch is reached. TetGen also prints its diagnostics to
// stdout. So tetrahedralize_plc() forks; the child runs TetGen with stdout and stderr
// redirected into a pipe and sends the mesh back through a second pipe. A crash, an
// exit() or a throw in the child becomes an error Status carrying TetGen's own words,
// and core/ never prints. Costs: a fork (copy-on-write) and one copy of the result.
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <stdio_ext.h>
#include <sys/wait.h>
#include <tetgen.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <new>
#include <string>

#include "core/generate/plc.h"
#include "core/validate.h"

namespace tetlod {
namespace {

// What the child sends first; the arrays follow (points, tets, one attribute per tet).
struct ChildHeader {
  int32_t code = -1;  // 0 ok, else TetGen's terminatetetgen() code or a kChild* code
  int32_t corners = 0;
  int32_t attributes = 0;
  int32_t first_number = 0;
  int64_t point_count = 0;
  int64_t tet_count = 0;
};
constexpr int32_t kChildUnexpectedException = 100;

struct TetgenOutput {
  std::vector<double> points;      // 3 per point
  std::vector<int32_t> tets;       // 4 per tet, 0-based
  std::vector<double> attributes;  // first region attribute, 1 per tet
};

const char* tetgen_error_text(int code) {
  switch (code) {
    case 1:
      return "out of memory";
    case 2:
      return "internal error";
    case 3:
      return "the input surfaces intersect themselves";
    case 4:
      return "an input feature is smaller than TetGen's tolerance";
    case 5:
      return "two input facets intersect";
    case 10:
      return "the input is invalid";
    case kChildUnexpectedException:
      return "unexpected exception";
    default:
      return "unknown error";
  }
}

// Copies `plc` into TetGen's input structure (0-based; tetgenio frees the arrays).
void fill_tetgen_input(const Plc& plc, tetgenio* in) {
  in->firstnumber = 0;
  in->numberofpoints = static_cast<int>(plc.points.size());
  in->pointlist = new REAL[3 * plc.points.size()];
  for (size_t i = 0; i < plc.points.size(); ++i) {
    in->pointlist[3 * i + 0] = plc.points[i].x;
    in->pointlist[3 * i + 1] = plc.points[i].y;
    in->pointlist[3 * i + 2] = plc.points[i].z;
  }

  const size_t facet_count = plc.facet_count();
  in->numberoffacets = static_cast<int>(facet_count);
  in->facetlist = new tetgenio::facet[facet_count];
  in->facetmarkerlist = new int[facet_count];
  for (size_t f = 0; f < facet_count; ++f) {
    tetgenio::facet& facet = in->facetlist[f];
    tetgenio::init(&facet);
    const uint32_t first = plc.facet_first_polygon[f];
    const uint32_t end = plc.facet_first_polygon[f + 1];
    facet.numberofpolygons = static_cast<int>(end - first);
    facet.polygonlist = new tetgenio::polygon[end - first];
    for (uint32_t p = first; p < end; ++p) {
      tetgenio::polygon& polygon = facet.polygonlist[p - first];
      const uint32_t v_first = plc.polygon_first_vertex[p];
      const uint32_t v_end = plc.polygon_first_vertex[p + 1];
      polygon.numberofvertices = static_cast<int>(v_end - v_first);
      polygon.vertexlist = new int[v_end - v_first];
      for (uint32_t v = v_first; v < v_end; ++v) {
        polygon.vertexlist[v - v_first] = static_cast<int>(plc.polygon_vertices[v]);
      }
    }
    in->facetmarkerlist[f] = plc.facet_markers[f];
  }

  in->numberofregions = static_cast<int>(plc.regions.size());
  in->regionlist = new REAL[5 * plc.regions.size()];
  for (size_t r = 0; r < plc.regions.size(); ++r) {
    in->regionlist[5 * r + 0] = plc.regions[r].seed.x;
    in->regionlist[5 * r + 1] = plc.regions[r].seed.y;
    in->regionlist[5 * r + 2] = plc.regions[r].seed.z;
    in->regionlist[5 * r + 3] = plc.regions[r].material;
    in->regionlist[5 * r + 4] = plc.regions[r].max_volume;  // -1: no per-region bound
  }
}

bool write_all(int fd, const void* data, size_t size) {
  const char* bytes = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t n = write(fd, bytes, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    bytes += n;
    size -= static_cast<size_t>(n);
  }
  return true;
}

// The child: runs TetGen, sends the header and arrays to `data_fd`, never returns.
[[noreturn]] void run_child(const Plc& plc, tetgenbehavior behavior, int data_fd, int message_fd) {
  // Drop output the parent had buffered, then send everything TetGen prints to the parent.
  __fpurge(stdout);
  __fpurge(stderr);
  dup2(message_fd, STDOUT_FILENO);
  dup2(message_fd, STDERR_FILENO);
  setvbuf(stdout, nullptr, _IONBF, 0);

  ChildHeader header;
  tetgenio in;
  tetgenio out;
  try {
    fill_tetgen_input(plc, &in);
    tetrahedralize(&behavior, &in, &out);
    header.code = 0;
  } catch (int code) {
    header.code = code;
  } catch (const std::bad_alloc&) {
    header.code = 1;
  } catch (...) {
    header.code = kChildUnexpectedException;
  }
  if (header.code == 0) {
    header.corners = out.numberofcorners;
    header.attributes = out.numberoftetrahedronattributes;
    header.first_number = out.firstnumber;
    header.point_count = out.numberofpoints;
    header.tet_count = out.numberoftetrahedra;
  }
  bool ok = write_all(data_fd, &header, sizeof(header));
  if (ok && header.code == 0 && header.corners == 4 && header.attributes >= 1) {
    const size_t points = static_cast<size_t>(header.point_count);
    const size_t tets = static_cast<size_t>(header.tet_count);
    std::vector<double> attributes(tets);
    for (size_t t = 0; t < tets; ++t) {
      attributes[t] = out.tetrahedronattributelist[static_cast<size_t>(header.attributes) * t];
    }
    ok = write_all(data_fd, out.pointlist, 3 * points * sizeof(double)) &&
         write_all(data_fd, out.tetrahedronlist, 4 * tets * sizeof(int)) &&
         write_all(data_fd, attributes.data(), tets * sizeof(double));
  }
  _exit(ok ? 0 : 3);
}

// Reads both pipes to their ends (so that neither side can block the other).
void drain(int data_fd, int message_fd, std::vector<char>* data, std::string* message) {
  char buffer[1 << 16];
  pollfd fds[2] = {{data_fd, POLLIN, 0}, {message_fd, POLLIN, 0}};
  int open_count = 2;
  while (open_count > 0) {
    if (poll(fds, 2, -1) < 0) {
      if (errno == EINTR) continue;
      break;
    }
    for (int i = 0; i < 2; ++i) {
      if (fds[i].fd < 0 || fds[i].revents == 0) continue;
      const ssize_t n = read(fds[i].fd, buffer, sizeof(buffer));
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        fds[i].fd = -1;
        --open_count;
        continue;
      }
      if (i == 0) {
        data->insert(data->end(), buffer, buffer + n);
      } else if (message->size() < 4096) {
        message->append(buffer, static_cast<size_t>(n));
      }
    }
  }
}

// TetGen's own words, on one line, for an error message.
std::string tetgen_says(std::string message) {
  std::replace(message.begin(), message.end(), '\n', ' ');
  message.erase(std::unique(message.begin(), message.end(),
                            [](char a, char b) { return a == ' ' && b == ' '; }),
                message.end());
  while (!message.empty() && message.back() == ' ') message.pop_back();
  while (!message.empty() && message.front() == ' ') message.erase(message.begin());
  return message.empty() ? std::string() : " (TetGen says: " + message + ")";
}

Status run_tetgen_isolated(const Plc& plc, const tetgenbehavior& behavior, TetgenOutput* out) {
  int data_pipe[2];
  int message_pipe[2];
  if (pipe2(data_pipe, O_CLOEXEC) != 0) {
    return Status::error(std::string("TetGen: cannot create a pipe: ") + std::strerror(errno));
  }
  if (pipe2(message_pipe, O_CLOEXEC) != 0) {
    const int error = errno;
    close(data_pipe[0]);
    close(data_pipe[1]);
    return Status::error(std::string("TetGen: cannot create a pipe: ") + std::strerror(error));
  }
  const pid_t pid = fork();
  if (pid < 0) {
    const int error = errno;
    for (int fd : {data_pipe[0], data_pipe[1], message_pipe[0], message_pipe[1]}) close(fd);
    return Status::error(std::string("TetGen: cannot start a process: ") + std::strerror(error));
  }
  if (pid == 0) {
    close(data_pipe[0]);
    close(message_pipe[0]);
    run_child(plc, behavior, data_pipe[1], message_pipe[1]);
  }
  close(data_pipe[1]);
  close(message_pipe[1]);
  std::vector<char> data;
  std::string message;
  drain(data_pipe[0], message_pipe[0], &data, &message);
  close(data_pipe[0]);
  close(message_pipe[0]);
  int wait_status = 0;
  while (waitpid(pid, &wait_status, 0) < 0 && errno == EINTR) {
  }

  ChildHeader header;
  const bool have_header = data.size() >= sizeof(header);
  if (have_header) std::memcpy(&header, data.data(), sizeof(header));
  if (WIFSIGNALED(wait_status)) {
    // TetGen 1.5.0 crashes while unwinding from its own error (see the top of the file),
    // or stops on one of its assertions.
    const int signal = WTERMSIG(wait_status);
    const char* what = signal == SIGKILL ? "was killed (out of memory?)"
                                         : "rejected the input or hit an internal error";
    return Status::error(std::string("TetGen failed: it ") + what + " (signal " +
                         std::to_string(signal) + ")" + tetgen_says(message));
  }
  if (!have_header) {
    return Status::error("TetGen exited without a result" + tetgen_says(message));
  }
  if (header.code != 0) {
    return Status::error("TetGen failed (code " + std::to_string(header.code) +
                         "): " + tetgen_error_text(header.code) + tetgen_says(message));
  }
  if (header.corners != 4 || header.attributes < 1 || header.first_number != 0 ||
      header.point_count <= 0 || header.tet_count <= 0 || header.point_count > (int64_t{1} << 31) ||
      header.tet_count > (int64_t{1} << 31)) {
    return Status::error("TetGen returned no usable tetrahedra" + tetgen_says(message));
  }
  const size_t points = static_cast<size_t>(header.point_count);
  const size_t tets = static_cast<size_t>(header.tet_count);
  const size_t expected = sizeof(header) + 3 * points * sizeof(double) +
                          4 * tets * sizeof(int32_t) + tets * sizeof(double);
  if (data.size() != expected || !WIFEXITED(wait_status) || WEXITSTATUS(wait_status) != 0) {
    return Status::error("TetGen's result was cut short" + tetgen_says(message));
  }
  const char* cursor = data.data() + sizeof(header);
  out->points.resize(3 * points);
  std::memcpy(out->points.data(), cursor, 3 * points * sizeof(double));
  cursor += 3 * points * sizeof(double);
  out->tets.resize(4 * tets);
  std::memcpy(out->tets.data(), cursor, 4 * tets * sizeof(int32_t));
  cursor += 4 * tets * sizeof(int32_t);
  out->attributes.resize(tets);
  std::memcpy(out->attributes.data(), cursor, tets * sizeof(double));
  return Status();
}

// Formats a double so that TetGen's switch parser (atof) reads back the same value.
std::string switch_number(double value) {
  char text[64];
  std::snprintf(text, sizeof(text), "%.17g", value);
  return text;
}

Status check_plc(const Plc& plc) {
  if (plc.points.empty() || plc.facet_count() == 0) return Status::error("the PLC is empty");
  if (plc.regions.empty()) return Status::error("the PLC has no region seeds");
  const size_t limit = static_cast<size_t>(1) << 30;
  if (plc.points.size() > limit || plc.polygon_vertices.size() > limit) {
    return Status::error("the PLC is too large for TetGen");
  }
  for (uint32_t v : plc.polygon_vertices) {
    if (v >= plc.points.size()) return Status::error("a PLC polygon uses a missing point");
  }
  for (const Vec3& p : plc.points) {
    if (!is_finite(p)) return Status::error("a PLC point has a non-finite coordinate");
  }
  for (const PlcRegion& r : plc.regions) {
    if (!is_finite(r.seed) || std::isnan(r.max_volume) || std::isinf(r.max_volume)) {
      return Status::error("a PLC region seed or volume bound is not finite");
    }
  }
  return Status();
}

}  // namespace

Status tetrahedralize_plc(const Plc& plc, const TetgenParams& params, TetMesh* mesh) {
  if (!(params.max_volume > 0) || !std::isfinite(params.max_volume)) {
    return Status::error("TetGen: the maximum tet volume must be a positive number, not " +
                         switch_number(params.max_volume));
  }
  if (!(params.quality >= 1.2) || !std::isfinite(params.quality)) {
    return Status::error("TetGen: the radius-edge ratio bound must be >= 1.2, not " +
                         switch_number(params.quality));
  }
  if (Status s = check_plc(plc); !s) return s;

  // p: PLC, z: 0-based, q: quality, a: volume bound, A: region attributes, Q: quiet.
  std::string switches =
      "pzq" + switch_number(params.quality) + "a" + switch_number(params.max_volume) + "AQ";
  // A bare `a` makes TetGen apply the regions' own volume bounds too.
  const bool regional = std::any_of(plc.regions.begin(), plc.regions.end(),
                                    [](const PlcRegion& r) { return r.max_volume > 0; });
  if (regional) switches += "a";
  tetgenbehavior behavior;
  if (!behavior.parse_commandline(switches.data()) || behavior.maxvolume != params.max_volume ||
      behavior.minratio != params.quality || !behavior.plc || !behavior.regionattrib ||
      (regional && !behavior.varvolume)) {
    return Status::error("TetGen: cannot pass the switches '" + switches + "'");
  }

  TetgenOutput out;
  if (Status s = run_tetgen_isolated(plc, behavior, &out); !s) return s;

  std::vector<int32_t> seeded;
  for (const PlcRegion& region : plc.regions) seeded.push_back(region.material);
  std::sort(seeded.begin(), seeded.end());

  const size_t vertex_count = out.points.size() / 3;
  const size_t tet_count = out.attributes.size();
  mesh->positions.resize(vertex_count);
  for (size_t i = 0; i < vertex_count; ++i) {
    mesh->positions[i] = {out.points[3 * i], out.points[3 * i + 1], out.points[3 * i + 2]};
  }
  mesh->tets.resize(tet_count);
  mesh->materials.resize(tet_count);
  for (size_t t = 0; t < tet_count; ++t) {
    const int32_t* corners = out.tets.data() + 4 * t;
    for (int k = 0; k < 4; ++k) {
      if (corners[k] < 0 || static_cast<size_t>(corners[k]) >= vertex_count) {
        return Status::error("TetGen output: a tet uses a missing point");
      }
    }
    // TetGen's corner order already has signed_volume6 > 0 (validate_mesh checks it).
    mesh->tets[t] = {static_cast<uint32_t>(corners[0]), static_cast<uint32_t>(corners[1]),
                     static_cast<uint32_t>(corners[2]), static_cast<uint32_t>(corners[3])};
    const double attribute = out.attributes[t];
    const int32_t material = static_cast<int32_t>(std::lround(attribute));
    // TetGen numbers an unseeded region above the largest seeded attribute.
    if (static_cast<double>(material) != attribute ||
        !std::binary_search(seeded.begin(), seeded.end(), material)) {
      return Status::error("TetGen: a region of the PLC has no seed (tet attribute " +
                           switch_number(attribute) + ")");
    }
    mesh->materials[t] = material;
  }

  ValidationReport report;
  if (Status s = validate_mesh(mesh, "TetGen output", {}, &report); !s) return s;
  if (report.reoriented_tets != 0 || report.removed_unused_vertices != 0) {
    return Status::error("TetGen output: " + std::to_string(report.reoriented_tets) +
                         " tets had the wrong orientation and " +
                         std::to_string(report.removed_unused_vertices) + " vertices were unused");
  }
  return Status();
}

}  // namespace tetlod
